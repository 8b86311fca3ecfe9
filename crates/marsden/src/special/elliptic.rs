//! Elliptic integrals and Jacobi elliptic functions.
//!
//! Conventions follow Abramowitz & Stegun (A&S) chapter 17 and DLMF chapters 19 and 22: the
//! *parameter* is `m = k²` (`k` the modulus), the complementary parameter `m₁ = 1 − m`, and
//!
//! ```text
//! F(φ | m) = ∫₀^φ dθ / √(1 − m sin²θ),     K(m) = F(π/2 | m),
//! E(m)     = ∫₀^{π/2} √(1 − m sin²θ) dθ.
//! ```
//!
//! The Jacobi functions are the inverse of `F`: `am(u | m) = φ` where `F(φ | m) = u`, and
//! `sn u = sin φ`, `cn u = cos φ`, `dn u = √(1 − m sn² u)` (A&S 16.1, DLMF 22.16).
//!
//! Complete integrals use the arithmetic–geometric mean (A&S 17.6), the incomplete integral
//! Carlson's symmetric form `R_F` (DLMF 19.25.5, 19.36.1), the Jacobi functions the descending
//! Landen transformation (A&S 16.4). All are accurate to a few ulps for moderate arguments.

use super::{SpecialError, domain, finite};
use std::f64::consts::PI;

mod jacobi;

pub(crate) use jacobi::jacobi_mm1;
pub use jacobi::{Jacobi, am, cn, dn, jacobi, sn};

/// Iteration cap for the quadratically convergent AGM / Landen loops (never reached: from
/// `b₀ ≥ 10⁻¹⁶⁰` they converge in fewer than 15 steps).
const MAX_AGM_STEPS: usize = 64;

/// Arithmetic–geometric mean `AGM(a, b)` of two positive numbers (A&S 17.6.1–2):
/// `a_{n+1} = (a_n + b_n)/2`, `b_{n+1} = √(a_n b_n)`, until the two agree to rounding.
fn agm(mut a: f64, mut b: f64) -> f64 {
    for _ in 0..MAX_AGM_STEPS {
        if (a - b).abs() <= f64::EPSILON * a {
            break;
        }
        let next = 0.5 * (a + b);
        b = (a * b).sqrt();
        a = next;
    }
    0.5 * (a + b)
}

/// `K` from the complementary parameter `m₁ = 1 − m > 0`: `K = π / (2 AGM(1, √m₁))`
/// (A&S 17.6.1). Passing `m₁` directly keeps full relative accuracy as `m → 1`.
pub(crate) fn ellip_k_m1(m1: f64) -> f64 {
    PI / (2.0 * agm(1.0, m1.sqrt()))
}

/// Complete elliptic integral of the first kind `K(m) = ∫₀^{π/2} (1 − m sin²θ)^{-1/2} dθ`.
///
/// Computed by the arithmetic–geometric mean, `K(m) = π / (2 AGM(1, √(1 − m)))`
/// (A&S 17.6.1, DLMF 19.8.5); valid for every `m < 1` (negative `m` included).
/// `K(0) = π/2`, `K(½) = 1.8540746773013719…`, and `K(m) ~ ½ ln(16/(1 − m))` as `m → 1`.
///
/// # Errors
/// [`SpecialError::NotFinite`] for NaN/infinite `m`, [`SpecialError::Domain`] for `m ≥ 1`.
///
/// ```
/// use marsden::special::elliptic::ellip_k;
/// assert!((ellip_k(0.0).unwrap() - std::f64::consts::FRAC_PI_2).abs() < 1e-16);
/// assert!((ellip_k(0.5).unwrap() - 1.854_074_677_301_371_9).abs() < 1e-15);
/// ```
pub fn ellip_k(m: f64) -> Result<f64, SpecialError> {
    finite("m", m)?;
    domain(m < 1.0, "m", m, "m < 1")?;
    Ok(ellip_k_m1(1.0 - m))
}

