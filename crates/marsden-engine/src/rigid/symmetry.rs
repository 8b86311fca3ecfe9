//! Whether each declared symmetry of a rigid body is one: the Lagrangian
//! `½ΩᵀJΩ + ½m|ẋ|² − U(R, x)` is invariant under a rotation in space `(R, x) ↦ (QR, Qx)` exactly
//! when `U` is (the kinetic energy always is, [MR99] §15.3), under a rotation about a body axis
//! `R ↦ RQ` when `U` is and `QᵀJQ = J` (the body is symmetric about that axis), and under a
//! translation `x ↦ x + s e_a` when `U` is. Checked with finite rotations and translations
//! (angles and shifts 0.3, 1.1, 2.5) at the initial state and at three states turned from it:
//! a symmetry leaves every value unchanged to round-off.
//!
//! [MR99]: marsden#references

use marsden::lie::potential::{ExternalLoads as _, RigidPotential};
use marsden::lie::so3::{self, Mat3, Vec3};
// A NaN defect (a potential that is not finite there) must not pass as a symmetry.
use marsden::lie::state::RigidState;
use marsden::numerics::dense::max_or_nan;
use marsden_problem::problem::rigid::{RigidAction, RigidSpec};

use super::FileRigidSystem;
use crate::start::SymmetryCheck;

/// The relative defect above which an action is not a symmetry (round-off of the checks).
const TOLERANCE: f64 = 1e-10;

/// The amounts of each finite action tried.
const AMOUNTS: [f64; 3] = [0.3, 1.1, 2.5];

/// The check of each declared symmetry of `body` around `state`.
pub(super) fn check(
    body: &RigidSpec,
    system: &FileRigidSystem,
    state: &RigidState,
) -> Vec<SymmetryCheck> {
    let states = nearby(state);
    body.symmetries
        .iter()
        .map(|s| {
            let defect = states
                .iter()
                .map(|st| defect(s.action, body, system, st))
                .fold(0.0, max_or_nan);
            let with_loads = body.loads.is_active();
            SymmetryCheck {
                name: s.name.clone(),
                of: "L",
                states: states.len(),
                max_relative_defect: defect,
                is_symmetry: defect <= TOLERANCE && !with_loads,
            }
        })
        .collect()
}

/// The warning of a declared action that is not a symmetry.
pub(super) fn warning(check: &SymmetryCheck) -> Option<String> {
    (!check.is_symmetry).then(|| {
        format!(
            "\"{}\" is not a symmetry of the rigid body (relative change of L under the action up \
             to {:.3e} at the initial state and {} states turned from it, or torques and forces \
             act), so J_{} is monitored but not conserved",
            check.name,
            check.max_relative_defect,
            check.states.saturating_sub(1),
            check.name
        )
    })
}

/// The initial state and three states turned from it in space.
fn nearby(state: &RigidState) -> Vec<RigidState> {
    let turns = [
        Vec3::new(0.4, -0.2, 0.7),
        Vec3::new(-1.3, 0.5, 0.1),
        Vec3::new(0.2, 2.0, -0.6),
    ];
    let mut out = vec![state.clone()];
    for turn in turns {
        let mut s = state.clone();
        s.set_rotation(0, &(so3::exp(&turn) * state.rotation(0)));
        out.push(s);
    }
    out
}

/// The largest relative change of `L`'s parts under the action of `action` by the amounts
/// tried, at `state`.
fn defect(
    action: RigidAction,
    body: &RigidSpec,
    system: &FileRigidSystem,
    state: &RigidState,
) -> f64 {
    let u = |r: &Mat3, x: &[f64]| system.potential.value(state.t, &so3::rows(r), x);
    let r = state.rotation(0);
    let x = &state.positions[..3];
    let u0 = u(&r, x);
    let scale = u0.abs().max(1.0);
    AMOUNTS
        .iter()
        .map(|&s| match action {
            RigidAction::Space(a) => {
                let q = so3::exp(&(Vec3::ith(a, s)));
                let qx = q * Vec3::new(x[0], x[1], x[2]);
                (u(&(q * r), qx.as_slice()) - u0).abs() / scale
            }
            RigidAction::Body(a) => {
                let q = so3::exp(&(Vec3::ith(a, s)));
                let j = body.inertia.tensor();
                let kinetic = (q.transpose() * j * q - j).amax() / j.amax();
                ((u(&(r * q), x) - u0).abs() / scale).max(kinetic)
            }
            RigidAction::Translation(a) => {
                let mut moved = [x[0], x[1], x[2]];
                moved[a] += s;
                (u(&r, &moved) - u0).abs() / scale
            }
        })
        .fold(0.0, max_or_nan)
}
