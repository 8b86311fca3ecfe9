//! Energy, momentum maps and Casimirs of rigid bodies ([MR99] §15; [LLM07] §3.3).
//!
//! * Energy `E = Σᵢ [½ Π_iᵀJ_i⁻¹Π_i + |p_i|²/2m_i] + U(t, R, x)`.
//! * Spatial rotations act on the left, `R ↦ QR`, `x ↦ Qx`: their momentum map is the spatial
//!   angular momentum `Σᵢ (R_iΠ_i + x_i × p_i)`, conserved exactly by the LGVI (discrete Noether)
//!   when `U` is invariant.
//! * Body rotations of body `i` act on the right, `R_i ↦ R_iQ`: momentum map `Π_i` (conserved
//!   componentwise along the symmetry axis of a symmetric top, `Π₃`).
//! * The Casimir `|Π_i|²` of the free body (the LGVI without potential is the Moser–Veselov map,
//!   which conserves it and the energy exactly).
//! * The orthogonality defect `max_i max |R_iᵀR_i − I|`.
//!
//! [MR99]: crate#references
//! [LLM07]: crate#references

use super::potential::RigidPotential;
use super::so3::{Vec3, orthogonality_defect};
use super::state::{RigidState, RigidSystem};

/// The kinetic energy `Σᵢ ½ Π_iᵀJ_i⁻¹Π_i + |p_i|²/2m_i`.
pub fn kinetic_energy<U, E>(system: &RigidSystem<U, E>, state: &RigidState) -> f64 {
    let mut kinetic = 0.0;
    for (i, body) in system.bodies.iter().enumerate() {
        let pi = state.momentum(i);
        kinetic += 0.5 * pi.dot(&(body.inertia.inverse() * pi));
        if let Some(mass) = body.mass {
            kinetic += 0.5 * state.linear_momentum(i).norm_squared() / mass;
        }
    }
    kinetic
}

/// The energy `E = T + U(t, R, x)`.
pub fn energy<U: RigidPotential, E>(system: &RigidSystem<U, E>, state: &RigidState) -> f64 {
    let potential = if U::ZERO {
        0.0
    } else {
        system
            .potential
            .value(state.t, &state.rotations, &state.positions)
    };
    kinetic_energy(system, state) + potential
}

/// The spatial angular momentum about the origin `Σᵢ (R_iΠ_i + x_i × p_i)` (the momentum map of
/// rotations acting on the left).
pub fn spatial_angular_momentum(state: &RigidState) -> Vec3 {
    (0..state.bodies())
        .map(|i| {
            state.rotation(i) * state.momentum(i)
                + state.position(i).cross(&state.linear_momentum(i))
        })
        .sum()
}

/// The total linear momentum `Σᵢ p_i`.
pub fn linear_momentum(state: &RigidState) -> Vec3 {
    (0..state.bodies()).map(|i| state.linear_momentum(i)).sum()
}

/// The body angular momentum `Π_i` of body `i` (the momentum map of rotations acting on the
/// right of `R_i`).
pub fn body_momentum(state: &RigidState, i: usize) -> Vec3 {
    state.momentum(i)
}

/// The Casimir `|Π_i|²` of body `i`.
pub fn casimir(state: &RigidState, i: usize) -> f64 {
    state.momentum(i).norm_squared()
}

/// `max_i max |R_iᵀR_i − I|`.
pub fn orthogonality(state: &RigidState) -> f64 {
    (0..state.bodies())
        .map(|i| orthogonality_defect(&state.rotation(i)))
        .fold(0.0, crate::numerics::dense::max_or_nan)
}
