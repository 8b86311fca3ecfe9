//! The inputs slice `[q, q̇, t]` of an expression, built on the stack.

use marsden::Scalar;

/// Calls `body` with the slice `[q₀ … qₙ₋₁, v₀ … vₙ₋₁, t]`.
///
/// The slice lives in a stack array sized to fit (3, 5, 9 or 17 values: n ≤ 1, 2, 4, 8), so the
/// unused tail that must be initialised stays short even for large dual numbers; more than 8
/// coordinates use the heap. `body` is called at one place only (it is inlined, and a body
/// inlined once per array size would be compiled once per size).
#[inline(always)]
pub fn with_inputs<S: Scalar, R>(q: &[S], v: &[S], t: S, body: impl FnOnce(&[S]) -> R) -> R {
    let n = q.len();
    let len = 2 * n + 1;
    let (mut three, mut five, mut nine, mut seventeen, mut heap);
    let x: &mut [S] = match len {
        0..=3 => {
            three = [t; 3];
            &mut three[..len]
        }
        4..=5 => {
            five = [t; 5];
            &mut five[..len]
        }
        6..=9 => {
            nine = [t; 9];
            &mut nine[..len]
        }
        10..=17 => {
            seventeen = [t; 17];
            &mut seventeen[..len]
        }
        _ => {
            heap = vec![t; len];
            &mut heap
        }
    };
    x[..n].copy_from_slice(q);
    x[n..2 * n].copy_from_slice(v);
    x[2 * n] = t;
    body(x)
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
