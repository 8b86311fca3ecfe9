//! Exact motion of the planar mathematical pendulum `θ̈ = −ω² sin θ` (`ω² = g/l`).
//!
//! With the energy `H = θ̇²/2 − ω² cos θ`, the *modulus* `k` of the motion is
//!
//! ```text
//! k² = sin²(θ₀/2) + θ̇₀²/(4ω²) = (H + ω²)/(2ω²),     k'² = 1 − k² = cos²(θ₀/2) − θ̇₀²/(4ω²).
//! ```
//!
//! * **Libration** (`k < 1`): `sin(θ/2) = k sn(ωt + u₀ | k²)`, `θ̇ = 2kω cn(ωt + u₀ | k²)`,
//!   period `4K(k²)/ω` (Lawden, *Elliptic Functions and Applications*, §5.2; DLMF 22.19.i).
//! * **Rotation** (`k > 1`): `θ/2 = ±am(kωt + v₀ | 1/k²)`, `θ̇ = ±2kω dn(kωt + v₀ | 1/k²)`;
//!   `θ` advances by `2π` every `2K(1/k²)/(kω)` (DLMF 22.19.i).
//! * **Separatrix** (`k = 1`): the same formulas at `m = 1`,
//!   `θ/2 = ±gd(ωt + v₀)`, `θ̇ = ±2ω sech(ωt + v₀)`.
//!
//! The phases `u₀`, `v₀` come from the incomplete integral: `u₀ = F(φ₀ | k²)` with
//! `sin φ₀ = sin(θ₀/2)/k`, `cos φ₀ = θ̇₀/(2kω)`, and `v₀ = F(±θ₀/2 | 1/k²)`. The
//! complementary parameter `k'²` is formed as `(cos(θ₀/2) − |w|)(cos(θ₀/2) + |w|)`,
//! `w = θ̇₀/(2ω)`, so motions close to the separatrix keep full accuracy.

use super::elliptic::{ellip_f_m1, ellip_k_m1, jacobi_mm1};
use super::{SpecialError, domain, finite};
use std::f64::consts::TAU;

/// Which of the three kinds of pendulum motion the initial data describe.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PendulumMotion {
    /// Oscillation about the lower equilibrium, `k < 1` (energy below the separatrix).
    Libration,
    /// Motion on the separatrix, `k = 1`: the pendulum creeps towards the upright position.
    Separatrix,
    /// The pendulum goes over the top, `k > 1`; `θ` grows (or decreases) without bound.
    Rotation,
}

/// Period of a librating pendulum of amplitude `θ_max` (`|θ_max| < π`):
/// `T = 4K(k²)/ω` with `k = sin(θ_max/2)` (Lawden §5.2; small amplitudes give `2π/ω`).
///
/// # Errors
/// [`SpecialError::NotFinite`] for non-finite input, [`SpecialError::Domain`] for `ω ≤ 0` or
/// `|θ_max| ≥ π` (no finite period).
///
/// ```
/// use marsden::special::pendulum::period;
/// // θ_max = π/2: T = 4K(½) = 7.416298709205487…
/// assert!((period(std::f64::consts::FRAC_PI_2, 1.0).unwrap() - 7.416_298_709_205_487).abs() < 1e-14);
/// ```
pub fn period(amplitude: f64, omega: f64) -> Result<f64, SpecialError> {
    finite("amplitude", amplitude)?;
    finite("omega", omega)?;
    domain(omega > 0.0, "omega", omega, "omega > 0")?;
    let half = 0.5 * amplitude.abs();
    domain(
        half < std::f64::consts::FRAC_PI_2,
        "amplitude",
        amplitude,
        "|amplitude| < pi",
    )?;
    let c = half.cos();
    Ok(4.0 * ellip_k_m1(c * c) / omega)
}

/// The exact solution of `θ̈ = −ω² sin θ` through the initial data `(θ₀, θ̇₀)` at `t = 0`.
///
/// All three kinds of motion are covered (see the [module documentation](self)); evaluate with
/// [`Pendulum::state`]. For the project's reference case `L = ½q̇² + cos q`, `q₀ = 1.5`,
/// `p₀ = 0`:
///
/// ```
/// use marsden::special::pendulum::Pendulum;
/// let pendulum = Pendulum::new(1.5, 0.0, 1.0).unwrap();
/// let (q, p) = pendulum.state(5.0).unwrap();
/// assert!((q + 0.624_745_744_305_078).abs() < 1e-14);
/// assert!((p - 1.216_860_432_372_502).abs() < 1e-14);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pendulum {
    omega: f64,
    theta0: f64,
    thetadot0: f64,
    motion: PendulumMotion,
    /// `k = √(k²)`, the modulus of the motion.
    modulus: f64,
    /// Parameter and complementary parameter of the Jacobi functions used: `(k², k'²)` for
    /// libration, `(1/k², −k'²/k²)` for rotation and separatrix.
    m: f64,
    m1: f64,
    /// Phase `u₀` (libration) or `v₀` (rotation, separatrix) of the Jacobi argument at `t = 0`.
    phase: f64,
    /// `2πj`, the multiple of `2π` removed from `θ₀` before solving.
    offset: f64,
    /// `±1`: direction of rotation (`+1` for libration).
    direction: f64,
}

