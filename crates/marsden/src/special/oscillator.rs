//! Exact solutions of the harmonic oscillator `m q̈ = −k q` and of the damped oscillator
//! `m q̈ = −k q − c q̇`, in the phase-space variables `(q, p)` with `p = m q̇`.
//!
//! With `ω₀² = k/m`, `γ = c/(2m)`, `v = p/m`, the solution of the damped equation is
//! (e.g. Goldstein, *Classical Mechanics*, §2; Landau–Lifshitz vol. 1, §25)
//!
//! ```text
//! q(t) = e^{−γt} [ q₀ C(t) + (v₀ + γq₀) S(t) ],
//! v(t) = e^{−γt} [ v₀ C(t) − (γv₀ + ω₀²q₀) S(t) ],
//! ```
//!
//! where `C = cos ω_d t`, `S = sin(ω_d t)/ω_d` with `ω_d = √(ω₀² − γ²)` when underdamped,
//! `C = 1`, `S = t` when critically damped, and `C = cosh λt`, `S = sinh(λt)/λ` with
//! `λ = √(γ² − ω₀²)` when overdamped. `γ = 0` gives the harmonic oscillator.

use super::{SpecialError, domain, finite};
use std::f64::consts::TAU;

/// Check `mass > 0`, `stiffness > 0`, and finite initial data.
fn check_common(mass: f64, stiffness: f64, q0: f64, p0: f64) -> Result<(), SpecialError> {
    finite("mass", mass)?;
    finite("stiffness", stiffness)?;
    finite("q0", q0)?;
    finite("p0", p0)?;
    domain(mass > 0.0, "mass", mass, "mass > 0")?;
    domain(stiffness > 0.0, "stiffness", stiffness, "stiffness > 0")
}

/// The exact solution of `m q̈ = −k q` through `(q₀, p₀)`, `p = m q̇`:
/// `q = q₀ cos ωt + p₀/(mω) sin ωt`, `p = p₀ cos ωt − mω q₀ sin ωt`, `ω = √(k/m)`.
///
/// ```
/// use marsden::special::oscillator::HarmonicOscillator;
/// let osc = HarmonicOscillator::new(1.0, 1.0, 1.0, 0.0).unwrap();
/// let (q, p) = osc.state(std::f64::consts::FRAC_PI_2).unwrap();
/// assert!(q.abs() < 1e-16 && (p + 1.0).abs() < 1e-16);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HarmonicOscillator {
    mass: f64,
    stiffness: f64,
    q0: f64,
    p0: f64,
    omega: f64,
}

impl HarmonicOscillator {
    /// Set up the solution for mass `m > 0`, stiffness `k > 0` and initial data `(q₀, p₀)`.
    ///
    /// # Errors
    /// [`SpecialError::NotFinite`] for non-finite input, [`SpecialError::Domain`] for
    /// `m ≤ 0` or `k ≤ 0`.
    pub fn new(mass: f64, stiffness: f64, q0: f64, p0: f64) -> Result<Self, SpecialError> {
        check_common(mass, stiffness, q0, p0)?;
        Ok(Self {
            mass,
            stiffness,
            q0,
            p0,
            omega: (stiffness / mass).sqrt(),
        })
    }

    /// `(q(t), p(t))` for any finite `t`.
    ///
    /// # Errors
    /// [`SpecialError::NotFinite`] for non-finite `t`.
    pub fn state(&self, t: f64) -> Result<(f64, f64), SpecialError> {
        finite("t", t)?;
        let (s, c) = (self.omega * t).sin_cos();
        let mw = self.mass * self.omega;
        Ok((
            self.q0.mul_add(c, self.p0 / mw * s),
            self.p0.mul_add(c, -mw * self.q0 * s),
        ))
    }

    /// Angular frequency `ω = √(k/m)`.
    pub fn omega(&self) -> f64 {
        self.omega
    }

    /// Period `2π/ω`.
    pub fn period(&self) -> f64 {
        TAU / self.omega
    }

