//! The Kepler problem: Kepler's equation and the exact propagation of bound two-body orbits.
//!
//! The Hamiltonian is `H(q, p) = |p|²/2 − μ/|q|` (relative motion, unit reduced mass) in any
//! dimension `D ≥ 2` (the motion stays in the plane of `q₀`, `p₀`). For a bound orbit
//! (`H < 0`) with non-zero angular momentum (Hairer–Lubich–Wanner, *Geometric Numerical
//! Integration*, §I.2.3; Danby, *Fundamentals of Celestial Mechanics*, §6.8):
//!
//! ```text
//! a = −μ/(2H),   n = √(μ/a³),   e cos E₀ = 1 − r₀/a,   e sin E₀ = q₀·p₀/√(μa),
//! M₀ = E₀ − e sin E₀,   M(t) = M₀ + n t,   E(t) − e sin E(t) = M(t),
//! ```
//!
//! and with `ΔE = E(t) − E₀` the state follows from the Lagrange coefficients
//! `q = f q₀ + g p₀`, `p = ḟ q₀ + ġ p₀`, which need neither the orientation of the orbit nor
//! the sign of its angular momentum (so both directions and every orientation are handled):
//!
//! ```text
//! f = 1 − (a/r₀)(1 − cos ΔE),           g = ((r₀/a) sin ΔE + e sin E₀ (1 − cos ΔE)) / n,
//! ḟ = −√(μa) sin ΔE / (r r₀),           ġ = 1 − (a/r)(1 − cos ΔE),
//! r = a (1 − e cos E₀ cos ΔE + e sin E₀ sin ΔE).
//! ```
//!
//! (`g` is the usual `t − (ΔE − sin ΔE)/n` with `t` eliminated by Kepler's equation, which
//! removes the cancellation for long times.)

use super::{SpecialError, domain, finite};
use std::cmp::Ordering;
use std::f64::consts::{PI, TAU};

/// Newton iterations allowed in [`solve_kepler`]; the monotone iteration needs fewer than 30
/// even for `e = 1 − 10⁻¹⁵`.
const MAX_NEWTON_STEPS: usize = 100;

/// Solve Kepler's equation `E − e sin E = M` for the eccentric anomaly `E`, `0 ≤ e < 1`.
///
/// `M` is reduced to `[−π, π]` (the solution is odd in `M` and `E(M + 2π) = E(M) + 2π`, so
/// the returned `E` satisfies the equation for the given, unreduced `M`). On `[0, π]` the
/// function `f(E) = E − e sin E − M` is increasing and convex, so Newton's method started at
/// the upper bound `E₀ = min(M + e, M/(1 − e), π)` (where `f(E₀) ≥ 0`) decreases
/// monotonically to the root; it stops when the iterates stop decreasing, i.e. at rounding
/// level (Danby §6.6; HLW §I.2.3). `E − e sin E` and `1 − e cos E` are evaluated as
/// `(1 − e)E + e(E − sin E)` and `(1 − e) + 2e sin²(E/2)` so that `e → 1`, `M → 0` stays
/// accurate.
///
/// # Errors
/// [`SpecialError::NotFinite`] for non-finite input, [`SpecialError::Domain`] unless
/// `0 ≤ e < 1`.
///
/// ```
/// use marsden::special::kepler::solve_kepler;
/// let (m, e) = (1.0, 0.6);
/// let ecc = solve_kepler(m, e).unwrap();
/// assert!((ecc - e * ecc.sin() - m).abs() < 1e-15);
/// ```
pub fn solve_kepler(mean_anomaly: f64, e: f64) -> Result<f64, SpecialError> {
    finite("mean_anomaly", mean_anomaly)?;
    finite("e", e)?;
    domain((0.0..1.0).contains(&e), "e", e, "0 <= e < 1")?;
    let j = (mean_anomaly / TAU).round();
    let reduced = (-TAU).mul_add(j, mean_anomaly);
    let ecc = kepler_on_half_turn(reduced.abs().min(PI), e)?;
    Ok(TAU.mul_add(j, ecc.copysign(reduced)))
}

/// Monotone Newton iteration for `E − e sin E = x`, `x ∈ [0, π]`.
fn kepler_on_half_turn(x: f64, e: f64) -> Result<f64, SpecialError> {
    let one_minus_e = 1.0 - e;
    let mut ecc = (x + e).min(x / one_minus_e).min(PI);
    for _ in 0..MAX_NEWTON_STEPS {
        let residual = one_minus_e.mul_add(ecc, e * x_minus_sin(ecc)) - x;
        if residual <= 0.0 {
            return Ok(ecc);
        }
        let half_sin = (0.5 * ecc).sin();
        let slope = (2.0 * e * half_sin).mul_add(half_sin, one_minus_e);
        let next = ecc - residual / slope;
        match next.partial_cmp(&ecc) {
            Some(Ordering::Less) => ecc = next,
            _ => return Ok(ecc), // no further decrease: converged to rounding level
        }
    }
    Err(SpecialError::NoConvergence("Kepler's equation"))
}

