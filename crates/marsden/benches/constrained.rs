//! One step of the constrained pendulum: a point mass in the plane in Cartesian coordinates
//! with the distance constraint `|q| = l` (`systems::CartesianPendulum`), midpoint rule,
//! `h = 0.01`, `θ₀ = 1.5` — the "pendulum with distance constraint" row of `bench/README.md`
//! (trep MidpointVI + constraint: 8 240 ns per step). Target: ≤ 400 ns (20× faster).
//!
//! Run (fat LTO, slow to build): `cargo bench -p marsden --bench constrained`. Each iteration is
//! one call of `Integrator::step` on a running trajectory (Newton tolerance 1e-12, the default),
//! after a few warm-up steps so the predictor is in its steady state.
//!
//! * `shake_rattle_step`: a full step as `Problem::integrator` builds it (SHAKE solve for
//!   `(q_{k+1}, λ_k)` plus the RATTLE momentum projection) — the figure to compare with trep;
//! * `shake_step`: the SHAKE solve alone (momenta not projected);
//! * `angle_pendulum_step`: the same pendulum in its angle coordinate, unconstrained, for scale;
//! * `spherical_*`: one step of the spherical pendulum (`systems::SphericalPendulum`, `θ₀ = 1`,
//!   `ϕ̇₀ = 0.8`) with SHAKE + RATTLE (midpoint, order 2), constrained Lobatto IIIA–IIIB
//!   (`lobatto-3`, stage constraints, order 4) and a composition of nine RATTLE steps
//!   (`kahan-li-6(trapezoid)`, order 6), in the same run.

use divan::Bencher;
use marsden::discrete::rules::{Composition, CompositionScheme, Galerkin};
use marsden::holonomic::MomentumProjection;
use marsden::systems::{CartesianPendulum, Pendulum, SphericalPendulum};
use marsden::{
    DiscreteAction, DiscreteForce, Initial, Integrator, Midpoint, NewtonOptions, Problem, Rule,
    State, TimeGrid,
};

const H: f64 = 0.01;

/// Steps timed together in one sample (left to divan, a cold first call can make it time
/// single ~200 ns steps with a 20 ns timer; see `benches/step.rs`).
const STEPS_PER_SAMPLE: u32 = 64;

fn main() {
    divan::main();
}

/// Warms the predictor, then times one step per iteration.
fn bench_steps<A, F, C, P>(bencher: Bencher, mut integrator: Integrator<A, F, C, P>, start: State)
where
    A: DiscreteAction,
    F: DiscreteForce,
    C: marsden::Constraint,
    P: MomentumProjection,
{
    let mut state = start;
    for _ in 0..8 {
        if integrator.step(&mut state, H).is_err() {
            return;
        }
    }
    bencher.bench_local(|| {
        let _ = divan::black_box(integrator.step(&mut state, H));
    });
}

fn constrained() -> Option<Problem<CartesianPendulum, marsden::NoForce, CartesianPendulum>> {
    let sys = CartesianPendulum::default();
    let grid = TimeGrid::new(0.0, H, 1).ok()?;
    Problem::new(sys, sys.initial(1.5, 0.0), grid)
        .ok()?
        .with_constraint(sys)
        .ok()
}

#[divan::bench(sample_size = STEPS_PER_SAMPLE)]
fn shake_rattle_step(bencher: Bencher) {
    let Some(problem) = constrained() else { return };
    let Ok(integrator) = problem.integrator(&Midpoint, NewtonOptions::default()) else {
        return;
    };
    bench_steps(bencher, integrator, problem.start().clone());
}

#[divan::bench(sample_size = STEPS_PER_SAMPLE)]
fn shake_step(bencher: Bencher) {
    let Some(problem) = constrained() else { return };
    let sys = *problem.lagrangian();
    let mut integrator = Integrator::new(Midpoint.discretize(sys)).with_constraint(sys);
    integrator.set_velocity_hint(problem.initial_velocity());
    bench_steps(bencher, integrator, problem.start().clone());
}

#[divan::bench(sample_size = STEPS_PER_SAMPLE)]
fn angle_pendulum_step(bencher: Bencher) {
    let sys = Pendulum::default();
    let Ok(grid) = TimeGrid::new(0.0, H, 1) else {
        return;
    };
    let Ok(problem) = Problem::new(sys, Initial::velocity(&[1.5], &[0.0]), grid) else {
        return;
    };
    let Ok(integrator) = problem.integrator(&Midpoint, NewtonOptions::default()) else {
        return;
    };
    bench_steps(bencher, integrator, problem.start().clone());
}

fn spherical() -> Option<Problem<SphericalPendulum, marsden::NoForce, SphericalPendulum>> {
    let sys = SphericalPendulum::default();
    let grid = TimeGrid::new(0.0, H, 1).ok()?;
    Problem::new(sys, sys.initial(1.0, 0.0, 0.0, 0.8), grid)
        .ok()?
        .with_constraint(sys)
        .ok()
}

fn bench_spherical<R: Rule>(bencher: Bencher, rule: &R) {
    let Some(problem) = spherical() else { return };
    let Ok(integrator) = problem.integrator(rule, NewtonOptions::default()) else {
        return;
    };
    bench_steps(bencher, integrator, problem.start().clone());
}

#[divan::bench(sample_size = STEPS_PER_SAMPLE)]
fn spherical_rattle_midpoint(bencher: Bencher) {
    bench_spherical(bencher, &Midpoint);
}

#[divan::bench(sample_size = STEPS_PER_SAMPLE)]
fn spherical_lobatto_3(bencher: Bencher) {
    let Ok(rule) = Galerkin::lobatto(3) else {
        return;
    };
    bench_spherical(bencher, &rule);
}

#[divan::bench(sample_size = STEPS_PER_SAMPLE)]
fn spherical_kahan_li_6_trapezoid(bencher: Bencher) {
    let rule = Composition::new(marsden::Trapezoid, CompositionScheme::KahanLi6);
    bench_spherical(bencher, &rule);
}

// Measured: see BENCHMARKS.md, section "Constrained pendulum".
