//! The damped harmonic oscillator `m q̈ = −k q − c q̇`: `L = ½ m v² − ½ k q²` with the Rayleigh
//! damping force `f_L = −c v` (reference case R12).
//!
//! With the midpoint rule and midpoint forces the discrete energy balance is exact:
//! `E_{k+1} − E_k = −c (q_{k+1} − q_k)²/h` (see [`crate::forces`] and R12).

use crate::mechanics::{Force, Lagrangian};
use crate::scalar::Scalar;
use crate::special::SpecialError;
use crate::special::oscillator::DampedOscillator as Exact;

/// Damped oscillator with mass `m`, stiffness `k` and damping `c`; it is both the
/// [`Lagrangian`] and the [`Force`] of the system.
///
/// ```
/// use marsden::{Initial, Midpoint, Problem, SolveOptions, TimeGrid, systems::DampedOscillator};
///
/// let osc = DampedOscillator::default(); // m = k = 1, c = 0.1 (R12)
/// let problem = Problem::new(osc, Initial::momentum(&[1.0], &[0.0]), TimeGrid::new(0.0, 0.1, 10)?)?
///     .with_force(osc);
/// let traj = problem.solve(&Midpoint, &SolveOptions::default())?;
/// assert!((traj.q(10)[0] - 0.55569741018856952).abs() < 1e-12);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DampedOscillator {
    /// Mass (default 1).
    pub m: f64,
    /// Stiffness (default 1).
    pub k: f64,
    /// Damping coefficient (default 0.1: damping ratio ζ = c/(2√(km)) = 0.05).
    pub c: f64,
}

impl Default for DampedOscillator {
    fn default() -> Self {
        Self {
            m: 1.0,
            k: 1.0,
            c: 0.1,
        }
    }
}

impl DampedOscillator {
    /// Energy `p²/2m + k q²/2`.
    pub fn energy(&self, q: f64, p: f64) -> f64 {
        0.5 * p * p / self.m + 0.5 * self.k * q * q
    }

    /// The exact solution through `(q₀, p₀)` at `t = 0`
    /// ([`crate::special::oscillator::DampedOscillator`]).
    pub fn exact(&self, q0: f64, p0: f64) -> Result<Exact, SpecialError> {
        Exact::new(self.m, self.k, self.c, q0, p0)
    }
}

impl Lagrangian for DampedOscillator {
    const FIXED_DOF: Option<usize> = Some(1);
    fn dof(&self) -> usize {
        1
    }
    #[inline(always)]
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        (v[0] * v[0] * self.m - q[0] * q[0] * self.k) * 0.5
    }
}

impl Force for DampedOscillator {
    #[inline(always)]
    fn force<S: Scalar>(&self, _t: S, _q: &[S], v: &[S], out: &mut [S]) {
        out[0] = v[0] * (-self.c);
    }
    fn validate(&self, dof: usize) -> Result<(), crate::error::Error> {
        crate::error::Error::check_len("damped oscillator force (dof)", &[0.0], dof)
    }
}
