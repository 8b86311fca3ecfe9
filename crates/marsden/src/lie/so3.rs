//! The rotation group SO(3) and its Lie algebra so(3) ≅ ℝ³: hat and vee, the exponential
//! (Rodrigues) and its inverse, the Cayley map and its inverse, quaternions and rotation vectors,
//! and the re-orthonormalisation of a matrix typed in as an attitude.
//!
//! `ξ^` is the skew matrix with `ξ^ v = ξ × v`; `vee` inverts it on the skew part of a matrix.
//! The Cayley map used by the LGVI ([LLM05], [LLM07] §3) is
//!
//! ```text
//! cay(f) = (I + f^)(I − f^)⁻¹ = I + 2/(1 + |f|²) (f^ + f^ f^),
//! cay⁻¹(F) = vee(F − Fᵀ) / (1 + tr F)          (defined unless F is a half turn),
//! ```
//!
//! a rotation by the angle `2 arctan |f|` about `f`, so `cay(f) = exp(2f^) + O(|f|³)`
//! ([HLW06] §IV.8.3). The exponential and quaternions are nalgebra's (`Rotation3`,
//! `UnitQuaternion`, well tested); the logarithm is written here because nalgebra's takes the
//! angle as an `arccos` of the trace, which loses half the digits near the angle 0.
//!
//! [LLM05]: crate#references
//! [LLM07]: crate#references
//! [HLW06]: crate#references

use crate::error::{Error, InputError};
use nalgebra::{Matrix3, Quaternion, Rotation3, UnitQuaternion, Vector3};

/// A 3×3 matrix of `f64` (an attitude, an inertia tensor).
pub type Mat3 = Matrix3<f64>;
/// A vector of ℝ³ (an element of so(3) ≅ ℝ³, a momentum, a position).
pub type Vec3 = Vector3<f64>;

/// The orthogonality defect accepted by [`attitude`] before re-orthonormalising.
pub const ATTITUDE_TOLERANCE: f64 = 1e-10;

/// `ξ^`: the skew matrix with `ξ^ v = ξ × v`.
pub fn hat(xi: &Vec3) -> Mat3 {
    xi.cross_matrix()
}

/// `vee(A) = ξ` with `ξ^ = (A − Aᵀ)/2`, the skew part of `A` as a vector (exactly the inverse of
/// [`hat`] on skew matrices).
pub fn vee(a: &Mat3) -> Vec3 {
    Vec3::new(
        0.5 * (a[(2, 1)] - a[(1, 2)]),
        0.5 * (a[(0, 2)] - a[(2, 0)]),
        0.5 * (a[(1, 0)] - a[(0, 1)]),
    )
}

/// `exp(ξ^)`, the rotation by the angle `|ξ|` about `ξ` (Rodrigues' formula).
pub fn exp(xi: &Vec3) -> Mat3 {
    Rotation3::new(*xi).into_inner()
}

/// The principal logarithm: `ξ` with `exp(ξ^) = R` and `|ξ| ≤ π`. `r` must be a rotation.
///
/// The angle is `θ = atan2(|vee(R)|, (tr R − 1)/2)`, accurate for every angle (an `arccos` of the
/// trace loses half the digits near 0 and π); `ξ = θ vee(R)/sin θ`, and near a half turn the
/// axis is read off the symmetric part `(R + Rᵀ)/2 − cos θ I = (1 − cos θ) n nᵀ`.
pub fn log(r: &Mat3) -> Vec3 {
    let skew = vee(r);
    let sine = skew.norm();
    let cosine = 0.5 * (r.trace() - 1.0);
    let angle = sine.atan2(cosine);
    if sine < 1e-8 {
        if cosine > 0.0 {
            // θ = |vee R| (1 + θ²/6 + …): the first-order formula is exact to round-off here.
            return skew * (1.0 + sine * sine / 6.0);
        }
        return angle * half_turn_axis(r, cosine, &skew);
    }
    skew * (angle / sine)
}

/// The unit axis `n` of a rotation by nearly π, from `(R + Rᵀ)/2 − cos θ I = (1 − cos θ) n nᵀ`,
/// its sign taken from `vee(R) = sin θ n`.
fn half_turn_axis(r: &Mat3, cosine: f64, skew: &Vec3) -> Vec3 {
    let outer = 0.5 * (r + r.transpose()) - cosine * Mat3::identity();
    let k = outer.diagonal().imax();
    let column = outer.column(k).into_owned();
    let n = column / column.norm();
    if n.dot(skew) < 0.0 { -n } else { n }
}

/// `cay(f) = (I + f^)(I − f^)⁻¹ = I + 2/(1 + |f|²)(f^ + f^f^)`: the rotation by `2 arctan |f|`
/// about `f` ([LLM07] §3, the Cayley parameters of the step's `F_k`).
///
/// [LLM07]: crate#references
pub fn cay(f: &Vec3) -> Mat3 {
    let s = hat(f);
    let w = 2.0 / (1.0 + f.norm_squared());
    Mat3::identity() + w * (s + s * s)
}