/// `x − sin x` without cancellation: the Maclaurin series `x³/3! − x⁵/5! + …` for `|x| < 1`.
fn x_minus_sin(x: f64) -> f64 {
    if x.abs() >= 1.0 {
        return x - x.sin();
    }
    let x2 = x * x;
    let mut term = x * x2 / 6.0;
    let mut sum = 0.0_f64;
    let mut k = 3.0;
    while term.abs() > f64::EPSILON * 0.25 * sum.abs() {
        sum += term;
        term *= -x2 / ((k + 1.0) * (k + 2.0));
        k += 2.0;
    }
    sum
}

/// Euclidean inner product.
fn dot<const D: usize>(a: &[f64; D], b: &[f64; D]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Energy `H = |p|²/2 − μ/|q|` of the Kepler problem.
pub fn kepler_energy<const D: usize>(mu: f64, q: &[f64; D], p: &[f64; D]) -> f64 {
    0.5 * dot(p, p) - mu / dot(q, q).sqrt()
}

/// Squared norm of the angular momentum `|q ∧ p|² = Σ_{i<j} (q_i p_j − q_j p_i)²` in any
/// dimension (equal to `|q|²|p|² − (q·p)²`, Lagrange's identity, without its cancellation).
pub fn angular_momentum_squared<const D: usize>(q: &[f64; D], p: &[f64; D]) -> f64 {
    let mut sum = 0.0;
    for i in 0..D {
        for j in i + 1..D {
            let l = q[i] * p[j] - q[j] * p[i];
            sum += l * l;
        }
    }
    sum
}

/// The exact bound orbit of `H = |p|²/2 − μ/|q|` through `(q₀, p₀)` at `t = 0`, in `D`
/// dimensions (`D = 2` or `3` in practice).
///
/// See the [module documentation](self) for the formulas. Reference case (`μ = 1`, `e = 0.6`,
/// pericentre at `t = 0`):
///
/// ```
/// use marsden::special::kepler::KeplerOrbit;
/// let orbit = KeplerOrbit::new(1.0, [0.4, 0.0], [0.0, 2.0]).unwrap();
/// let (q, p) = orbit.state(std::f64::consts::PI).unwrap(); // apocentre
/// assert!((q[0] + 1.6).abs() < 1e-15 && q[1].abs() < 1e-15);
/// assert!(p[0].abs() < 1e-15 && (p[1] + 0.5).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KeplerOrbit<const D: usize> {
    mu: f64,
    q0: [f64; D],
    p0: [f64; D],
    r0: f64,
    energy: f64,
    a: f64,
    n: f64,
    e: f64,
    /// `e cos E₀ = 1 − r₀/a`.
    e_cos: f64,
    /// `e sin E₀ = q₀·p₀/√(μa)`.
    e_sin: f64,
    /// Eccentric anomaly `E₀` at `t = 0`.
    ecc0: f64,
    /// Mean anomaly `M₀` at `t = 0`.
    mean0: f64,
}

impl<const D: usize> KeplerOrbit<D> {
    /// Set up the exact orbit from the gravitational parameter `μ > 0` and the initial data.
    ///
    /// # Errors
    /// [`SpecialError::NotFinite`] for non-finite input; [`SpecialError::Domain`] for `μ ≤ 0`
    /// or `q₀ = 0`; [`SpecialError::Unbound`] for energy `≥ 0`; [`SpecialError::Degenerate`]
    /// for zero angular momentum (radial, collision orbit) or an eccentricity that rounds to 1.
    pub fn new(mu: f64, q0: [f64; D], p0: [f64; D]) -> Result<Self, SpecialError> {
        finite("mu", mu)?;
        domain(mu > 0.0, "mu", mu, "mu > 0")?;
        for (&q, &p) in q0.iter().zip(&p0) {
            finite("q0", q)?;
            finite("p0", p)?;
        }
        let r0 = dot(&q0, &q0).sqrt();
        domain(r0 > 0.0, "|q0|", r0, "|q0| > 0")?;
        let energy = kepler_energy(mu, &q0, &p0);
        if energy >= 0.0 {
            return Err(SpecialError::Unbound { energy });
        }
        if angular_momentum_squared(&q0, &p0) == 0.0 {
            return Err(SpecialError::Degenerate(
                "zero angular momentum (radial orbit)",
            ));
        }
        let a = -mu / (2.0 * energy);
        let n = (mu / a).sqrt() / a;
        let e_cos = 1.0 - r0 / a;
        let e_sin = dot(&q0, &p0) / (mu * a).sqrt();
        let e = e_cos.hypot(e_sin);
        if e >= 1.0 {
            return Err(SpecialError::Degenerate("eccentricity rounds to 1"));
        }
        let ecc0 = e_sin.atan2(e_cos);
        Ok(Self {
            mu,
            q0,
            p0,
            r0,
            energy,
            a,
            n,
            e,
            e_cos,
            e_sin,
            ecc0,
            mean0: ecc0 - e_sin,
        })
    }

