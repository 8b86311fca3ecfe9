//! Jacobi elliptic functions `sn`, `cn`, `dn` and the amplitude `am` (A&S 16, DLMF 22).

use super::ellip_k_m1;
use crate::special::{SpecialError, domain, finite, parity_sign};
use std::f64::consts::PI;

/// Maximal number of Landen steps; the AGM behind them converges quadratically, so for every
/// `m₁ ≥ 10⁻³⁰⁸` fewer than 15 are taken.
const MAX_LANDEN_STEPS: usize = 40;

/// The four Jacobi elliptic functions at one point `(u | m)`.
///
/// `am` is the amplitude, `F(am | m) = u`; `sn = sin am`, `cn = cos am`,
/// `dn = √(1 − m sn²)` (A&S 16.1.5, DLMF 22.16.11). They satisfy `sn² + cn² = 1`,
/// `dn² + m sn² = 1`, and `d sn/du = cn dn`, `d cn/du = −sn dn`, `d dn/du = −m sn cn`,
/// `d am/du = dn` (DLMF 22.6.1, 22.13.1–3, 22.16.1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jacobi {
    /// `sn(u | m) = sin am(u | m)`.
    pub sn: f64,
    /// `cn(u | m) = cos am(u | m)`.
    pub cn: f64,
    /// `dn(u | m) = √(1 − m sn²(u | m))`.
    pub dn: f64,
    /// The amplitude `am(u | m)`, a continuous increasing function of `u` with
    /// `am(u + 2K) = am(u) + π`.
    pub am: f64,
}

/// Jacobi elliptic functions `sn, cn, dn, am` of argument `u` and parameter `0 ≤ m ≤ 1`.
///
/// Method: `u` is first reduced to `r ∈ [−K, K]` with `u = r + 2jK`, using
/// `sn(u) = (−1)^j sn(r)`, `cn(u) = (−1)^j cn(r)`, `dn(u) = dn(r)`, `am(u) = am(r) + jπ`
/// (DLMF 22.4.3, 22.16.2), so large arguments keep the right sign and periodicity. Then the
/// descending Landen transformation (A&S 16.4.2–3): with the AGM sequence `a₀ = 1`,
/// `b₀ = √m₁`, `c₀ = √m`, `c_{n+1} = c_n²/(4a_{n+1})` run until `c_N/a_N < ε`, set
/// `φ_N = 2^N a_N r` and `φ_{n−1} = ½(φ_n + arcsin((c_n/a_n) sin φ_n))`; `am(r) = φ₀`.
/// `dn` is taken as `√(m₁ + m cn²)`, a sum of non-negative terms (no cancellation).
/// `m = 0` gives the circular and `m = 1` the hyperbolic functions exactly
/// (`sn = tanh`, `cn = dn = sech`, `am = gd`, DLMF 22.5.ii).
///
/// Accuracy (checked against 1500 random mpmath values, `|u| ≤ 12`, `m` up to `1 − 10⁻¹⁵`):
/// absolute error below `3·10⁻¹⁵`, growing like `ε|u|` for large `|u|`, which is the
/// conditioning of the functions themselves. The error is absolute: where `cn` and `dn` are
/// both tiny (`u ≈ K` with `m → 1`) their *relative* error can reach `ε/√m₁`.
///
/// # Errors
/// [`SpecialError::NotFinite`] for non-finite input, [`SpecialError::Domain`] unless
/// `0 ≤ m ≤ 1`.
///
/// ```
/// use marsden::special::elliptic::{ellip_k, jacobi};
/// let m = 0.5;
/// let j = jacobi(ellip_k(m).unwrap(), m).unwrap();
/// assert!((j.sn - 1.0).abs() < 1e-15 && j.cn.abs() < 1e-15);
/// assert!((j.dn - (1.0_f64 - m).sqrt()).abs() < 1e-15);
/// ```
pub fn jacobi(u: f64, m: f64) -> Result<Jacobi, SpecialError> {
    finite("u", u)?;
    finite("m", m)?;
    domain((0.0..=1.0).contains(&m), "m", m, "0 <= m <= 1")?;
    Ok(jacobi_mm1(u, m, 1.0 - m))
}

/// `sn(u | m)`; see [`jacobi`] for method, accuracy and errors.
pub fn sn(u: f64, m: f64) -> Result<f64, SpecialError> {
    jacobi(u, m).map(|j| j.sn)
}

