//! Expression evaluation against the same Lagrangian written in Rust, at `f64` and at the
//! hyper-dual numbers the integrators use for second derivatives.
//!
//! Run with `cargo bench -p marsden-expr --bench expr`.

use divan::{Bencher, black_box};
use marsden::Scalar;
use marsden_expr::{Program, Symbols, Tape};
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

/// The symbolic `∇V`, `∇²V` tapes of a separable Lagrangian, fused and plain (every constant in
/// a register, one instruction per operation: the layout before fusing).
mod tapes {
    use super::*;

    const KEPLER: &str = "0.5*(x_dot^2 + y_dot^2) + mu/sqrt(x^2 + y^2)";
    const PENDULUM: &str = "0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)";

    fn form(text: &str, coords: &[&str], params: &[(&str, f64)]) -> marsden_expr::SeparableForm {
        let inputs = coords
            .iter()
            .map(|q| q.to_string())
            .chain(coords.iter().map(|q| format!("{q}_dot")));
        let mut symbols = Symbols::with_inputs(inputs).unwrap_or_default();
        for &(name, value) in params {
            let _ = symbols.add_constant(name, value);
        }
        Program::compile(text, &symbols)
            .unwrap_or_else(|e| panic!("{e}"))
            .separable(coords.len())
            .unwrap_or_else(|| panic!("{text} is separable"))
    }

    fn kepler_gradient() -> Tape {
        let f = form(KEPLER, &["x", "y"], &[("mu", 1.0)]);
        f.gradient().cloned().unwrap_or_default()
    }

    fn pendulum(hessian: bool) -> Tape {
        let params = [("m", PARAMS.m), ("l", PARAMS.l), ("g", PARAMS.g)];
        let f = form(PENDULUM, &["theta"], &params);
        let tape = if hessian { f.hessian() } else { f.gradient() };
        tape.cloned().unwrap_or_default()
    }

    fn run<S: Scalar>(b: Bencher, tape: &Tape, x: &[S]) {
        let (mut regs, mut out) = (Vec::new(), vec![S::from(0.0); tape.len()]);
        b.bench_local(|| {
            black_box(tape).eval_into(black_box(x), &mut regs, &mut out);
            black_box(out[0])
        });
    }

    /// `∇V` of `V = −μ/|q|` written in Rust (7 operations).
    #[inline(never)]
    fn kepler_gradient_rust(mu: f64, q: &[f64], g: &mut [f64]) {
        let r2 = q[0] * q[0] + q[1] * q[1];
        let k = mu / (r2 * r2.sqrt());
        g[0] = k * q[0];
        g[1] = k * q[1];
    }

    #[divan::bench]
    fn kepler_gradient_rust_f64(b: Bencher) {
        let mut g = [0.0; 2];
        b.bench_local(|| {
            kepler_gradient_rust(black_box(1.0), black_box(&[0.4, 0.3]), &mut g);
            black_box(g[0])
        });
    }

    #[divan::bench]
    fn kepler_gradient_fused(b: Bencher) {
        run(b, &kepler_gradient(), &[0.4_f64, 0.3, 0.0]);
    }

    #[divan::bench]
    fn kepler_gradient_plain(b: Bencher) {
        run(b, kepler_gradient().plain(), &[0.4_f64, 0.3, 0.0]);
    }

    #[divan::bench]
    fn pendulum_gradient_fused(b: Bencher) {
        run(b, &pendulum(false), &[0.3_f64, 0.0]);
    }

    #[divan::bench]
    fn pendulum_gradient_plain(b: Bencher) {
        run(b, pendulum(false).plain(), &[0.3_f64, 0.0]);
    }

    #[divan::bench]
    fn pendulum_hessian_fused(b: Bencher) {
        run(b, &pendulum(true), &[0.3_f64, 0.0]);
    }

    #[divan::bench]
    fn pendulum_hessian_plain(b: Bencher) {
        run(b, pendulum(true).plain(), &[0.3_f64, 0.0]);
    }

    /// The same tapes at hyper-dual numbers (the generic path).
    #[divan::bench]
    fn kepler_gradient_fused_hyperdual(b: Bencher) {
        run(b, &kepler_gradient(), &hd_kepler());
    }

    #[divan::bench]
    fn kepler_gradient_plain_hyperdual(b: Bencher) {
        run(b, kepler_gradient().plain(), &hd_kepler());
    }

    fn hd_kepler() -> [Hd2; 3] {
        [
            Hd2::from_re(0.4).derivative1(0).derivative2(0),
            Hd2::from_re(0.3).derivative1(1).derivative2(1),
            Hd2::from_re(0.0),
        ]
    }
}