    /// `(q(t), p(t))` on the exact orbit, for any finite `t` (negative included).
    ///
    /// Accuracy: a few ulps times the number of revolutions, which is the conditioning of the
    /// phase `n t`.
    ///
    /// # Errors
    /// [`SpecialError::NotFinite`] for non-finite `t` (or a mean anomaly that overflows).
    pub fn state(&self, t: f64) -> Result<([f64; D], [f64; D]), SpecialError> {
        finite("t", t)?;
        let ecc = solve_kepler(self.n.mul_add(t, self.mean0), self.e)?;
        let delta = ecc - self.ecc0;
        let (s, c) = delta.sin_cos();
        let half = (0.5 * delta).sin();
        let one_minus_cos = 2.0 * half * half;
        let a = self.a;
        let r = a * (1.0 - self.e_cos * c + self.e_sin * s);
        let f = 1.0 - a / self.r0 * one_minus_cos;
        let g = (self.r0 / a * s + self.e_sin * one_minus_cos) / self.n;
        let fdot = -(self.mu * a).sqrt() * s / (r * self.r0);
        let gdot = 1.0 - a / r * one_minus_cos;
        let mut q = [0.0; D];
        let mut p = [0.0; D];
        for i in 0..D {
            q[i] = f * self.q0[i] + g * self.p0[i];
            p[i] = fdot * self.q0[i] + gdot * self.p0[i];
        }
        Ok((q, p))
    }

    /// The initial data `(q₀, p₀)`.
    pub fn initial_state(&self) -> ([f64; D], [f64; D]) {
        (self.q0, self.p0)
    }

    /// The gravitational parameter `μ`.
    pub fn mu(&self) -> f64 {
        self.mu
    }

    /// The (conserved) energy `H = |p|²/2 − μ/|q| < 0`.
    pub fn energy(&self) -> f64 {
        self.energy
    }

    /// Semi-major axis `a = −μ/(2H)`.
    pub fn semi_major_axis(&self) -> f64 {
        self.a
    }

    /// Eccentricity `e = √((1 − r₀/a)² + (q₀·p₀)²/(μa)) ∈ [0, 1)`.
    pub fn eccentricity(&self) -> f64 {
        self.e
    }

    /// Eccentricity (Laplace–Runge–Lenz) vector `(|p|²/μ − 1/r) q − (q·p/μ) p`, pointing to the
    /// pericentre with length `e` (HLW §I.2.3); zero for a circular orbit.
    pub fn eccentricity_vector(&self) -> [f64; D] {
        let (q, p) = (&self.q0, &self.p0);
        let cq = dot(p, p) / self.mu - 1.0 / self.r0;
        let cp = dot(q, p) / self.mu;
        std::array::from_fn(|i| cq * q[i] - cp * p[i])
    }

    /// Norm of the (conserved) angular momentum, `|q ∧ p| > 0`.
    pub fn angular_momentum_norm(&self) -> f64 {
        angular_momentum_squared(&self.q0, &self.p0).sqrt()
    }

    /// Mean motion `n = √(μ/a³)`.
    pub fn mean_motion(&self) -> f64 {
        self.n
    }

    /// Orbital period `2π/n = 2π √(a³/μ)`.
    pub fn period(&self) -> f64 {
        TAU / self.n
    }

    /// Eccentric anomaly `E₀` at `t = 0`, in `(−π, π]` (0 at pericentre, π at apocentre).
    pub fn eccentric_anomaly_at_epoch(&self) -> f64 {
        self.ecc0
    }

    /// Mean anomaly `M₀ = E₀ − e sin E₀` at `t = 0`; the pericentre passages are at
    /// `t = (2πj − M₀)/n`.
    pub fn mean_anomaly_at_epoch(&self) -> f64 {
        self.mean0
    }
}

impl KeplerOrbit<2> {
    /// Signed angular momentum `L = q₁p₂ − q₂p₁` (positive for counter-clockwise motion).
    pub fn angular_momentum(&self) -> f64 {
        self.q0[0] * self.p0[1] - self.q0[1] * self.p0[0]
    }
}

impl KeplerOrbit<3> {
    /// Angular momentum vector `L = q × p`.
    pub fn angular_momentum(&self) -> [f64; 3] {
        let (q, p) = (&self.q0, &self.p0);
        [
            q[1] * p[2] - q[2] * p[1],
            q[2] * p[0] - q[0] * p[2],
            q[0] * p[1] - q[1] * p[0],
        ]
    }
}

#[cfg(test)]
mod tests;
