//! The exact motion of the free asymmetric rigid body in the body frame: Euler's equations
//! `Π̇ = Π × J⁻¹Π`, `J = diag(J₁, J₂, J₃)` with distinct moments, solved by Jacobi elliptic
//! functions ([LL76] §37).
//!
//! With the energy `2E = Σ Π_i²/J_i` and `M² = |Π|²`, label the axes `a, b, c` so that
//! `J_b` is the middle moment and the motion winds about axis `c`: the axis of the largest moment
//! when `M² > 2EJ_b`, of the smallest otherwise (`a` is the remaining one). Then, with
//! `Ω = J⁻¹Π`,
//!
//! ```text
//! Ω_a = s_a A cn(u | m),  Ω_b = s_b B sn(u | m),  Ω_c = s_c C dn(u | m),   u = λ t + u₀,
//! A² = (2EJ_c − M²)/(J_a(J_c − J_a)),  B² = (2EJ_c − M²)/(J_b(J_c − J_b)),
//! C² = (M² − 2EJ_a)/(J_c(J_c − J_a)),  λ² = (J_c − J_b)(M² − 2EJ_a)/(J_aJ_bJ_c),
//! m = (J_b − J_a)(2EJ_c − M²)/((J_c − J_b)(M² − 2EJ_a)),
//! ```
//!
//! where `s_a = 1`, `s_c = sign Π_c(0)`, and Euler's equations fix
//! `s_b = ε_{abc} s_a s_c sign(J_c − J_a)` (`ε_{abc} = ±1` the parity of `(a, b, c)`)
//! (substituting `d sn/du = cn dn`, `d cn/du = −sn dn`, `d dn/du = −m sn cn`). The phase `u₀` is
//! `F(φ₀ | m)` with `φ₀ = atan2(Ω_b(0)/(s_bB), Ω_a(0)/A)`.
//!
//! [LL76]: crate#references

use super::elliptic::{ellip_f, jacobi};
use super::{SpecialError, finite};

/// The free rigid body's exact body angular momentum `Π(t)` from `Π(0)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EulerTop {
    moments: [f64; 3],
    /// Axis indices `(a, b, c)`.
    axes: [usize; 3],
    amplitudes: [f64; 3],
    rate: f64,
    phase: f64,
    parameter: f64,
}

impl EulerTop {
    /// The motion with principal moments `moments` (distinct, positive) from `pi0`.
    ///
    /// # Errors
    /// [`SpecialError::NotFinite`] for non-finite data; [`SpecialError::Domain`] for a
    /// non-positive moment; [`SpecialError::Degenerate`] for equal moments (the symmetric top is
    /// solved by circular functions), for `Π(0) = 0`, or for motion on the separatrix
    /// `M² = 2EJ_b` or at a steady rotation about a principal axis.
    pub fn new(moments: [f64; 3], pi0: [f64; 3]) -> Result<Self, SpecialError> {
        for (&j, name) in moments.iter().zip(["J1", "J2", "J3"]) {
            finite(name, j)?;
            super::domain(j > 0.0, name, j, "a positive principal moment")?;
        }
        for (&p, name) in pi0.iter().zip(["Pi1", "Pi2", "Pi3"]) {
            finite(name, p)?;
        }
        let mut order = [0, 1, 2];
        order.sort_by(|&i, &j| moments[i].total_cmp(&moments[j]));
        let [small, middle, large] = order;
        if moments[small] == moments[middle] || moments[middle] == moments[large] {
            return Err(SpecialError::Degenerate("two equal principal moments"));
        }
        let m2: f64 = pi0.iter().map(|p| p * p).sum();
        let e2: f64 = (0..3).map(|i| pi0[i] * pi0[i] / moments[i]).sum();
        if m2 == 0.0 {
            return Err(SpecialError::Degenerate("the body is at rest"));
        }
        let separatrix = m2 - e2 * moments[middle];
        if separatrix.abs() <= 1e-14 * m2 {
            return Err(SpecialError::Degenerate(
                "motion on the separatrix M² = 2E J₂",
            ));
        }
        let (a, b, c) = if separatrix > 0.0 {
            (small, middle, large)
        } else {
            (large, middle, small)
        };
        let [ja, jb, jc] = [moments[a], moments[b], moments[c]];
        let outer = e2 * jc - m2;
        let inner = m2 - e2 * ja;
        let amp_a = (outer / (ja * (jc - ja))).sqrt();
        let amp_b = (outer / (jb * (jc - jb))).sqrt();
        let amp_c = (inner / (jc * (jc - ja))).sqrt();
        let rate = ((jc - jb) * inner / (ja * jb * jc)).sqrt();
        let parameter = ((jb - ja) * outer / ((jc - jb) * inner)).clamp(0.0, 1.0);
        if amp_a == 0.0 || rate.is_nan() || rate <= 0.0 {
            return Err(SpecialError::Degenerate(
                "a steady rotation about a principal axis",
            ));
        }
        let s_c = if pi0[c] < 0.0 { -1.0 } else { 1.0 };
        // Euler's equations J_bΩ̇_b = ±(J_c − J_a)Ω_cΩ_a: + when (a, b, c) is cyclic.
        let parity = if (b + 3 - a) % 3 == 1 { 1.0 } else { -1.0 };
        let s_b = parity * s_c * (jc - ja).signum();
        let omega = [
            pi0[0] / moments[0],
            pi0[1] / moments[1],
            pi0[2] / moments[2],
        ];
        let phi0 = (omega[b] / (s_b * amp_b)).atan2(omega[a] / amp_a);
        let phase = ellip_f(phi0, parameter)?;
        Ok(Self {
            moments,
            axes: [a, b, c],
            amplitudes: [amp_a, s_b * amp_b, s_c * amp_c],
            rate,
            phase,
            parameter,
        })
    }

    /// `Π(t)`.
    ///
    /// # Errors
    /// [`SpecialError::NotFinite`] for a non-finite `t`.
    pub fn momentum(&self, t: f64) -> Result<[f64; 3], SpecialError> {
        let j = jacobi(self.rate * finite("t", t)? + self.phase, self.parameter)?;
        let [a, b, c] = self.axes;
        let mut pi = [0.0; 3];
        pi[a] = self.moments[a] * self.amplitudes[0] * j.cn;
        pi[b] = self.moments[b] * self.amplitudes[1] * j.sn;
        pi[c] = self.moments[c] * self.amplitudes[2] * j.dn;
        Ok(pi)
    }

    /// The parameter `m = k²` of the elliptic functions.
    pub fn parameter(&self) -> f64 {
        self.parameter
    }

    /// The period of `Π(t)`: `4K(m)/λ`.
    ///
    /// # Errors
    /// Those of [`super::elliptic::ellip_k`] (never for a motion off the separatrix).
    pub fn period(&self) -> Result<f64, SpecialError> {
        Ok(4.0 * super::elliptic::ellip_k(self.parameter)? / self.rate)
    }
}
