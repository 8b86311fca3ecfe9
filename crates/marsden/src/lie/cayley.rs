//! The implicit part of an LGVI step: `F_k` from the momentum equation, by Newton on its Cayley
//! parameters.
//!
//! With `a = hΠ_k + (h²/2)M_k` the discrete Legendre transform of the LGVI reads
//! `a^ = F J_d − J_d Fᵀ` ([LLM07] eq. (23)). Writing `F = cay(f) = (I + f^)(I − f^)⁻¹`,
//! multiplying by `(I − f^)` on the left and `(I + f^)` on the right, and using
//! `f^ J_d + J_d f^ = (Jf)^` and `f^ a^ f^ = −(a·f) f^`, it becomes three equations
//! ([LLM05] eq. (16)):
//!
//! ```text
//! φ(f) = a + a × f + (a·f) f − 2 J f = 0,       ∂φ/∂f = a^ + (a·f) I + f aᵀ − 2J,
//! ```
//!
//! started from the solution of the linear part, `(2J − a^) f₀ = a`, and stopped by the crate's
//! one rule ([`Convergence`]): residual `‖φ‖∞ ≤ tol · ‖a‖∞`, or an update at round-off relative to
//! `max(1, ‖f‖∞)`. For `h|Ω|` small it converges in two or three iterations.
//!
//! [LLM05]: crate#references
//! [LLM07]: crate#references

use super::so3::{Mat3, Vec3, hat};
use crate::numerics::newton::{Convergence, NewtonFailure, NewtonOptions, NewtonReport};

/// The residual `φ(f)` and its Jacobian.
#[inline(always)]
fn residual(j: &Mat3, a: &Vec3, f: &Vec3) -> (Vec3, Mat3) {
    let af = a.dot(f);
    let phi = a + a.cross(f) + af * f - 2.0 * (j * f);
    let jacobian = hat(a) + Mat3::from_diagonal_element(af) + f * a.transpose() - 2.0 * j;
    (phi, jacobian)
}

/// `m⁻¹ b` by the closed-form inverse of a 3×3 matrix (its adjugate over its determinant, as
/// the hand-written C step does): a third of the instructions of a pivoted LU for this size,
/// and as accurate for the well-conditioned Jacobians of small steps (`2J` plus `O(h)`).
/// `None` for a zero or non-finite determinant.
#[inline(always)]
fn solve3(m: &Mat3, b: &Vec3) -> Option<Vec3> {
    let inverse = m.try_inverse()?;
    let x = inverse * b;
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// Solves `a + a × f + (a·f) f − 2Jf = 0` for the Cayley parameters `f` of `F_k`.
///
/// # Errors
/// The [`NewtonFailure`] of the iteration: a singular Jacobian (`pivot` = its determinant), a
/// non-finite residual, or the budget spent (with the last residual).
pub fn solve_cayley(
    j: &Mat3,
    a: &Vec3,
    options: &NewtonOptions,
) -> Result<(Vec3, NewtonReport), NewtonFailure> {
    let linear = 2.0 * j - hat(a);
    let mut f = solve3(&linear, a).ok_or(NewtonFailure::Singular {
        iteration: 0,
        pivot: linear.determinant(),
    })?;
    let scale = a.amax();
    let mut convergence = Convergence::new(options);
    let mut report = NewtonReport::default();
    let (mut phi, mut jacobian) = residual(j, a, &f);
    report.evaluations = 1;
    loop {
        report.residual = phi.amax();
        if convergence.check(&report, scale)? {
            return Ok((f, report));
        }
        let update = solve3(&jacobian, &-phi).ok_or(NewtonFailure::Singular {
            iteration: report.iterations,
            pivot: jacobian.determinant(),
        })?;
        f += update;
        report.iterations += 1;
        report.factorizations += 1;
        (phi, jacobian) = residual(j, a, &f);
        report.evaluations += 1;
        convergence.record_update(update.amax(), f.amax().max(1.0));
    }
}
