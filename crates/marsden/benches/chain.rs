//! The midpoint rule on the FPU-β chain (`systems::Chain`, n = 10³ … 10⁶ particles): Newton
//! with the tridiagonal Jacobian `M/h + (h/4)∇²V`, banded LU ([`marsden::numerics::banded`]), Jacobian
//! reused across iterations and steps ([`marsden::separable::alpha`]). The cost per step should be
//! linear in n; `scripts/bench_table.py` fits the exponent of `median ∝ n^a` to the rows.
//!
//! Run: `cargo bench -p marsden --bench chain` (fewer samples for large n keep it to about a
//! minute).

use divan::Bencher;
use marsden::systems::Chain;
use marsden::{Integrator, Midpoint, Rule, State};

#[global_allocator]
static ALLOC: divan::AllocProfiler = divan::AllocProfiler::system();

const H: f64 = 0.05;

fn main() {
    divan::main();
}

/// A smooth start: the lowest mode with amplitude 1 (strongly nonlinear for β = 1) plus a
/// short wave packet, at rest.
fn start(n: usize) -> State {
    let x = |i: usize| (i + 1) as f64 / (n + 1) as f64;
    let q = (0..n)
        .map(|i| {
            let s = x(i);
            (std::f64::consts::PI * s).sin() + 0.1 * (-(s - 0.5).powi(2) * 400.0).exp()
        })
        .collect();
    State {
        t: 0.0,
        q,
        p: vec![0.0; n],
    }
}

fn bench_chain(bencher: Bencher, n: usize) {
    let mut integrator = Integrator::new(Midpoint.discretize(Chain::new(n)));
    let mut state = start(n);
    for _ in 0..4 {
        if integrator.step(&mut state, H).is_err() {
            return;
        }
    }
    bencher.bench_local(|| {
        let _ = divan::black_box(integrator.step(&mut state, H));
    });
}

#[divan::bench(args = [1_000, 10_000, 100_000], max_time = 3)]
fn midpoint(bencher: Bencher, n: usize) {
    bench_chain(bencher, n);
}

/// n = 10⁶ separately, with few samples (a step takes tens of milliseconds).
#[divan::bench(args = [1_000_000], sample_count = 10, sample_size = 1)]
fn midpoint_large(bencher: Bencher, n: usize) {
    bench_chain(bencher, n);
}
