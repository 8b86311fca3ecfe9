//! One step of a hanging chain of `N` hinged rods (`marsden::lie::multibody`), N = 10, 100,
//! 1000: the joint system is banded, so the cost per step should grow about linearly in `N`.
//!
//! One step of two free bodies on a spring, with and without a damper between them
//! (`dumbbell_step`): the dampers' end loads are implicit in the end momenta, settled by extra
//! projections (`MultibodyStatistics::damper_iterations`; the test
//! `damper_settles_in_few_projections` counts them).
//!
//! `cargo bench -p marsden --bench multibody`. Default Newton options, `h = 0.001`.

use divan::Bencher;
use marsden::lie::body::{Inertia, RigidBody};
use marsden::lie::lgvi::LgviOptions;
use marsden::lie::multibody::chain::HangingChain;
use marsden::lie::multibody::damper::{Damper, Dampers};
use marsden::lie::multibody::joints::JointSet;
use marsden::lie::multibody::spring::{Spring, Springs};
use marsden::lie::multibody::step::MultibodyLgvi;
use marsden::lie::potential::NoLoads;
use marsden::lie::so3::{self, Vec3};
use marsden::lie::state::{BodyInitial, RigidState, RigidSystem};

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

/// Two free bodies on a spring (stiffness 20), spinning; a damper of coefficient `c` between
/// two other points of theirs when `c > 0`.
fn dumbbell(c: f64) -> Option<MultibodyLgvi<Springs, NoLoads>> {
    let a = RigidBody::free(Inertia::principal([0.3, 0.4, 0.5]).ok()?, 1.5).ok()?;
    let b = RigidBody::free(Inertia::principal([0.2, 0.25, 0.3]).ok()?, 1.0).ok()?;
    let spring = Spring {
        bodies: [Some(0), Some(1)],
        points: [[0.3, 0.1, 0.0], [-0.2, 0.0, 0.15]],
        stiffness: 20.0,
        rest_length: 1.0,
    };
    let system = RigidSystem::new(
        vec![a, b],
        Springs {
            springs: vec![spring],
        },
    );
    let (ra, rb) = (
        so3::exp(&Vec3::new(0.1, 0.2, -0.3)),
        so3::exp(&Vec3::new(-0.4, 0.1, 0.2)),
    );
    let bodies = [
        BodyInitial {
            position: [-0.6, 0.0, 0.1],
            linear_momentum: [0.1, 0.3, 0.0],
            ..BodyInitial::rotating(&ra, &Vec3::new(0.2, -0.1, 0.4))
        },
        BodyInitial {
            position: [0.7, 0.1, 0.0],
            linear_momentum: [-0.2, -0.1, 0.2],
            ..BodyInitial::rotating(&rb, &Vec3::new(-0.1, 0.3, 0.1))
        },
    ];
    let state = RigidState::new(&system, 0.0, &bodies).ok()?;
    let damper = Damper {
        bodies: [Some(0), Some(1)],
        points: [[0.0, -0.1, 0.2], [0.1, 0.1, 0.0]],
        coefficient: c,
    };
    let dampers = Dampers {
        dampers: if c > 0.0 { vec![damper] } else { Vec::new() },
    };
    let joints = JointSet::new(Vec::new(), 2).ok()?;
    let lgvi = MultibodyLgvi::new(system, joints, state, 0.005, LgviOptions::default()).ok()?;
    Some(lgvi.with_dampers(dampers))
}

#[divan::bench(args = [0.0, 2.0], sample_count = 30)]
fn dumbbell_step(bencher: Bencher, damping: f64) {
    let Some(mut lgvi) = dumbbell(damping) else {
        return;
    };
    bencher.bench_local(|| {
        let _ = divan::black_box(lgvi.step());
    });
}
