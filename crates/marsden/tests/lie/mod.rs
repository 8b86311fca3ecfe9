//! Rigid bodies on SO(3): the Lie algebra and the Cayley map, the body moment by AD against finite
//! differences, the exact free-body solution, free bodies and several bodies, typed failures. The
//! reference cases R19 and R20 are in `reference/` and use the helpers here.

mod body_moment;
mod exact_free_body;
mod failures;
mod free_bodies;
mod group;
mod multibody;
mod particles;
mod springs;

use marsden::NewtonOptions;
use marsden::discrete::rules::composition::CompositionScheme;
use marsden::lie::body::{Inertia, RigidBody};
use marsden::lie::lgvi::{Lgvi, LgviOptions};
use marsden::lie::potential::{NoLoads, NoPotential, UniformGravity};
use marsden::lie::so3::{self, Mat3, Vec3};
use marsden::lie::state::{BodyInitial, RigidState, RigidSystem};

/// Newton options of the conservation tests: converged to round-off.
pub fn tight() -> LgviOptions {
    LgviOptions {
        newton: NewtonOptions {
            residual_tolerance: 1e-15,
            ..NewtonOptions::default()
        },
        composition: None,
    }
}

/// `tight()` with a composition.
pub fn composed(scheme: Option<CompositionScheme>) -> LgviOptions {
    LgviOptions {
        composition: scheme,
        ..tight()
    }
}

/// R19: J = diag(2, 1, 2/3), Π₀ = (cos 1.1, 0, sin 1.1) (HLW06's test body: not a mass
/// distribution, `2 > 1 + 2/3`).
pub const R19_MOMENTS: [f64; 3] = [2.0, 1.0, 2.0 / 3.0];

/// R19's Π₀.
pub fn r19_pi0() -> [f64; 3] {
    [1.1_f64.cos(), 0.0, 1.1_f64.sin()]
}

/// R19: the free rigid body from R₀ = I, stepped by `h`.
pub fn free_body(h: f64, options: LgviOptions) -> Lgvi<NoPotential, NoLoads> {
    let body = RigidBody::fixed_point(Inertia::principal_unphysical(R19_MOMENTS).unwrap());
    let system = RigidSystem::new(vec![body], NoPotential);
    let pi0 = Vec3::from(r19_pi0());
    let state = RigidState::new(
        &system,
        0.0,
        &[BodyInitial::rotating(&Mat3::identity(), &pi0)],
    )
    .unwrap();
    Lgvi::new(system, state, h, options).unwrap()
}

/// R20: the heavy symmetric top J = diag(5, 5, 1), U = mgl e₃·(R e₃), mgl = 20,
/// R₀ = exp(0.05 ê₁), Ω₀ = (0, 0, 50).
pub fn heavy_top(h: f64, options: LgviOptions) -> Lgvi<UniformGravity, NoLoads> {
    let body = RigidBody::fixed_point(Inertia::principal([5.0, 5.0, 1.0]).unwrap());
    let system = RigidSystem::new(vec![body], UniformGravity::top(20.0));
    let r0 = so3::exp(&Vec3::new(0.05, 0.0, 0.0));
    let pi0 = Vec3::new(0.0, 0.0, 50.0);
    let state = RigidState::new(&system, 0.0, &[BodyInitial::rotating(&r0, &pi0)]).unwrap();
    Lgvi::new(system, state, h, options).unwrap()
}
