//! A rigid body: its inertia tensor `J` (about the fixed point, or about the centre of mass for a
//! free body), validated once, and an optional mass for a free body, whose centre of mass moves
//! in ℝ³. A particle is a point mass: a free body without rotational degrees of freedom.
//!
//! The LGVI needs the nonstandard inertia `J_d = ½ tr(J) I − J` ([LLM07] §3): the kinetic energy
//! is `½ ΩᵀJΩ = ½ tr(Ω^ J_d Ω^ᵀ)`, and `ξ^ J_d + J_d ξ^ = (J ξ)^`. In the principal frame
//! `J_d = diag(J₂ + J₃ − J₁, J₁ + J₃ − J₂, J₁ + J₂ − J₃)/2`, which is positive semidefinite
//! exactly when the principal moments satisfy the triangle inequalities `J₁ ≤ J₂ + J₃` (and
//! cyclic) that every mass distribution does ([MR99] §15.2); equality is a flat body.
//!
//! [LLM07]: crate#references
//! [MR99]: crate#references

use super::so3::{Mat3, Vec3};
use crate::error::{Error, InputError};

/// Relative tolerance of the symmetry and triangle-inequality checks (round-off of typed input).
const CHECK_TOLERANCE: f64 = 1e-12;

/// Which principal moments an inertia accepts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Moments {
    /// Those of a mass distribution: positive, satisfying the triangle inequalities.
    Physical,
    /// Any positive moments (test problems of Euler's equations).
    Any,
}

/// A validated inertia tensor `J` with what the step needs: `J⁻¹` and `J_d = ½ tr(J) I − J`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inertia {
    matrix: Mat3,
    inverse: Mat3,
    nonstandard: Mat3,
    principal: Vec3,
}

impl Inertia {
    /// The inertia with principal moments `(J₁, J₂, J₃)` along the body axes,
    /// `J = diag(J₁, J₂, J₃)`.
    ///
    /// # Errors
    /// [`InputError::InvalidInertia`] unless all are positive and satisfy the triangle
    /// inequalities; [`InputError::NonFinite`] for a non-finite moment.
    pub fn principal(moments: [f64; 3]) -> Result<Self, Error> {
        Self::matrix(&[
            moments[0], 0.0, 0.0, //
            0.0, moments[1], 0.0, //
            0.0, 0.0, moments[2],
        ])
    }

    /// The inertia of a symmetric 3×3 matrix given row-major.
    ///
    /// # Errors
    /// [`InputError::InvalidInertia`] (with the matrix and its eigenvalues) unless the matrix is
    /// symmetric (to 1e-12 relative), positive definite, and its eigenvalues satisfy the
    /// triangle inequalities; [`InputError::NonFinite`] for a non-finite entry.
    pub fn matrix(rows: &[f64; 9]) -> Result<Self, Error> {
        Self::validated(0, rows, Moments::Physical)
    }

    /// [`Inertia::principal`] without the triangle inequalities: any positive definite `J`, such
    /// as the test body `J = diag(2, 1, 2/3)` of [HLW06] §VII.5 (R19), which no mass distribution
    /// has (`2 > 1 + 2/3`). Euler's equations are well posed for it; `J_d` is indefinite, so the
    /// discrete Lagrangian is not convex, but the step's Cayley equation stays regular for small
    /// `h|Ω|`.
    ///
    /// # Errors
    /// [`InputError::InvalidInertia`] unless all are positive; [`InputError::NonFinite`].
    ///
    /// [HLW06]: crate#references
    pub fn principal_unphysical(moments: [f64; 3]) -> Result<Self, Error> {
        let rows = [
            moments[0], 0.0, 0.0, //
            0.0, moments[1], 0.0, //
            0.0, 0.0, moments[2],
        ];
        Self::validated(0, &rows, Moments::Any)
    }

