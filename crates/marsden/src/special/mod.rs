//! Special functions and exact reference solutions.
//!
//! The test-suite and the catalog compare the integrators against *known answers*; this module
//! provides them in plain `f64`, with no dependency beyond `std`:
//!
//! * [`elliptic`]: complete and incomplete elliptic integrals (`K`, `E`, `F`, Carlson's `R_F`)
//!   and the Jacobi elliptic functions `sn`, `cn`, `dn`, `am`;
//! * [`pendulum`]: the exact motion of the planar pendulum `θ̈ = −ω² sin θ` (libration,
//!   separatrix and rotation);
//! * [`kepler`]: Kepler's equation and the exact propagation of bound two-body orbits;
//! * [`oscillator`]: the harmonic and the damped harmonic oscillator;
//! * [`euler_top`]: the free asymmetric rigid body (Euler's equations) by elliptic functions.
//!
//! Every fallible routine returns [`SpecialError`] for invalid input (non-finite numbers,
//! parameters outside the domain, unbound or degenerate orbits) instead of panicking.

pub mod elliptic;
pub mod euler_top;
pub mod kepler;
pub mod oscillator;
pub mod pendulum;

/// Why a special function or an exact solution could not be evaluated.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SpecialError {
    /// An argument is NaN or infinite.
    #[error("argument `{name}` is not finite ({value})")]
    NotFinite {
        /// Name of the offending argument.
        name: &'static str,
        /// Its value.
        value: f64,
    },
    /// An argument is finite but outside the domain of the function.
    #[error("argument `{name}` = {value} is outside the domain: {expected}")]
    Domain {
        /// Name of the offending argument.
        name: &'static str,
        /// Its value.
        value: f64,
        /// The domain that was expected, in words.
        expected: &'static str,
    },
    /// The two-body initial data have non-negative energy (parabolic or hyperbolic orbit).
    #[error("orbit is not bound: energy {energy} >= 0")]
    Unbound {
        /// The energy `|p|²/2 − μ/|q|` of the initial data.
        energy: f64,
    },
    /// The initial data describe a degenerate motion the solution does not cover.
    #[error("degenerate motion: {0}")]
    Degenerate(&'static str),
    /// An iteration that converges in exact arithmetic stopped before convergence.
    #[error("iteration did not converge: {0}")]
    NoConvergence(&'static str),
}

/// Fail with [`SpecialError::NotFinite`] unless `value` is finite.
pub(crate) fn finite(name: &'static str, value: f64) -> Result<f64, SpecialError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(SpecialError::NotFinite { name, value })
    }
}

/// Fail with [`SpecialError::Domain`] unless `ok` holds.
pub(crate) fn domain(
    ok: bool,
    name: &'static str,
    value: f64,
    expected: &'static str,
) -> Result<(), SpecialError> {
    if ok {
        Ok(())
    } else {
        Err(SpecialError::Domain {
            name,
            value,
            expected,
        })
    }
}

/// `(-1)^j` for an integer-valued `j` (exact for `|j| < 2^53`).
pub(crate) fn parity_sign(j: f64) -> f64 {
    if j.rem_euclid(2.0) == 0.0 { 1.0 } else { -1.0 }
}
