//! Linear (Rayleigh) damping `f_L(v) = −C v`.
//!
//! The force derived from Rayleigh's dissipation function `R(v) = ½ vᵀ C v` as `f = −∂R/∂v`
//! (Goldstein, *Classical Mechanics*, 3rd ed., §1.5; [MW01] §3.1 uses it as the model dissipative
//! force). For symmetric positive semi-definite `C` the continuous power is `⟨f, v⟩ = −2R ≤ 0`;
//! with the midpoint rule the discrete work `⟨f_d⁻ + f_d⁺, v̄⟩ = −h v̄ᵀCv̄ ≤ 0` is non-positive
//! too, `v̄ = (q_{k+1} − q_k)/h` (reference case R12).
//!
//! [MW01]: crate#references

use crate::error::Error;
use crate::mechanics::Force;
use crate::scalar::Scalar;

/// The damping coefficients `C`.
#[derive(Debug, Clone, PartialEq)]
enum Coefficients {
    /// `C = c I`.
    Uniform(f64),
    /// `C = diag(c)`.
    Diagonal(Vec<f64>),
    /// A full `n × n` matrix, row-major.
    Matrix { n: usize, c: Vec<f64> },
}

/// Linear damping `f_L(t, q, v) = −C v` with a scalar, diagonal or full matrix `C`.
///
/// ```
/// use marsden::{Force, forces::LinearDamping};
///
/// let damping = LinearDamping::uniform(0.5).unwrap();
/// let mut f = [0.0; 2];
/// damping.force(0.0, &[1.0, 2.0], &[3.0, -4.0], &mut f);
/// assert_eq!(f, [-1.5, 2.0]);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct LinearDamping {
    coefficients: Coefficients,
}

impl LinearDamping {
    /// `C = c I` (every coordinate damped with the same coefficient `c`).
    pub fn uniform(c: f64) -> Result<Self, Error> {
        Error::check_finite("damping coefficient", &[c])?;
        Ok(Self {
            coefficients: Coefficients::Uniform(c),
        })
    }

    /// `C = diag(c₁, …, c_n)`.
    pub fn diagonal(c: &[f64]) -> Result<Self, Error> {
        Error::check_finite("damping coefficients", c)?;
        Ok(Self {
            coefficients: Coefficients::Diagonal(c.to_vec()),
        })
    }

    /// A full `n × n` damping matrix given row-major (`c.len() = n²`).
    pub fn matrix(n: usize, c: &[f64]) -> Result<Self, Error> {
        Error::check_len("damping matrix", c, n * n)?;
        Error::check_finite("damping matrix", c)?;
        Ok(Self {
            coefficients: Coefficients::Matrix { n, c: c.to_vec() },
        })
    }

    /// Rayleigh's dissipation function `R(v) = ½ vᵀ C v` (the force is `−∂R/∂v`).
    pub fn dissipation(&self, v: &[f64]) -> f64 {
        let mut f = vec![0.0; v.len()];
        self.apply(v, &mut f);
        -0.5 * f.iter().zip(v).map(|(a, b)| a * b).sum::<f64>()
    }

    /// `out = −C v`.
    #[inline]
    fn apply<S: Scalar>(&self, v: &[S], out: &mut [S]) {
        match &self.coefficients {
            Coefficients::Uniform(c) => {
                for (o, &vi) in out.iter_mut().zip(v) {
                    *o = vi * (-c);
                }
            }
            Coefficients::Diagonal(c) => {
                for ((o, &vi), ci) in out.iter_mut().zip(v).zip(c) {
                    *o = vi * (-ci);
                }
            }
            Coefficients::Matrix { n, c } => {
                for (o, row) in out.iter_mut().zip(c.chunks_exact((*n).max(1))) {
                    *o = row
                        .iter()
                        .zip(v)
                        .fold(S::from(0.0), |acc, (&cij, &vj)| acc - vj * cij);
                }
            }
        }
    }
}

impl Force for LinearDamping {
    #[inline]
    fn force<S: Scalar>(&self, _t: S, _q: &[S], v: &[S], out: &mut [S]) {
        self.apply(v, out);
    }

    fn validate(&self, dof: usize) -> Result<(), Error> {
        match &self.coefficients {
            Coefficients::Uniform(_) => Ok(()),
            Coefficients::Diagonal(c) => Error::check_len("damping coefficients", c, dof),
            Coefficients::Matrix { c, .. } => Error::check_len("damping matrix", c, dof * dof),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::InputError;

    #[test]
    fn matrix_damping_is_minus_c_v_and_dissipation_is_half_vcv() {
        let d = LinearDamping::matrix(2, &[2.0, 1.0, 1.0, 3.0]).unwrap();
        let mut f = [0.0; 2];
        d.force(0.0, &[0.0; 2], &[1.0, -1.0], &mut f);
        assert_eq!(f, [-1.0, 2.0]);
        // ½ (2 − 1 − 1 + 3) = 1.5
        assert_eq!(d.dissipation(&[1.0, -1.0]), 1.5);
        assert!(d.validate(2).is_ok());
        assert!(matches!(
            d.validate(3),
            Err(Error::Input(InputError::DimensionMismatch {
                expected: 9,
                ..
            }))
        ));
    }

    #[test]
    fn diagonal_damping_checks_its_length() {
        let d = LinearDamping::diagonal(&[1.0, 0.5]).unwrap();
        let mut f = [0.0; 2];
        d.force(0.0, &[0.0; 2], &[2.0, 2.0], &mut f);
        assert_eq!(f, [-2.0, -1.0]);
        assert!(d.validate(3).is_err());
        assert!(LinearDamping::uniform(f64::NAN).is_err());
        assert!(LinearDamping::matrix(2, &[1.0; 3]).is_err());
    }
}
