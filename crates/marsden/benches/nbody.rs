//! One step of the gravitational N-body problem (`systems::NBody`, Plummer data
//! `plummer_N{64,256,1024}_seed20241121.txt` of the benchmark data kept beside the repository with
//! the C reference, G = 1, ε = 0.01, h = 1e-3) with the trapezoid rule — explicit Störmer–Verlet
//! with the vectorised direct-summation gradient ([`marsden::systems::nbody::gravity`]) — next to
//! `verlet nbody FILE 1 0.01 0.001 … full` (`scripts/bench.sh` runs both and prints the ratio).
//! Target: ≤ 1.1× `verlet.c` at N = 1024.
//!
//! `midpoint_*` times the implicit midpoint step on the same data (Newton with Jacobian
//! `M/h + (h/4)∇²V`, dense AD Hessian: for scale only, at N = 64).
//!
//! Run: `cargo bench -p marsden --bench nbody` (needs the benchmark data files kept beside the
//! repository with the C reference `verlet.c`, or `MARSDEN_BENCH_DATA=dir`).

use std::path::PathBuf;

use divan::Bencher;
use marsden::systems::nbody::file;
use marsden::{DiscreteAction, Integrator, Midpoint, Rule, State, Trapezoid};

#[global_allocator]
static ALLOC: divan::AllocProfiler = divan::AllocProfiler::system();

const H: f64 = 1e-3;
const SOFTENING: f64 = 0.01;

fn main() {
    divan::main();
}

fn data(bodies: usize) -> PathBuf {
    let dir = std::env::var_os("MARSDEN_BENCH_DATA").map_or_else(
        || PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/bench/data"),
        PathBuf::from,
    );
    dir.join(format!("plummer_N{bodies}_seed20241121.txt"))
}

/// Loads the Plummer data, warms the step, then times one step per iteration.
fn bench_steps<A: DiscreteAction>(
    bencher: Bencher,
    bodies: usize,
    discretize: impl Fn(marsden::systems::NBody) -> A,
) {
    let Ok((system, q, p)) = file::load(data(bodies), 1.0, SOFTENING) else {
        eprintln!("skipped: {} not readable", data(bodies).display());
        return;
    };
    let mut integrator = Integrator::new(discretize(system));
    let mut state = State { t: 0.0, q, p };
    for _ in 0..4 {
        if integrator.step(&mut state, H).is_err() {
            return;
        }
    }
    bencher.bench_local(|| {
        let _ = divan::black_box(integrator.step(&mut state, H));
    });
}

#[divan::bench(args = [64, 256, 1024], max_time = 4)]
fn trapezoid(bencher: Bencher, bodies: usize) {
    bench_steps(bencher, bodies, |s| Trapezoid.discretize(s));
}

#[divan::bench(args = [64], max_time = 4)]
fn midpoint(bencher: Bencher, bodies: usize) {
    bench_steps(bencher, bodies, |s| Midpoint.discretize(s));
}
