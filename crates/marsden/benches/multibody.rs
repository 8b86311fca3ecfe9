//! One step of a hanging chain of `N` hinged rods (`marsden::lie::multibody`), N = 10, 100,
//! 1000: the joint system is banded, so the cost per step should grow about linearly in `N`.
//!
//! `cargo bench -p marsden --bench multibody`. Default Newton options, `h = 0.001`.

use divan::Bencher;
use marsden::lie::lgvi::LgviOptions;
use marsden::lie::multibody::chain::HangingChain;
use marsden::lie::multibody::step::MultibodyLgvi;

// Shows allocations per step in divan's output (none after the first step).
#[global_allocator]
static ALLOC: divan::AllocProfiler = divan::AllocProfiler::system();

fn main() {
    divan::main();
}

#[divan::bench(args = [10, 100, 1000], sample_count = 30)]
fn chain_step(bencher: Bencher, links: usize) {
    let Ok((system, joints, state)) = HangingChain::new(links).build() else {
        return;
    };
    let Ok(mut lgvi) = MultibodyLgvi::new(system, joints, state, 0.001, LgviOptions::default())
    else {
        return;
    };
    bencher.bench_local(|| {
        let _ = divan::black_box(lgvi.step());
    });
}