/// `cay(f) − I = 2/(1 + |f|²)(f^ + f^f^)`, the offset of the step's rotation from the identity:
/// `R_{k+1} = R_k + R_k (F_k − I)` rounds once on the sum instead of on every product of
/// `R_k F_k` (over 10⁶ heavy-top steps of `h = 0.001`: `max |RᵀR − I|` 1.75e-13 with `R_k F_k`).
pub fn cay_offset(f: &Vec3) -> Mat3 {
    let s = hat(f);
    let w = 2.0 / (1.0 + f.norm_squared());
    w * (s + s * s)
}

/// `cay⁻¹(F) = vee(F − Fᵀ)/(1 + tr F)`; `None` for a half turn (`tr F = −1`), which has no
/// Cayley parameters.
pub fn cay_inv(r: &Mat3) -> Option<Vec3> {
    let denominator = 1.0 + r.trace();
    (denominator.abs() > f64::EPSILON).then(|| 2.0 * vee(r) / denominator)
}

/// The orthogonality defect `max |RᵀR − I|` (max-norm over the entries).
pub fn orthogonality_defect(r: &Mat3) -> f64 {
    // nalgebra's `amax` skips NaN (`>` is false): a NaN attitude must not read as orthogonal.
    crate::numerics::dense::max_norm((r.transpose() * r - Mat3::identity()).as_slice())
}

/// The nearest rotation to a nearly orthonormal `r` (its polar factor), by the Newton iteration
/// `R ← ½(R + R⁻ᵀ)` ([HLW06] §IV.4, Higham's polar iteration), which converges quadratically
/// from a defect below 1; the result is orthonormal to round-off.
///
/// [HLW06]: crate#references
pub fn orthonormalize(r: &Mat3) -> Mat3 {
    let mut r = *r;
    for _ in 0..8 {
        let Some(inverse) = r.try_inverse() else {
            break;
        };
        let next = 0.5 * (r + inverse.transpose());
        let change = (next - r).amax();
        r = next;
        if change <= 4.0 * f64::EPSILON {
            break;
        }
    }
    r
}

/// A matrix typed in as an attitude (9 entries, row-major): accepted when `det R > 0` and
/// `max |RᵀR − I| ≤` [`ATTITUDE_TOLERANCE`] (1e-10), then re-orthonormalised to round-off.
///
/// # Errors
/// [`InputError::NonFinite`] for a non-finite entry, [`InputError::NotARotation`] with the
/// defect and the determinant otherwise.
pub fn attitude(what: &'static str, rows: &[f64; 9]) -> Result<Mat3, Error> {
    Error::check_finite(what, rows)?;
    let r = Mat3::from_row_slice(rows);
    let defect = orthogonality_defect(&r);
    let determinant = r.determinant();
    // Written so that a NaN defect or determinant (an overflow) is refused, not accepted.
    let rotation = defect <= ATTITUDE_TOLERANCE && determinant > 0.0;
    if !rotation {
        return Err(Error::Input(InputError::NotARotation {
            what,
            defect,
            determinant,
            tolerance: ATTITUDE_TOLERANCE,
        }));
    }
    Ok(orthonormalize(&r))
}

/// The 9 entries of `r`, row-major (`R11, R12, …, R33`: the order of the problem files).
pub fn rows(r: &Mat3) -> [f64; 9] {
    let mut out = [0.0; 9];
    for i in 0..3 {
        for j in 0..3 {
            out[3 * i + j] = r[(i, j)];
        }
    }
    out
}

/// The rotation of the quaternion `w + xi + yj + zk` (normalised first; `(w, x, y, z)` and
/// `−(w, x, y, z)` give the same rotation).
///
/// # Errors
/// [`InputError::NonFinite`] for a non-finite component, [`InputError::InvalidOption`] for the
/// zero quaternion.
pub fn from_quaternion(q: &[f64; 4]) -> Result<Mat3, Error> {
    Error::check_finite("quaternion", q)?;
    let quaternion = Quaternion::new(q[0], q[1], q[2], q[3]);
    let norm = quaternion.norm();
    if norm == 0.0 {
        return Err(Error::Input(InputError::InvalidOption {
            name: "quaternion",
            value: norm,
            reason: "must be non-zero",
        }));
    }
    Ok(UnitQuaternion::from_quaternion(quaternion)
        .to_rotation_matrix()
        .into_inner())
}

/// The unit quaternion `(w, x, y, z)` of the rotation `r`, with `w ≥ 0`.
pub fn to_quaternion(r: &Mat3) -> [f64; 4] {
    let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(*r));
    let sign = if q.w < 0.0 { -1.0 } else { 1.0 };
    [sign * q.w, sign * q.i, sign * q.j, sign * q.k]
}

/// The rotation of the rotation vector `θ n` (angle times unit axis): [`exp`].
pub fn from_rotation_vector(v: &Vec3) -> Mat3 {
    exp(v)
}

/// The rotation vector `θ n` of `r` with `0 ≤ θ ≤ π`: [`log`].
pub fn to_rotation_vector(r: &Mat3) -> Vec3 {
    log(r)
}
