//! One midpoint step of the pendulum (q₀ = 1.5, h = 0.05): the Lagrangian as a problem-file
//! expression ([`ExprLagrangian`]) against the same Lagrangian in Rust ([`Pendulum`]).
//!
//! The state advances from one iteration to the next, as in a run, so the predictor is warm
//! and each step costs what it costs inside `marsden run` (about one Newton update).
//!
//! `cargo bench -p marsden-spec --bench lagrangian_path`; the ratio `expr / rust` is the
//! overhead of the expression path (goal ≤ 2×).

use divan::{Bencher, black_box};
use marsden::systems::Pendulum;
use marsden::{Integrator, Lagrangian, Midpoint, Rule, State};
use marsden_expr::{Program, Symbols};
use marsden_spec::model::ExprLagrangian;

fn main() {
    divan::main();
}

const H: f64 = 0.05;

/// The pendulum as `marsden run` compiles it from `examples/pendulum.toml`.
fn expression_pendulum() -> ExprLagrangian {
    let mut symbols = Symbols::with_inputs(["theta", "theta_dot", "t"]).unwrap_or_default();
    for name in ["m", "l", "g"] {
        let _ = symbols.add_constant(name, 1.0);
    }
    let program = Program::compile("0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)", &symbols)
        .unwrap_or_else(|e| panic!("{e}"));
    ExprLagrangian::new(program, 1)
}

fn bench_steps<L: Lagrangian>(b: Bencher, lagrangian: L) {
    let mut integrator = Integrator::new(Midpoint.discretize(lagrangian));
    let mut state = State {
        t: 0.0,
        q: vec![1.5],
        p: vec![0.0],
    };
    // Warm up the predictor's history.
    for _ in 0..10 {
        let _ = integrator.step(&mut state, H);
    }
    b.bench_local(|| black_box(integrator.step(black_box(&mut state), H)));
}

#[divan::bench(sample_count = 1000, sample_size = 200)]
fn midpoint_step_rust(b: Bencher) {
    bench_steps(b, Pendulum::default());
}

#[divan::bench(sample_count = 1000, sample_size = 200)]
fn midpoint_step_expr(b: Bencher) {
    bench_steps(b, expression_pendulum());
}
