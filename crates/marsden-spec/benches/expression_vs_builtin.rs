//! A Lagrangian typed as text ([`ExprLagrangian`]) against the same system from the catalog,
//! in the library (`Integrator::advance`, no run loop), and the evaluators of an expression.
//!
//! `cargo bench -p marsden-spec --bench expression_vs_builtin`. Rows, each `builtin` and
//! `expression` (ratios in BENCHMARKS.md):
//! * `kepler_trapezoid`: 1000 explicit steps, e = 0.6, h = 0.01 (`expression`: ∇V by native
//!   code with the default `jit` feature; `expression_interpreted`: by the tape interpreter);
//! * `pendulum_midpoint`: 100 midpoint steps, q₀ = 1.5, h = 0.05;
//! * `double_pendulum_midpoint`: 100 midpoint steps, q₀ = (1.5, 2), h = 0.01;
//! * `kepler_gradient`: `∇V` by the symbolic tape (compiled, and interpreted), by AD of the
//!   expression, and in Rust;
//! * `kepler_value`: `L` by the accumulator interpreter and by the register tape.

use divan::{Bencher, black_box};
use marsden::systems::{DoublePendulum, Kepler, Pendulum};
use marsden::{Integrator, Lagrangian, Midpoint, Rule, State, Trapezoid};
use marsden_expr::{Program, Symbols};
use marsden_spec::model::{ExprLagrangian, slots};

fn main() {
    divan::main();
}

fn expression(text: &str, coordinates: &[&str], params: &[(&str, f64)]) -> ExprLagrangian {
    let names: Vec<String> = coordinates.iter().map(|c| c.to_string()).collect();
    let mut symbols = Symbols::with_inputs(slots::tangent_inputs(&names)).unwrap_or_default();
    for &(name, value) in params {
        let _ = symbols.add_constant(name, value);
    }
    let program = Program::compile(text, &symbols).unwrap_or_else(|e| panic!("{e}"));
    ExprLagrangian::new(program, coordinates.len())
}

fn kepler_text() -> ExprLagrangian {
    expression(
        "0.5*(x_dot^2 + y_dot^2) + mu/sqrt(x^2 + y^2)",
        &["x", "y"],
        &[("mu", 1.0)],
    )
}

fn pendulum_text() -> ExprLagrangian {
    let params = [("m", 1.0), ("l", 1.0), ("g", 1.0)];
    expression(
        "0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)",
        &["theta"],
        &params,
    )
}

fn double_pendulum_text() -> ExprLagrangian {
    let text = "0.5*(m1 + m2)*l1^2*a_dot^2 + 0.5*m2*l2^2*b_dot^2 \
                + m2*l1*l2*a_dot*b_dot*cos(a - b) + (m1 + m2)*g*l1*cos(a) + m2*g*l2*cos(b)";
    let params = [
        ("m1", 1.0),
        ("m2", 1.0),
        ("l1", 1.0),
        ("l2", 1.0),
        ("g", 9.81),
    ];
    expression(text, &["a", "b"], &params)
}

fn double_pendulum_builtin() -> DoublePendulum {
    DoublePendulum {
        m1: 1.0,
        m2: 1.0,
        l1: 1.0,
        l2: 1.0,
        g: 9.81,
    }
}

/// `steps` steps per iteration of `rule` from `(q, p)`, the state carried over.
fn advance<L: Lagrangian, R: Rule>(
    b: Bencher,
    l: L,
    rule: R,
    q: &[f64],
    p: &[f64],
    h: f64,
    steps: usize,
) {
    let mut integrator = Integrator::new(rule.discretize(l));
    let mut state = State {
        t: 0.0,
        q: q.to_vec(),
        p: p.to_vec(),
    };
    let _ = integrator.advance(&mut state, h, 10);
    b.bench_local(|| black_box(integrator.advance(black_box(&mut state), h, steps)));
}

#[divan::bench_group(sample_count = 200)]
mod expression_vs_builtin {
    use super::*;