    /// The inertia of body number `body` (the index reported in errors) from a symmetric matrix,
    /// with or without the triangle inequalities.
    ///
    /// # Errors
    /// As [`Inertia::matrix`].
    pub fn validated(body: usize, rows: &[f64; 9], moments: Moments) -> Result<Self, Error> {
        Error::check_finite("inertia", rows)?;
        let matrix = Mat3::from_row_slice(rows);
        let scale = matrix.amax();
        let invalid = |reason: String, principal: [f64; 3]| {
            Error::Input(InputError::InvalidInertia {
                body,
                reason,
                matrix: rows.to_vec(),
                principal,
            })
        };
        let asymmetry = (matrix - matrix.transpose()).amax();
        if asymmetry > CHECK_TOLERANCE * scale {
            return Err(invalid(
                format!("not symmetric: max |J − Jᵀ| = {asymmetry:.3e}"),
                [f64::NAN; 3],
            ));
        }
        let mut eigen: Vec<f64> = matrix.symmetric_eigenvalues().iter().copied().collect();
        eigen.sort_by(f64::total_cmp);
        let principal = [eigen[0], eigen[1], eigen[2]];
        if principal[0] <= 0.0 {
            return Err(invalid(
                format!(
                    "not positive definite: smallest principal moment {}",
                    principal[0]
                ),
                principal,
            ));
        }
        // Sorted ascending, the only inequality that can fail is J₃ ≤ J₁ + J₂.
        let excess = principal[2] - principal[0] - principal[1];
        if moments == Moments::Physical && excess > CHECK_TOLERANCE * principal[2] {
            return Err(invalid(
                format!(
                    "the principal moments violate the triangle inequality: {} > {} + {} \
                     (no mass distribution has them)",
                    principal[2], principal[0], principal[1]
                ),
                principal,
            ));
        }
        let inverse = matrix
            .try_inverse()
            .ok_or_else(|| invalid("singular (not positive definite)".into(), principal))?;
        let nonstandard = 0.5 * matrix.trace() * Mat3::identity() - matrix;
        Ok(Self {
            matrix,
            inverse,
            nonstandard,
            principal: Vec3::from(principal),
        })
    }

    /// `J`.
    pub fn tensor(&self) -> &Mat3 {
        &self.matrix
    }

    /// `J⁻¹` (so `Ω = J⁻¹Π`).
    pub fn inverse(&self) -> &Mat3 {
        &self.inverse
    }

    /// `J_d = ½ tr(J) I − J`, the nonstandard inertia of the discrete Lagrangian.
    pub fn nonstandard(&self) -> &Mat3 {
        &self.nonstandard
    }

    /// The principal moments (eigenvalues of `J`), ascending.
    pub fn principal_moments(&self) -> &Vec3 {
        &self.principal
    }

    /// The inertia of a point mass: `J = 0`, and `J⁻¹ = 0` on its (zero) angular momentum, so its
    /// rotational kinetic energy `½ΠᵀJ⁻¹Π` and angular velocity vanish ([`RigidBody::particle`]).
    pub fn point() -> Self {
        Self {
            matrix: Mat3::zeros(),
            inverse: Mat3::zeros(),
            nonstandard: Mat3::zeros(),
            principal: Vec3::zeros(),
        }
    }
}

/// A rigid body: an inertia, and a mass when the body is free (its centre of mass `x ∈ ℝ³` moves
/// with momentum `p = m ẋ`); without a mass it turns about a fixed point. A particle has a mass
/// and no attitude to speak of: its configuration space is ℝ³.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidBody {
    /// The inertia tensor (about the fixed point, or the centre of mass for a free body;
    /// [`Inertia::point`] for a particle).
    pub inertia: Inertia,
    /// The mass of a free body or particle; `None` for a body with a fixed point.
    pub mass: Option<f64>,
    /// A point mass: its attitude stays `I` and its angular momentum 0; loads on it act at its
    /// position, so they have no moment.
    pub particle: bool,
}

impl RigidBody {
    /// A body turning about a fixed point (configuration space SO(3)).
    pub fn fixed_point(inertia: Inertia) -> Self {
        Self {
            inertia,
            mass: None,
            particle: false,
        }
    }

    /// A free body of mass `mass` (configuration space SO(3) × ℝ³).
    ///
    /// # Errors
    /// [`InputError::InvalidOption`] unless `mass` is positive and finite.
    pub fn free(inertia: Inertia, mass: f64) -> Result<Self, Error> {
        Ok(Self {
            inertia,
            mass: Some(checked_mass(mass)?),
            particle: false,
        })
    }

    /// A particle of mass `mass` (configuration space ℝ³): a point mass among bodies, joined to
    /// them by joints at its position (spherical or distance joints: rows without a moment on
    /// it), pulled by springs and dampers attached there.
    ///
    /// # Errors
    /// As [`RigidBody::free`].
    pub fn particle(mass: f64) -> Result<Self, Error> {
        Ok(Self {
            inertia: Inertia::point(),
            mass: Some(checked_mass(mass)?),
            particle: true,
        })
    }
}

/// `mass` if it is positive and finite.
fn checked_mass(mass: f64) -> Result<f64, Error> {
    if mass.is_finite() && mass > 0.0 {
        Ok(mass)
    } else {
        Err(Error::Input(InputError::InvalidOption {
            name: "mass",
            value: mass,
            reason: "must be positive and finite",
        }))
    }
}
