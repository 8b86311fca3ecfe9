//! The inputs slice `[q, q̇, t]` of an expression, built on the stack.

use marsden::Scalar;

/// Calls `body` with the slice `[q₀ … qₙ₋₁, v₀ … vₙ₋₁, t]`.
///
/// The slice lives in a stack array sized to fit (3, 5, 9 or 17 values: n ≤ 1, 2, 4, 8), so the
/// unused tail that must be initialised stays short even for large dual numbers; more than 8
/// coordinates use the heap.
#[inline(always)]
pub fn with_inputs<S: Scalar, R>(q: &[S], v: &[S], t: S, body: impl FnOnce(&[S]) -> R) -> R {
    let n = q.len();
    let len = 2 * n + 1;
    let value = |i: usize| {
        if i < n {
            q[i]
        } else if i < 2 * n {
            v[i - n]
        } else {
            t
        }
    };
    let body = |x: &mut [S]| body(x);
    match len {
        0..=3 => with_buffer::<S, 3, R>(len, t, value, body),
        4..=5 => with_buffer::<S, 5, R>(len, t, value, body),
        6..=9 => with_buffer::<S, 9, R>(len, t, value, body),
        _ => with_buffer::<S, 17, R>(len, t, value, body),
    }
}

/// Runs `body` on a buffer of `len` values `init(0) … init(len − 1)`, in a local array if
/// `len ≤ CAP` (`fill` pads the unused part), else on the heap. One or two values take an array
/// of two: padding a larger array of hyper-dual numbers costs several percent of a step.
#[inline(always)]
fn with_buffer<S: Copy, const CAP: usize, R>(
    len: usize,
    fill: S,
    init: impl FnMut(usize) -> S,
    body: impl FnOnce(&mut [S]) -> R,
) -> R {
    if len <= 2 {
        on_stack::<S, 2, R>(len, fill, init, body)
    } else if len <= CAP {
        on_stack::<S, CAP, R>(len, fill, init, body)
    } else {
        let mut heap: Vec<S> = (0..len).map(init).collect();
        body(&mut heap)
    }
}

/// [`with_buffer`] in a local array of `K ≥ len` values (never returned or moved, so the
/// inline storage is not copied).
#[inline(always)]
fn on_stack<S: Copy, const K: usize, R>(
    len: usize,
    fill: S,
    mut init: impl FnMut(usize) -> S,
    body: impl FnOnce(&mut [S]) -> R,
) -> R {
    let mut buf = [fill; K];
    for (i, slot) in buf[..len].iter_mut().enumerate() {
        *slot = init(i);
    }
    body(&mut buf[..len])
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