impl Pendulum {
    /// Set up the exact solution from `θ(0) = theta0`, `θ̇(0) = thetadot0`, with `ω > 0`.
    ///
    /// `θ₀` may be any real number: it is reduced to `[−π, π]` and the multiple of `2π`
    /// restored in [`state`](Self::state).
    ///
    /// # Errors
    /// [`SpecialError::NotFinite`] for non-finite input, [`SpecialError::Domain`] for `ω ≤ 0`.
    pub fn new(theta0: f64, thetadot0: f64, omega: f64) -> Result<Self, SpecialError> {
        finite("theta0", theta0)?;
        finite("thetadot0", thetadot0)?;
        finite("omega", omega)?;
        domain(omega > 0.0, "omega", omega, "omega > 0")?;
        let j = (theta0 / TAU).round();
        let reduced = (-TAU).mul_add(j, theta0); // |reduced| ≤ π, so cos(reduced/2) > 0
        let (s, c) = (0.5 * reduced).sin_cos();
        let w = thetadot0 / (2.0 * omega);
        let k2 = s.mul_add(s, w * w);
        let kp2 = (c - w.abs()) * (c + w.abs());
        let mut solution = Self {
            omega,
            theta0,
            thetadot0,
            motion: PendulumMotion::Libration,
            modulus: k2.sqrt(),
            m: k2,
            m1: kp2,
            phase: 0.0,
            offset: TAU * j,
            direction: 1.0,
        };
        if kp2 > 0.0 {
            // sn u₀ = s/k, cn u₀ = w/k, so am u₀ = atan2(s, w).
            solution.phase = ellip_f_m1(s.atan2(w), kp2)?;
        } else {
            solution.motion = if kp2 == 0.0 {
                PendulumMotion::Separatrix
            } else {
                PendulumMotion::Rotation
            };
            solution.direction = w.signum();
            solution.m = 1.0 / k2;
            solution.m1 = -kp2 / k2;
            solution.phase = ellip_f_m1(solution.direction * 0.5 * reduced, -kp2 / k2)?;
        }
        Ok(solution)
    }

    /// `(θ(t), θ̇(t))` on the exact solution, for any finite `t` (negative included).
    ///
    /// # Errors
    /// [`SpecialError::NotFinite`] for non-finite `t`.
    pub fn state(&self, t: f64) -> Result<(f64, f64), SpecialError> {
        finite("t", t)?;
        let k = self.modulus;
        let kw = k * self.omega;
        if self.motion == PendulumMotion::Libration {
            let j = jacobi_mm1(self.omega.mul_add(t, self.phase), self.m, self.m1);
            // sin(θ/2) = k sn, cos(θ/2) = dn (since dn² = 1 − k² sn²).
            let theta = 2.0 * (k * j.sn).atan2(j.dn);
            Ok((self.offset + theta, 2.0 * kw * j.cn))
        } else {
            let j = jacobi_mm1(kw.mul_add(t, self.phase), self.m, self.m1);
            let sign = self.direction;
            Ok((self.offset + 2.0 * sign * j.am, 2.0 * sign * kw * j.dn))
        }
    }

    /// Kind of motion: libration, separatrix or rotation.
    pub fn motion(&self) -> PendulumMotion {
        self.motion
    }

    /// The modulus `k = √(sin²(θ₀/2) + θ̇₀²/(4ω²))`; `k < 1` librates, `k > 1` rotates.
    pub fn modulus(&self) -> f64 {
        self.modulus
    }

    /// The frequency `ω` of small oscillations.
    pub fn omega(&self) -> f64 {
        self.omega
    }

    /// The initial data `(θ₀, θ̇₀)`.
    pub fn initial_state(&self) -> (f64, f64) {
        (self.theta0, self.thetadot0)
    }

    /// The conserved energy `H = θ̇²/2 − ω² cos θ` (per unit `m l²`) of the initial data.
    pub fn energy(&self) -> f64 {
        0.5 * self.thetadot0 * self.thetadot0 - self.omega * self.omega * self.theta0.cos()
    }

    /// Period of the motion: `4K(k²)/ω` for libration, `2K(1/k²)/(kω)` for rotation (time for
    /// `θ` to advance by `2π`), `+∞` on the separatrix.
    pub fn period(&self) -> f64 {
        match self.motion {
            PendulumMotion::Libration => 4.0 * ellip_k_m1(self.m1) / self.omega,
            PendulumMotion::Separatrix => f64::INFINITY,
            PendulumMotion::Rotation => 2.0 * ellip_k_m1(self.m1) / (self.modulus * self.omega),
        }
    }
}

#[cfg(test)]
mod tests;