/// Complete elliptic integral of the second kind `E(m) = ∫₀^{π/2} (1 − m sin²θ)^{1/2} dθ`.
///
/// By the AGM with the Gauss–Legendre sum (A&S 17.6.3–4, DLMF 19.8.6):
/// `E = K (1 − Σ_{n≥0} 2^{n−1} c_n²)` with `c₀² = m`, `c_{n+1} = (a_n − b_n)/2`.
/// Valid for `m ≤ 1` (`E(1) = 1`). Near `m = 1` the sum cancels and the relative error grows
/// like `K(m)·ε`.
///
/// # Errors
/// [`SpecialError::NotFinite`] for NaN/infinite `m`, [`SpecialError::Domain`] for `m > 1`.
///
/// ```
/// use marsden::special::elliptic::ellip_e;
/// assert!((ellip_e(0.5).unwrap() - 1.350_643_881_047_675_5).abs() < 1e-15);
/// ```
pub fn ellip_e(m: f64) -> Result<f64, SpecialError> {
    finite("m", m)?;
    domain(m <= 1.0, "m", m, "m <= 1")?;
    if m == 1.0 {
        return Ok(1.0);
    }
    let (mut a, mut b) = (1.0_f64, (1.0 - m).sqrt());
    let mut sum = 0.5 * m; // 2^{-1} c₀²
    let mut weight = 0.5;
    for _ in 0..MAX_AGM_STEPS {
        let c = 0.5 * (a - b);
        if c.abs() <= f64::EPSILON * a {
            break;
        }
        weight *= 2.0;
        sum += weight * c * c;
        let next = 0.5 * (a + b);
        b = (a * b).sqrt();
        a = next;
    }
    let k = PI / (2.0 * 0.5 * (a + b));
    Ok(k * (1.0 - sum))
}

/// Carlson's symmetric elliptic integral of the first kind
/// `R_F(x, y, z) = ½ ∫₀^∞ dt / √((t + x)(t + y)(t + z))` (DLMF 19.16.1).
///
/// Duplication algorithm of Carlson (1995), DLMF 19.36.1: the arguments are replaced by
/// `(x + λ)/4, …` with `λ = √x√y + √y√z + √z√x` until they agree to `(3ε)^{1/6}`, then the
/// series `A^{-1/2} (1 − E₂/10 + E₃/14 + E₂²/24 − 3E₂E₃/44 − 5E₂³/208 + 3E₃²/104 + E₂²E₃/16)`
/// in the elementary symmetric functions `E₂, E₃` of the normalised deviations is summed.
///
/// # Errors
/// [`SpecialError::NotFinite`] for a non-finite argument, [`SpecialError::Domain`] for a
/// negative argument or more than one zero argument.
///
/// ```
/// use marsden::special::elliptic::carlson_rf;
/// // R_F(0, 1, 2) = 1.3110287771460599… (test value of Carlson, Numer. Algorithms 10, 1995)
/// assert!((carlson_rf(0.0, 1.0, 2.0).unwrap() - 1.311_028_777_146_059_9).abs() < 1e-15);
/// ```
pub fn carlson_rf(x: f64, y: f64, z: f64) -> Result<f64, SpecialError> {
    for (name, v) in [("x", x), ("y", y), ("z", z)] {
        finite(name, v)?;
        domain(v >= 0.0, name, v, "non-negative")?;
    }
    let smallest_pair = (x + y).min(y + z).min(z + x);
    domain(
        smallest_pair > 0.0,
        "x, y, z",
        smallest_pair,
        "at most one zero argument",
    )?;
    Ok(rf_unchecked(x, y, z))
}

