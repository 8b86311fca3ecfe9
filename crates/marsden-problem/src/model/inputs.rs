//! The inputs slice `[q, q̇, t]` of an expression, built on the stack.

use marsden::Scalar;
use marsden::numerics::scratch::with_slice;

/// Calls `body` with the slice `[q₀ … qₙ₋₁, v₀ … vₙ₋₁, t]`, on the stack for up to 16
/// coordinates ([`with_slice`]).
#[inline(always)]
pub fn with_inputs<S: Scalar, R>(q: &[S], v: &[S], t: S, body: impl FnOnce(&[S]) -> R) -> R {
    let n = q.len();
    with_slice(2 * n + 1, t, |x| {
        x[..n].copy_from_slice(q);
        x[n..2 * n].copy_from_slice(v);
        body(x)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lays_out_positions_velocities_time() {
        for n in [1, 2, 3, 4, 8, 9, 12] {
            let q: Vec<f64> = (0..n).map(|i| i as f64).collect();
            let v: Vec<f64> = (0..n).map(|i| 100.0 + i as f64).collect();
            let got = with_inputs(&q, &v, -1.0, |x| x.to_vec());
            let want: Vec<f64> = q.iter().chain(&v).copied().chain([-1.0]).collect();
            assert_eq!(got, want, "n = {n}");
        }
    }
}