    /// The conserved energy `p²/(2m) + k q²/2`.
    pub fn energy(&self) -> f64 {
        0.5 * (self.p0 * self.p0 / self.mass + self.stiffness * self.q0 * self.q0)
    }
}

/// The three regimes of the damped oscillator, by the sign of `ω₀² − γ²`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DampingRegime {
    /// `γ < ω₀`: decaying oscillation with frequency `ω_d = √(ω₀² − γ²)`.
    Underdamped,
    /// `γ = ω₀`: fastest non-oscillating decay, `q = e^{−γt}(q₀ + (v₀ + γq₀)t)`.
    CriticallyDamped,
    /// `γ > ω₀`: sum of two decaying exponentials with rates `γ ± √(γ² − ω₀²)`.
    Overdamped,
}

/// The exact solution of `m q̈ = −k q − c q̇` through `(q₀, p₀)`, `p = m q̇`, in all three
/// regimes (see the [module documentation](self)).
///
/// Reference case `m = k = 1`, `c = 0.1`, `q₀ = 1`, `p₀ = 0`:
///
/// ```
/// use marsden::special::oscillator::DampedOscillator;
/// let osc = DampedOscillator::new(1.0, 1.0, 0.1, 1.0, 0.0).unwrap();
/// let (q, p) = osc.state(1.0).unwrap();
/// assert!((q - 0.554_991_720_617_898_3).abs() < 1e-15);
/// assert!((p + 0.800_790_107_353_309_4).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DampedOscillator {
    mass: f64,
    stiffness: f64,
    damping: f64,
    q0: f64,
    p0: f64,
    /// `γ = c/(2m)`.
    gamma: f64,
    /// `ω₀² = k/m`.
    omega0_sq: f64,
    regime: DampingRegime,
    /// `ω_d` (underdamped), `λ` (overdamped) or 0 (critical).
    frequency: f64,
}

impl DampedOscillator {
    /// Set up the solution for mass `m > 0`, stiffness `k > 0`, damping `c ≥ 0` and initial
    /// data `(q₀, p₀)`.
    ///
    /// # Errors
    /// [`SpecialError::NotFinite`] for non-finite input, [`SpecialError::Domain`] for
    /// `m ≤ 0`, `k ≤ 0` or `c < 0`.
    pub fn new(
        mass: f64,
        stiffness: f64,
        damping: f64,
        q0: f64,
        p0: f64,
    ) -> Result<Self, SpecialError> {
        check_common(mass, stiffness, q0, p0)?;
        finite("damping", damping)?;
        domain(damping >= 0.0, "damping", damping, "damping >= 0")?;
        let gamma = damping / (2.0 * mass);
        let omega0_sq = stiffness / mass;
        let omega0 = omega0_sq.sqrt();
        // ω₀² − γ² as a product: exact cancellation when γ ≈ ω₀.
        let discriminant = (omega0 - gamma) * (omega0 + gamma);
        let (regime, frequency) = if discriminant > 0.0 {
            (DampingRegime::Underdamped, discriminant.sqrt())
        } else if discriminant < 0.0 {
            (DampingRegime::Overdamped, (-discriminant).sqrt())
        } else {
            (DampingRegime::CriticallyDamped, 0.0)
        };
        Ok(Self {
            mass,
            stiffness,
            damping,
            q0,
            p0,
            gamma,
            omega0_sq,
            regime,
            frequency,
        })
    }

    /// `(q(t), p(t))` for any finite `t` (for very negative `t` the exponential growth may
    /// overflow to infinity).
    ///
    /// # Errors
    /// [`SpecialError::NotFinite`] for non-finite `t`.
    pub fn state(&self, t: f64) -> Result<(f64, f64), SpecialError> {
        finite("t", t)?;
        let (ec, es) = self.propagators(t);
        let (g, v0) = (self.gamma, self.p0 / self.mass);
        let q = self.q0 * ec + g.mul_add(self.q0, v0) * es;
        let v = v0 * ec - g.mul_add(v0, self.omega0_sq * self.q0) * es;
        Ok((q, self.mass * v))
    }

