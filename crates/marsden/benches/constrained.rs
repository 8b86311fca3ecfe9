//! One step of the constrained pendulum: a point mass in the plane in Cartesian coordinates
//! with the distance constraint `|q| = l` (`systems::CartesianPendulum`), midpoint rule,
//! `h = 0.01`, `θ₀ = 1.5` — the "pendulum with distance constraint" row of `bench/README.md`
//! (trep MidpointVI + constraint: 8 240 ns per step). Target: ≤ 400 ns (20× faster).
//!
//! Run (fat LTO, slow to build): `cargo bench -p marsden --bench constrained`.
//!
//! * `shake_rattle_step`: a full step as `Problem::integrator` builds it (SHAKE solve for
//!   `(q_{k+1}, λ_k)` plus the RATTLE momentum projection) — the figure to compare with trep;
//! * `shake_step`: the SHAKE solve alone (momenta not projected);
//! * `angle_pendulum_step`: the same pendulum in its angle coordinate, unconstrained, for scale.

use marsden::systems::{CartesianPendulum, Pendulum};
use marsden::{Initial, Integrator, Midpoint, NewtonOptions, Problem, Rule, State, TimeGrid};

const H: f64 = 0.01;

fn main() {
    divan::main();
}

fn problem() -> Problem<CartesianPendulum, marsden::NoForce, CartesianPendulum> {
    let sys = CartesianPendulum::default();
    Problem::new(
        sys,
        sys.initial(1.5, 0.0),
        TimeGrid::new(0.0, H, 1).unwrap(),
    )
    .unwrap()
    .with_constraint(sys)
    .unwrap()
}

#[divan::bench]
fn shake_rattle_step(bencher: divan::Bencher) {
    let problem = problem();
    let mut integrator = problem
        .integrator(&Midpoint, NewtonOptions::default())
        .unwrap();
    let mut state = problem.start().clone();
    bencher.bench_local(|| {
        integrator.step(&mut state, H).unwrap();
    });
}

#[divan::bench]
fn shake_step(bencher: divan::Bencher) {
    let problem = problem();
    let sys = *problem.lagrangian();
    let mut integrator = Integrator::new(Midpoint.discretize(sys)).with_constraint(sys);
    integrator.set_velocity_hint(problem.initial_velocity());
    let mut state = problem.start().clone();
    bencher.bench_local(|| {
        integrator.step(&mut state, H).unwrap();
    });
}

#[divan::bench]
fn angle_pendulum_step(bencher: divan::Bencher) {
    let sys = Pendulum::default();
    let problem = Problem::new(
        sys,
        Initial::velocity(&[1.5], &[0.0]),
        TimeGrid::new(0.0, H, 1).unwrap(),
    )
    .unwrap();
    let mut integrator = problem
        .integrator(&Midpoint, NewtonOptions::default())
        .unwrap();
    let mut state: State = problem.start().clone();
    bencher.bench_local(|| {
        integrator.step(&mut state, H).unwrap();
    });
}
