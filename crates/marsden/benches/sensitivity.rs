//! The cost of derivatives through a run, beside the plain run, in the same process: Kepler
//! e = 0.6 from pericentre, midpoint and gauss-2, h = 0.01, 1000 steps (Newton tolerance 1e-12).
//!
//! * `plain`: the run alone (`Integrator::step` 1000 times);
//! * `tangent`: the run with `∂(q, p)/∂(q₀, p₀)` propagated (all 2n = 4 columns; one step
//!   Jacobian by the implicit function theorem and one 4×4 product per step);
//! * `adjoint`: the gradient of a loss on every 10th sample by the reverse sweep with the
//!   default checkpoints (`m = ⌈√K⌉`): a plain forward sweep, then the recomputed steps with
//!   their Jacobians and one transposed product each.
//!
//! Run (fat LTO, slow to build): `cargo bench -p marsden --bench sensitivity`. Per-step figures
//! are the medians divided by 1000; ratios to `plain` of the same rule come from the same run.

use divan::Bencher;
use marsden::discrete::rules::Galerkin;
use marsden::sensitivity::{AdjointOptions, TangentOptions, adjoint, tangent};
use marsden::systems::Kepler;
use marsden::{DiscreteAction, Integrator, Midpoint, Rule, State, TimeGrid};

const STEPS: usize = 1000;

fn main() {
    divan::main();
}

fn start() -> State {
    let (q, p) = Kepler::pericentre(0.6);
    State {
        t: 0.0,
        q: q.to_vec(),
        p: p.to_vec(),
    }
}

fn grid() -> TimeGrid {
    TimeGrid::new(0.0, 0.01, STEPS).unwrap_or(TimeGrid {
        t0: 0.0,
        h: 0.01,
        steps: STEPS,
        end: None,
    })
}

fn plain<A: DiscreteAction + Clone>(bencher: Bencher, action: A) {
    bencher.bench_local(|| {
        let mut vi = Integrator::new(action.clone());
        let mut s = start();
        let ok = vi.advance(&mut s, 0.01, STEPS).is_ok();
        divan::black_box((ok, s))
    });
}

fn forward<A: DiscreteAction + Clone>(bencher: Bencher, action: A) {
    let grid = grid();
    bencher.bench_local(|| {
        let mut vi = Integrator::new(action.clone());
        divan::black_box(tangent(&mut vi, start(), &grid, &TangentOptions::default()).is_ok())
    });
}

fn reverse<A: DiscreteAction + Clone>(bencher: Bencher, action: A) {
    let grid = grid();
    bencher.bench_local(|| {
        let mut vi = Integrator::new(action.clone());
        let loss = |k: usize, x: &State, out: &mut [f64]| {
            if k.is_multiple_of(10) {
                out[0] += x.q[0];
            }
        };
        divan::black_box(adjoint(&mut vi, start(), &grid, loss, &AdjointOptions::default()).is_ok())
    });
}

fn gauss2() -> Option<impl DiscreteAction + Clone> {
    Some(Galerkin::gauss(2).ok()?.discretize(Kepler::default()))
}

#[divan::bench]
fn midpoint_plain(b: Bencher) {
    plain(b, Midpoint.discretize(Kepler::default()));
}

#[divan::bench]
fn midpoint_tangent(b: Bencher) {
    forward(b, Midpoint.discretize(Kepler::default()));
}

#[divan::bench]
fn midpoint_adjoint(b: Bencher) {
    reverse(b, Midpoint.discretize(Kepler::default()));
}

#[divan::bench]
fn gauss2_plain(b: Bencher) {
    if let Some(action) = gauss2() {
        plain(b, action);
    }
}

#[divan::bench]
fn gauss2_tangent(b: Bencher) {
    if let Some(action) = gauss2() {
        forward(b, action);
    }
}

#[divan::bench]
fn gauss2_adjoint(b: Bencher) {
    if let Some(action) = gauss2() {
        reverse(b, action);
    }
}
