//! The Lie group variational integrator on the heavy top (R20): one step, and a run of 10⁴ steps.
//!
//! `cargo bench -p marsden --bench lgvi`, next to `verlet.c heavy-top` (the same step by hand in
//! C: Cayley Newton, closed-form moment). Default Newton options (residual 1e-12 relative).

use divan::Bencher;
use marsden::lie::body::{Inertia, RigidBody};
use marsden::lie::lgvi::{Lgvi, LgviOptions};
use marsden::lie::potential::{NoLoads, UniformGravity};
use marsden::lie::so3::{self, Vec3};
use marsden::lie::state::{BodyInitial, RigidState, RigidSystem};

// Shows allocations per step in divan's output.
#[global_allocator]
static ALLOC: divan::AllocProfiler = divan::AllocProfiler::system();

fn main() {
    divan::main();
}

/// Steps timed together in one sample (as in the `step` bench: a single ~100 ns step is at the
/// timer's precision).
const STEPS_PER_SAMPLE: u32 = 64;

fn top(h: f64) -> Option<Lgvi<UniformGravity, NoLoads>> {
    let body = RigidBody::fixed_point(Inertia::principal([5.0, 5.0, 1.0]).ok()?);
    let system = RigidSystem::new(vec![body], UniformGravity::top(20.0));
    let r0 = so3::exp(&Vec3::new(0.05, 0.0, 0.0));
    let initial = BodyInitial::rotating(&r0, &Vec3::new(0.0, 0.0, 50.0));
    let state = RigidState::new(&system, 0.0, &[initial]).ok()?;
    Lgvi::new(system, state, h, LgviOptions::default()).ok()
}

#[divan::bench(sample_size = STEPS_PER_SAMPLE)]
fn heavy_top_step(bencher: Bencher) {
    let Some(mut lgvi) = top(0.001) else {
        return;
    };
    bencher.bench_local(|| {
        let _ = divan::black_box(lgvi.step());
    });
}

#[divan::bench(sample_count = 20)]
fn heavy_top_10k_steps(bencher: Bencher) {
    bencher.bench_local(|| {
        let Some(mut lgvi) = top(0.001) else {
            return;
        };
        for _ in 0..10_000 {
            if lgvi.step().is_err() {
                return;
            }
        }
        divan::black_box(lgvi.state().momenta[0]);
    });
}