    /// `(e^{−γt} C(t), e^{−γt} S(t))`, evaluated without intermediate overflow.
    fn propagators(&self, t: f64) -> (f64, f64) {
        let (g, w) = (self.gamma, self.frequency);
        match self.regime {
            DampingRegime::Underdamped => {
                let decay = (-g * t).exp();
                let (s, c) = (w * t).sin_cos();
                (decay * c, decay * s / w)
            }
            DampingRegime::CriticallyDamped => {
                let decay = (-g * t).exp();
                (decay, decay * t)
            }
            DampingRegime::Overdamped if (w * t).abs() < 1.0 => {
                let decay = (-g * t).exp();
                (decay * (w * t).cosh(), decay * (w * t).sinh() / w)
            }
            DampingRegime::Overdamped => {
                // Rates γ ∓ λ; the slow one as ω₀²/(γ + λ) to avoid cancellation.
                let slow = (-self.omega0_sq / (g + w) * t).exp();
                let fast = (-(g + w) * t).exp();
                (0.5 * (slow + fast), 0.5 * (slow - fast) / w)
            }
        }
    }

    /// The damping regime.
    pub fn regime(&self) -> DampingRegime {
        self.regime
    }

    /// Decay rate `γ = c/(2m)` of the envelope.
    pub fn decay_rate(&self) -> f64 {
        self.gamma
    }

    /// Damped angular frequency `ω_d = √(ω₀² − γ²)` if underdamped, else `None`.
    pub fn damped_frequency(&self) -> Option<f64> {
        (self.regime == DampingRegime::Underdamped).then_some(self.frequency)
    }

    /// Undamped angular frequency `ω₀ = √(k/m)`.
    pub fn natural_frequency(&self) -> f64 {
        self.omega0_sq.sqrt()
    }

    /// Mechanical energy `p²/(2m) + k q²/2` at `(q, p)`; along the solution it decreases at the
    /// rate `dE/dt = −c q̇²`.
    pub fn energy_at(&self, q: f64, p: f64) -> f64 {
        0.5 * (p * p / self.mass + self.stiffness * q * q)
    }

    /// The damping coefficient `c`.
    pub fn damping(&self) -> f64 {
        self.damping
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * b.abs().max(1.0)
    }

    #[test]
    fn project_reference_values() {
        let osc = DampedOscillator::new(1.0, 1.0, 0.1, 1.0, 0.0).unwrap();
        assert_eq!(osc.regime(), DampingRegime::Underdamped);
        let cases = [
            (0.1, 0.9950207737420776, -0.099_335_909_578_646_85),
            (1.0, 0.554_991_720_617_898_4, -0.800_790_107_353_309_4),
            (10.0, -0.529_208_818_907_019_8, 0.32397955310035503),
            (100.0, 0.005_133_470_375_040_278, 0.004_115_201_704_341_301),
        ];
        for (t, q, p) in cases {
            let (qt, pt) = osc.state(t).unwrap();
            assert!((qt - q).abs() < 2e-16 * t.max(1.0), "t={t}: {qt} vs {q}");
            assert!((pt - p).abs() < 2e-16 * t.max(1.0), "t={t}: {pt} vs {p}");
        }
    }

    #[test]
    fn harmonic_oscillator() {
        let osc = HarmonicOscillator::new(2.0, 8.0, 0.5, -1.0).unwrap();
        assert_eq!(osc.omega(), 2.0);
        let energy = osc.energy();
        for t in [0.0, 0.3, 2.0, -5.0] {
            let (q, p) = osc.state(t).unwrap();
            let expected_q = 0.5 * (2.0 * t).cos() - 0.25 * (2.0 * t).sin();
            assert!(
                close(q, expected_q, 1e-15)
                    && close(
                        p,
                        2.0 * (-2.0) * 0.5 * (2.0 * t).sin() - (2.0 * t).cos(),
                        1e-15
                    )
            );
            assert!(close(0.25 * p * p + 4.0 * q * q, energy, 1e-15));
        }
        let (q, p) = osc.state(osc.period()).unwrap();
        assert!(close(q, 0.5, 1e-15) && close(p, -1.0, 1e-15));
        // Zero damping reduces to the harmonic oscillator.
        let undamped = DampedOscillator::new(2.0, 8.0, 0.0, 0.5, -1.0).unwrap();
        for t in [0.7, 9.0] {
            let (a, b) = (osc.state(t).unwrap(), undamped.state(t).unwrap());
            assert!(close(a.0, b.0, 1e-15) && close(a.1, b.1, 1e-15));
        }
    }

