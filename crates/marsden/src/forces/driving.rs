//! Driving forces that depend on time only: constant `f = F` and periodic
//! `f_i(t) = A_i cos(ω_i t + φ_i)`.
//!
//! A force independent of `(q, v)` adds nothing to the Newton Jacobian of a step; the rules
//! sample it at their quadrature times (midpoint: `f_d^± = (h/2) f(t_k + h/2)`; trapezoid:
//! `f_d⁻ = (h/2) f(t_k)`, `f_d⁺ = (h/2) f(t_{k+1})`). A constant force is equivalent to adding the
//! potential `−⟨F, q⟩` to `L`, and every rule then integrates it exactly (reference case R9).

use crate::error::Error;
use crate::error::InputError;
use crate::mechanics::Force;
use crate::scalar::Scalar;

/// A constant generalised force `f_L = F` (e.g. a uniform field, a fixed load).
///
/// ```
/// use marsden::{Force, forces::ConstantForce};
///
/// let load = ConstantForce::new(&[0.0, -9.81]).unwrap();
/// let mut f = [1.0; 2];
/// load.force(0.3, &[0.0; 2], &[0.0; 2], &mut f);
/// assert_eq!(f, [0.0, -9.81]);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ConstantForce {
    value: Vec<f64>,
}

impl ConstantForce {
    /// The force `F` (one component per coordinate).
    pub fn new(value: &[f64]) -> Result<Self, Error> {
        Error::check_finite("constant force", value)?;
        Ok(Self {
            value: value.to_vec(),
        })
    }

    /// The force `F`.
    pub fn value(&self) -> &[f64] {
        &self.value
    }
}

impl Force for ConstantForce {
    #[inline]
    fn force<S: Scalar>(&self, _t: S, _q: &[S], _v: &[S], out: &mut [S]) {
        for (o, &f) in out.iter_mut().zip(&self.value) {
            *o = S::from(f);
        }
    }

    fn validate(&self, dof: usize) -> Result<(), Error> {
        Error::check_len("constant force", &self.value, dof)
    }
}

/// Time-periodic driving, one harmonic per coordinate: `f_i(t) = A_i cos(ω_i t + φ_i)`.
///
/// Coordinates with `A_i = 0` are undriven. The classical driven pendulum
/// `θ̈ + θ̇/Q + sin θ = A cos(ω t)` (Baker & Gollub, *Chaotic Dynamics*, 2nd ed., ch. 3) uses
/// [`PeriodicForce::on`]`(0, 1, A, ω, 0)` together with [`crate::forces::LinearDamping`].
///
/// ```
/// use marsden::{Force, forces::PeriodicForce};
///
/// let drive = PeriodicForce::on(1, 2, 2.0, std::f64::consts::PI, 0.0).unwrap();
/// let mut f = [9.0; 2];
/// drive.force(1.0, &[0.0; 2], &[0.0; 2], &mut f);
/// assert_eq!(f, [0.0, -2.0]);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct PeriodicForce {
    amplitude: Vec<f64>,
    omega: Vec<f64>,
    phase: Vec<f64>,
}

impl PeriodicForce {
    /// Amplitudes `A_i`, angular frequencies `ω_i` and phases `φ_i` (all of length n).
    pub fn new(amplitude: &[f64], omega: &[f64], phase: &[f64]) -> Result<Self, Error> {
        Error::check_len("driving frequencies", omega, amplitude.len())?;
        Error::check_len("driving phases", phase, amplitude.len())?;
        for (what, x) in [
            ("driving amplitudes", amplitude),
            ("driving frequencies", omega),
            ("driving phases", phase),
        ] {
            Error::check_finite(what, x)?;
        }
        Ok(Self {
            amplitude: amplitude.to_vec(),
            omega: omega.to_vec(),
            phase: phase.to_vec(),
        })
    }

    /// Drives only coordinate `index` of an `n`-coordinate system with `A cos(ω t + φ)`.
    pub fn on(
        index: usize,
        n: usize,
        amplitude: f64,
        omega: f64,
        phase: f64,
    ) -> Result<Self, Error> {
        if index >= n {
            return Err(Error::Input(InputError::DimensionMismatch {
                what: "driven coordinate index (as a length)",
                expected: n,
                found: index + 1,
            }));
        }
        let mut a = vec![0.0; n];
        a[index] = amplitude;
        Self::new(&a, &vec![omega; n], &vec![phase; n])
    }

    /// The force at time `t` (plain `f64`).
    pub fn at(&self, t: f64, out: &mut [f64]) {
        self.force(t, &[], &[], out);
    }
}

impl Force for PeriodicForce {
    #[inline]
    fn force<S: Scalar>(&self, t: S, _q: &[S], _v: &[S], out: &mut [S]) {
        let coefficients = self.amplitude.iter().zip(&self.omega).zip(&self.phase);
        for (o, ((&a, &w), &phi)) in out.iter_mut().zip(coefficients) {
            *o = if a == 0.0 {
                S::from(0.0)
            } else {
                (t * w + phi).cos() * a
            };
        }
    }

    fn validate(&self, dof: usize) -> Result<(), Error> {
        Error::check_len("driving amplitudes", &self.amplitude, dof)
    }
}