/// `cn(u | m)`; see [`jacobi`] for method, accuracy and errors.
pub fn cn(u: f64, m: f64) -> Result<f64, SpecialError> {
    jacobi(u, m).map(|j| j.cn)
}

/// `dn(u | m)`; see [`jacobi`] for method, accuracy and errors.
pub fn dn(u: f64, m: f64) -> Result<f64, SpecialError> {
    jacobi(u, m).map(|j| j.dn)
}

/// The amplitude `am(u | m)`, inverse of [`ellip_f`](super::ellip_f) in `φ`; see [`jacobi`].
pub fn am(u: f64, m: f64) -> Result<f64, SpecialError> {
    jacobi(u, m).map(|j| j.am)
}

/// [`jacobi`] with the complementary parameter `m₁ = 1 − m` supplied separately (more
/// accurate near `m = 1` when the caller knows `m₁` directly). Requires finite `u`,
/// `0 ≤ m ≤ 1`, `m₁ ≥ 0`.
pub(crate) fn jacobi_mm1(u: f64, m: f64, m1: f64) -> Jacobi {
    if m1 == 0.0 {
        return hyperbolic(u);
    }
    if m == 0.0 {
        return circular(u);
    }
    let quarter = ellip_k_m1(m1);
    let j = (u / (2.0 * quarter)).round();
    let r = (-2.0 * quarter).mul_add(j, u);
    let phi = landen_amplitude(r, m, m1);
    let (s, c) = phi.sin_cos();
    let sign = parity_sign(j);
    Jacobi {
        sn: sign * s,
        cn: sign * c,
        dn: m.mul_add(c * c, m1).sqrt(),
        am: PI.mul_add(j, phi),
    }
}

/// `m = 0`: `sn = sin`, `cn = cos`, `dn = 1`, `am(u) = u` (DLMF 22.5.3).
fn circular(u: f64) -> Jacobi {
    let (sn, cn) = u.sin_cos();
    Jacobi {
        sn,
        cn,
        dn: 1.0,
        am: u,
    }
}

/// `m = 1`: `sn = tanh`, `cn = dn = sech`, `am = gd(u) = arctan(sinh u)` (DLMF 22.5.4, 4.23.39).
fn hyperbolic(u: f64) -> Jacobi {
    let sech = 1.0 / u.cosh();
    Jacobi {
        sn: u.tanh(),
        cn: sech,
        dn: sech,
        am: u.sinh().atan(),
    }
}

/// Amplitude `am(r | m)` by the descending Landen transformation (A&S 16.4.2–3); accurate for
/// `|r| ≲ K`, which [`jacobi_mm1`] guarantees.
///
/// The back-substitution `2φ_{n−1} − φ_n = arcsin(γ_n sin φ_n)`, `γ_n = c_n/a_n`, is evaluated
/// as `atan2(γ_n sin φ_n, hypot(cos φ_n, β_n sin φ_n))` with `β_n = b_n/a_n`, using
/// `1 − γ_n² = β_n²`: the arcsine of an argument close to 1 (which occurs for `m → 1` near
/// `φ = ±π/2`) would amplify rounding errors by `1/√(1 − γ_n²)`.
fn landen_amplitude(r: f64, m: f64, m1: f64) -> f64 {
    let mut gammas = [0.0_f64; MAX_LANDEN_STEPS];
    let mut betas = [0.0_f64; MAX_LANDEN_STEPS];
    let (mut a, mut b, mut c) = (1.0_f64, m1.sqrt(), m.sqrt());
    let mut steps = 0;
    while steps < MAX_LANDEN_STEPS && c > f64::EPSILON * a {
        let a_next = 0.5 * (a + b);
        c = 0.25 * c * c / a_next; // (a − b)/2 without cancellation, since a² − b² = c²
        b = (a * b).sqrt();
        a = a_next;
        gammas[steps] = c / a;
        betas[steps] = b / a;
        steps += 1;
    }
    let mut phi = (a * r) * 2.0_f64.powi(steps as i32);
    for (gamma, beta) in gammas[..steps].iter().zip(&betas[..steps]).rev() {
        let (s, c) = phi.sin_cos();
        let psi = (gamma * s).atan2(c.hypot(beta * s));
        phi = 0.5 * (phi + psi);
    }
    phi
}
