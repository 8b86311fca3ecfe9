//! Symmetries: Lie group actions, their momentum maps, and the checks that a declared action
//! really is a symmetry.
//!
//! Concept of the notes (MW01): *Hamiltonian momentum maps*, *the Lagrangian momentum map*, *Noether's theorem* (continuous
//! and discrete), *equivariance*. The pieces:
//!
//! * [`GroupAction`] (infinitesimal generators `ξ_Q(q)`, generic over the scalar) and
//!   [`FiniteAction`] (`Φ_g`, `Ad*`), with their tangent and cotangent lifts by AD
//!   ([`tangent_lift`], [`cotangent_lift`], [`act_tangent`], [`act_cotangent`]);
//! * built-ins: [`Translations`], [`AxisRotation`] (`SO(2)`), [`Rotations`] (`SO(3)`, hat map),
//!   and the [`Symmetry`] enum that holds any of them (so a system can declare a list,
//!   [`DeclaresSymmetries`]);
//! * momentum maps `J_L`, `J_H`, `J^±_{L_d}` ([`momentum`]);
//! * symmetry checks with the size of the defect ([`check`]) and the equivariance defect
//!   ([`equivariance_defect`]).
//!
//! Conservation along runs (Noether, and the balance law with forces) is monitored by
//! [`crate::analysis::diagnostics::noether`].
//!
//! ```
//! use marsden::symmetry::{AxisRotation, momentum_map};
//!
//! // Angular momentum of a planar particle: J = x p_y − y p_x.
//! let mut j = [0.0];
//! momentum_map(&AxisRotation::planar(1), &[0.4, 0.0], &[0.0, 2.0], &mut j);
//! assert_eq!(j[0], 0.8);
//! ```

mod action;
mod builtin;
mod catalog;
pub mod check;
pub mod momentum;

pub use action::{
    FiniteAction, GroupAction, act_cotangent, act_tangent, cotangent_lift, generator_jacobian,
    generators, tangent_lift, validate,
};
pub use builtin::{AxisRotation, Rotations, Translations, hat, rotation_matrix};
pub use check::{Sample, SymmetryReport};
pub use momentum::{
    Side, StepSpan, discrete_momentum, discrete_momentum_offset, lagrangian_momentum_map,
    momentum_map,
};

use crate::error::Error;
use crate::scalar::Scalar;

/// Any built-in group action (so that a system can declare a list of different symmetries).
#[derive(Debug, Clone, PartialEq)]
pub enum Symmetry {
    /// Translations of all particles by one vector.
    Translations(Translations),
    /// Rotations about one axis.
    AxisRotation(AxisRotation),
    /// The full rotation group.
    Rotations(Rotations),
}

impl GroupAction for Symmetry {
    fn name(&self) -> String {
        match self {
            Self::Translations(g) => g.name(),
            Self::AxisRotation(g) => g.name(),
            Self::Rotations(g) => g.name(),
        }
    }
    fn dof(&self) -> usize {
        match self {
            Self::Translations(g) => g.dof(),
            Self::AxisRotation(g) => g.dof(),
            Self::Rotations(g) => g.dof(),
        }
    }
    fn algebra_dim(&self) -> usize {
        match self {
            Self::Translations(g) => g.algebra_dim(),
            Self::AxisRotation(g) => g.algebra_dim(),
            Self::Rotations(g) => g.algebra_dim(),
        }
    }
    fn generator<S: Scalar>(&self, a: usize, q: &[S], out: &mut [S]) {
        match self {
            Self::Translations(g) => g.generator(a, q, out),
            Self::AxisRotation(g) => g.generator(a, q, out),
            Self::Rotations(g) => g.generator(a, q, out),
        }
    }
}

impl FiniteAction for Symmetry {
    fn act<S: Scalar>(&self, xi: &[f64], q: &[S], out: &mut [S]) {
        match self {
            Self::Translations(g) => g.act(xi, q, out),
            Self::AxisRotation(g) => g.act(xi, q, out),
            Self::Rotations(g) => g.act(xi, q, out),
        }
    }
    fn coadjoint(&self, xi: &[f64], mu: &[f64], out: &mut [f64]) {
        match self {
            Self::Translations(g) => g.coadjoint(xi, mu, out),
            Self::AxisRotation(g) => g.coadjoint(xi, mu, out),
            Self::Rotations(g) => g.coadjoint(xi, mu, out),
        }
    }
}

/// A system that declares its continuous symmetries (catalog systems do; see
/// [`crate::systems`]). Their momentum maps are what [`crate::analysis::diagnostics::noether`] monitors.
pub trait DeclaresSymmetries {
    /// The group actions leaving the system invariant.
    fn symmetries(&self) -> Vec<Symmetry>;
}

/// Equivariance defect `|J_H(Φ_g^{T*Q}(q, p)) − Ad*_{g⁻¹} J_H(q, p)|` (max-norm) for `g = exp(ξ)`
/// (seed: *equivariance*; cotangent lifts make `J_H` equivariant, [MR99] Thm 12.1.4).
///
/// [MR99]: crate#references
pub fn equivariance_defect<G: FiniteAction>(
    action: &G,
    xi: &[f64],
    q: &[f64],
    p: &[f64],
) -> Result<f64, Error> {
    let (n, m) = (q.len(), action.algebra_dim());
    validate(action, n, q)?;
    let (mut gq, mut gp) = (vec![0.0; n], vec![0.0; n]);
    act_cotangent(action, xi, q, p, &mut gq, &mut gp)?;
    let (mut j, mut j_moved, mut j_co) = (vec![0.0; m], vec![0.0; m], vec![0.0; m]);
    momentum_map(action, q, p, &mut j);
    momentum_map(action, &gq, &gp, &mut j_moved);
    action.coadjoint(xi, &j, &mut j_co);
    Ok(j_moved
        .iter()
        .zip(&j_co)
        .fold(0.0, |m, (a, b)| m.max((a - b).abs())))
}