    #[test]
    fn all_regimes_solve_the_equation_and_dissipate() {
        let h = 1e-5;
        for c in [0.3, 3.9, 4.0, 4.1, 25.0] {
            let osc = DampedOscillator::new(2.0, 2.0, c, 0.7, 1.3).unwrap();
            let (q0, p0) = osc.state(0.0).unwrap();
            assert!(close(q0, 0.7, 1e-15) && close(p0, 1.3, 1e-15), "c={c}");
            for t in [-0.5, 0.2, 3.0, 8.0] {
                let at = |s: f64| osc.state(s).unwrap();
                let ((q, p), (qp, pp), (qm, pm)) = (at(t), at(t + h), at(t - h));
                let v = p / 2.0;
                assert!(close((qp - qm) / (2.0 * h), v, 1e-7), "c={c}, t={t}");
                assert!(
                    close((pp - pm) / (2.0 * h), -2.0 * q - c * v, 1e-7),
                    "c={c}, t={t}"
                );
                let de = (osc.energy_at(qp, pp) - osc.energy_at(qm, pm)) / (2.0 * h);
                assert!(close(de, -c * v * v, 1e-7), "c={c}, t={t}");
            }
        }
    }

    #[test]
    fn regimes_are_continuous_across_critical_damping() {
        let critical = DampedOscillator::new(1.0, 1.0, 2.0, 1.0, -0.4).unwrap();
        assert_eq!(critical.regime(), DampingRegime::CriticallyDamped);
        let under = DampedOscillator::new(1.0, 1.0, 2.0 - 1e-9, 1.0, -0.4).unwrap();
        let over = DampedOscillator::new(1.0, 1.0, 2.0 + 1e-9, 1.0, -0.4).unwrap();
        assert_eq!(under.regime(), DampingRegime::Underdamped);
        assert_eq!(over.regime(), DampingRegime::Overdamped);
        for t in [0.5, 3.0, 40.0] {
            let (a, b, c) = (under.state(t), critical.state(t), over.state(t));
            let (a, b, c) = (a.unwrap(), b.unwrap(), c.unwrap());
            assert!(close(b.0, (-t).exp() * (1.0 + 0.6 * t), 1e-14));
            assert!(close(a.0, b.0, 1e-7) && close(c.0, b.0, 1e-7), "t={t}");
            assert!(close(a.1, b.1, 1e-7) && close(c.1, b.1, 1e-7), "t={t}");
        }
        // Heavily overdamped, long times: no overflow, slow mode e^{−(k/c)t} dominates.
        let heavy = DampedOscillator::new(1.0, 1.0, 1e3, 1.0, 0.0).unwrap();
        let (q, _) = heavy.state(2e3).unwrap();
        assert!(q.is_finite() && close(q, (-2.0_f64).exp(), 1e-5), "{q}");
    }

    #[test]
    fn invalid_input_is_an_error() {
        assert!(HarmonicOscillator::new(0.0, 1.0, 1.0, 0.0).is_err());
        assert!(HarmonicOscillator::new(1.0, -1.0, 1.0, 0.0).is_err());
        assert!(HarmonicOscillator::new(1.0, 1.0, f64::NAN, 0.0).is_err());
        assert!(DampedOscillator::new(1.0, 1.0, -0.1, 1.0, 0.0).is_err());
        assert!(
            DampedOscillator::new(1.0, 1.0, 0.1, 1.0, 0.0)
                .unwrap()
                .state(f64::NAN)
                .is_err()
        );
    }
}