    const KEPLER: (&[f64], &[f64]) = (&[0.4, 0.0], &[0.0, 2.0]);
    const PENDULUM: (&[f64], &[f64]) = (&[1.5], &[0.0]);
    const DOUBLE: (&[f64], &[f64]) = (&[1.5, 2.0], &[0.0, 0.0]);

    #[divan::bench]
    fn kepler_trapezoid_builtin(b: Bencher) {
        advance(
            b,
            Kepler::default(),
            Trapezoid,
            KEPLER.0,
            KEPLER.1,
            0.01,
            1000,
        );
    }

    #[divan::bench]
    fn kepler_trapezoid_expression(b: Bencher) {
        advance(b, kepler_text(), Trapezoid, KEPLER.0, KEPLER.1, 0.01, 1000);
    }

    #[divan::bench]
    fn kepler_trapezoid_expression_interpreted(b: Bencher) {
        advance(
            b,
            kepler_text().interpreted(),
            Trapezoid,
            KEPLER.0,
            KEPLER.1,
            0.01,
            1000,
        );
    }

    #[divan::bench]
    fn pendulum_midpoint_builtin(b: Bencher) {
        advance(
            b,
            Pendulum::default(),
            Midpoint,
            PENDULUM.0,
            PENDULUM.1,
            0.05,
            100,
        );
    }

    #[divan::bench]
    fn pendulum_midpoint_expression(b: Bencher) {
        advance(
            b,
            pendulum_text(),
            Midpoint,
            PENDULUM.0,
            PENDULUM.1,
            0.05,
            100,
        );
    }

    #[divan::bench]
    fn double_pendulum_midpoint_builtin(b: Bencher) {
        advance(
            b,
            double_pendulum_builtin(),
            Midpoint,
            DOUBLE.0,
            DOUBLE.1,
            0.01,
            100,
        );
    }

    #[divan::bench]
    fn double_pendulum_midpoint_expression(b: Bencher) {
        advance(
            b,
            double_pendulum_text(),
            Midpoint,
            DOUBLE.0,
            DOUBLE.1,
            0.01,
            100,
        );
    }

    #[divan::bench]
    fn kepler_gradient_builtin(b: Bencher) {
        gradient(b, Kepler::default());
    }

    #[divan::bench]
    fn kepler_gradient_expression(b: Bencher) {
        gradient(b, kepler_text());
    }

    #[divan::bench]
    fn kepler_gradient_expression_interpreted(b: Bencher) {
        gradient(b, kepler_text().interpreted());
    }

    #[divan::bench]
    fn kepler_gradient_expression_ad(b: Bencher) {
        gradient(b, kepler_text().without_structure());
    }

    #[divan::bench]
    fn kepler_value_interpreter(b: Bencher) {
        let l = kepler_text();
        let x = [0.4, 0.3, 0.1, 2.0, 0.0];
        b.bench_local(|| black_box(l.program().eval(black_box(&x))));
    }

    #[divan::bench]
    fn kepler_value_tape(b: Bencher) {
        let tape = kepler_text().program().tape();
        let x = [0.4, 0.3, 0.1, 2.0, 0.0];
        let (mut regs, mut out) = (Vec::new(), [0.0]);
        b.bench_local(|| {
            tape.eval_into(black_box(&x), &mut regs, &mut out);
            black_box(out[0])
        });
    }

    fn gradient<L: Lagrangian>(b: Bencher, l: L) {
        let (mut grad, mut scratch) = ([0.0; 2], Vec::new());
        // The first call compiles the native code: outside the samples, or divan would size
        // them by it (one call per sample, below its timer's precision).
        l.potential_gradient(0.0, &[0.4, 0.3], &mut grad, &mut scratch);
        b.bench_local(|| {
            l.potential_gradient(0.0, black_box(&[0.4, 0.3]), &mut grad, &mut scratch);
            black_box(grad[0])
        });
    }
}