/// The duplication algorithm of [`carlson_rf`] without argument checks.
fn rf_unchecked(x0: f64, y0: f64, z0: f64) -> f64 {
    let a0 = (x0 + y0 + z0) / 3.0;
    let spread = (a0 - x0).abs().max((a0 - y0).abs()).max((a0 - z0).abs());
    // Carlson's stopping quantity Q = (3r)^{-1/6} max|A₀ − ·| with r = ε.
    let q = spread / (3.0 * f64::EPSILON).powf(1.0 / 6.0);
    let (mut x, mut y, mut z, mut a) = (x0, y0, z0, a0);
    let mut scale = 1.0; // 4^{-n}
    for _ in 0..MAX_AGM_STEPS {
        if scale * q < a.abs() {
            break;
        }
        let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
        let lambda = sx * sy + sy * sz + sz * sx;
        x = 0.25 * (x + lambda);
        y = 0.25 * (y + lambda);
        z = 0.25 * (z + lambda);
        a = 0.25 * (a + lambda);
        scale *= 0.25;
    }
    let dx = (a0 - x0) * scale / a;
    let dy = (a0 - y0) * scale / a;
    let dz = -(dx + dy);
    let e2 = dx * dy - dz * dz;
    let e3 = dx * dy * dz;
    let series = 1.0 - e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0
        - 3.0 * e2 * e3 / 44.0
        - 5.0 * e2 * e2 * e2 / 208.0
        + 3.0 * e3 * e3 / 104.0
        + e2 * e2 * e3 / 16.0;
    series / a.sqrt()
}

/// Incomplete elliptic integral of the first kind `F(φ | m) = ∫₀^φ (1 − m sin²θ)^{-1/2} dθ`.
///
/// For `|φ| ≤ π/2`, `F(φ | m) = sin φ · R_F(cos²φ, cos²φ + m₁ sin²φ, 1)` (DLMF 19.25.5, with
/// `1 − m sin²φ` written as `cos²φ + m₁ sin²φ` to avoid cancellation); other `φ` use the
/// quasi-periodicity `F(φ + nπ | m) = F(φ | m) + 2n K(m)` (DLMF 19.2.10). Hence `F` is the
/// inverse of the amplitude `am` for every real `φ`.
///
/// Valid for all real `φ` when `m < 1`, and for `|φ| < π/2` when `m = 1`
/// (`F(φ | 1) = artanh(sin φ)`).
///
/// # Errors
/// [`SpecialError::NotFinite`] for non-finite arguments, [`SpecialError::Domain`] for `m > 1`,
/// or `m = 1` with `|φ| > π/2`.
///
/// ```
/// use marsden::special::elliptic::{ellip_f, ellip_k};
/// let m = 0.7;
/// let k = ellip_k(m).unwrap();
/// assert!((ellip_f(std::f64::consts::FRAC_PI_2, m).unwrap() - k).abs() < 1e-15);
/// assert!((ellip_f(-3.0 * std::f64::consts::PI, m).unwrap() + 6.0 * k).abs() < 1e-14);
/// ```
pub fn ellip_f(phi: f64, m: f64) -> Result<f64, SpecialError> {
    finite("phi", phi)?;
    finite("m", m)?;
    domain(m <= 1.0, "m", m, "m <= 1")?;
    ellip_f_m1(phi, 1.0 - m)
}

/// [`ellip_f`] in terms of the complementary parameter `m₁ = 1 − m ≥ 0` alone (pass it
/// directly when it is known more accurately than `1 − m`). Arguments must be finite.
pub(crate) fn ellip_f_m1(phi: f64, m1: f64) -> Result<f64, SpecialError> {
    let n = (phi / PI).round();
    let r = (-PI).mul_add(n, phi); // r ∈ [−π/2, π/2] up to rounding
    let (s, c) = r.sin_cos();
    if m1 == 0.0 {
        domain(n == 0.0, "phi", phi, "|phi| < pi/2 when m = 1")?;
        domain(c > 0.0, "phi", phi, "|phi| < pi/2 when m = 1")?;
    }
    let c2 = c * c;
    let reduced = s * rf_unchecked(c2, c2 + m1 * s * s, 1.0);
    if n == 0.0 {
        Ok(reduced)
    } else {
        Ok((2.0 * ellip_k_m1(m1)).mul_add(n, reduced))
    }
}

#[cfg(test)]
mod tests;
