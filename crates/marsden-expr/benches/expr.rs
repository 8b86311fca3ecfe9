//! Expression evaluation against the same Lagrangian written in Rust, at `f64` and at the
//! hyper-dual numbers the integrators use for second derivatives.
//!
//! Run with `cargo bench -p marsden-expr --bench expr`.

use divan::{Bencher, black_box};
use marsden::Scalar;
use marsden_expr::{Program, Symbols};
use num_dual::HyperDualSVec64;

fn main() {
    divan::main();
}

/// Pendulum parameters, read at run time as physics code would.
struct Params {
    m: f64,
    l: f64,
    g: f64,
}

const PARAMS: Params = Params {
    m: 1.3,
    l: 0.7,
    g: 9.81,
};

#[inline(never)]
fn pendulum_rust<S: Scalar>(p: &Params, x: &[S]) -> S {
    let (theta, theta_dot) = (x[0], x[1]);
    theta_dot.powi(2) * (0.5 * p.m * p.l.powi(2)) + theta.cos() * (p.m * p.g * p.l)
}

fn pendulum_program() -> Program {
    let mut symbols = Symbols::with_inputs(["theta", "theta_dot"]).unwrap_or_default();
    for (name, value) in [("m", PARAMS.m), ("l", PARAMS.l), ("g", PARAMS.g)] {
        let _ = symbols.add_constant(name, value);
    }
    Program::compile("0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)", &symbols)
        .unwrap_or_else(|e| panic!("{e}"))
}

const DOUBLE: &str = "0.5*(m1+m2)*l1^2*th1_dot^2 + 0.5*m2*l2^2*th2_dot^2 \
    + m2*l1*l2*th1_dot*th2_dot*cos(th1-th2) + (m1+m2)*g*l1*cos(th1) + m2*g*l2*cos(th2)";

#[inline(never)]
fn double_rust<S: Scalar>(p: &[f64; 5], x: &[S]) -> S {
    let [m1, m2, l1, l2, g] = *p;
    let (th1, th2, w1, w2) = (x[0], x[1], x[2], x[3]);
    w1.powi(2) * (0.5 * (m1 + m2) * l1 * l1)
        + w2.powi(2) * (0.5 * m2 * l2 * l2)
        + w1 * w2 * (th1 - th2).cos() * (m2 * l1 * l2)
        + th1.cos() * ((m1 + m2) * g * l1)
        + th2.cos() * (m2 * g * l2)
}

const DOUBLE_PARAMS: [f64; 5] = [1.0, 2.5, 0.8, 1.1, 9.81];

fn double_program() -> Program {
    let mut symbols =
        Symbols::with_inputs(["th1", "th2", "th1_dot", "th2_dot"]).unwrap_or_default();
    for (name, value) in ["m1", "m2", "l1", "l2", "g"].into_iter().zip(DOUBLE_PARAMS) {
        let _ = symbols.add_constant(name, value);
    }
    Program::compile(DOUBLE, &symbols).unwrap_or_else(|e| panic!("{e}"))
}

type Hd = HyperDualSVec64<1, 1>;

fn hd_inputs() -> [Hd; 2] {
    [
        Hd::from_re(0.3).derivative1(0),
        Hd::from_re(1.7).derivative2(0),
    ]
}

type Hd2 = HyperDualSVec64<2, 2>;

fn hd2_inputs() -> [Hd2; 4] {
    [
        Hd2::from_re(0.3).derivative1(0),
        Hd2::from_re(-0.4).derivative1(1),
        Hd2::from_re(1.7).derivative2(0),
        Hd2::from_re(0.9).derivative2(1),
    ]
}

mod pendulum_f64 {
    use super::*;

    #[divan::bench]
    fn rust(b: Bencher) {
        let x = [0.3_f64, 1.7];
        b.bench(|| pendulum_rust(black_box(&PARAMS), black_box(&x)));
    }

    #[divan::bench]
    fn expr(b: Bencher) {
        let program = pendulum_program();
        let x = [0.3_f64, 1.7];
        b.bench(|| black_box(&program).eval(black_box(&x)));
    }
}

mod pendulum_hyperdual {
    use super::*;

    #[divan::bench]
    fn rust(b: Bencher) {
        let x = hd_inputs();
        b.bench(|| pendulum_rust(black_box(&PARAMS), black_box(&x)));
    }

    #[divan::bench]
    fn expr(b: Bencher) {
        let program = pendulum_program();
        let x = hd_inputs();
        b.bench(|| black_box(&program).eval(black_box(&x)));
    }
}

mod double_pendulum_f64 {
    use super::*;

    #[divan::bench]
    fn rust(b: Bencher) {
        let x = [0.3_f64, -0.4, 1.7, 0.9];
        b.bench(|| double_rust(black_box(&DOUBLE_PARAMS), black_box(&x)));
    }

    #[divan::bench]
    fn expr(b: Bencher) {
        let program = double_program();
        let x = [0.3_f64, -0.4, 1.7, 0.9];
        b.bench(|| black_box(&program).eval(black_box(&x)));
    }
}

mod double_pendulum_hyperdual {
    use super::*;

    #[divan::bench]
    fn rust(b: Bencher) {
        let x = hd2_inputs();
        b.bench(|| double_rust(black_box(&DOUBLE_PARAMS), black_box(&x)));
    }

    #[divan::bench]
    fn expr(b: Bencher) {
        let program = double_program();
        let x = hd2_inputs();
        b.bench(|| black_box(&program).eval(black_box(&x)));
    }
}

#[divan::bench]
fn compile_double_pendulum() -> Program {
    double_program()
}
