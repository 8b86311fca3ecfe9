//! Scratch buffers for the hot path, scoped to a closure.
//!
//! Rules and the step build short vectors of dual numbers (node positions and velocities,
//! offsets, AD inputs) on every evaluation. [`with_buffer`] keeps up to `CAP` of them in a plain
//! local array — never returned or moved, so no copies of inline storage — and hands a slice to
//! the closure; longer vectors go to the heap, so small systems never allocate and large ones
//! still work.

/// Runs `body` on a buffer of `len` values `init(0) … init(len − 1)`, on the stack if
/// `len ≤ CAP` (`fill` pads the unused part of the array). Up to two values take an array of
/// two, so that small systems do not pay for padding a long array of hyper-dual numbers.
#[inline(always)]
pub fn with_buffer<S: Copy, const CAP: usize, R>(
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

/// [`with_buffer`] in an array of `K ≥ len` values.
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

/// Inline capacity for per-node vectors of length n (positions, velocities, forces).
pub const NODE: usize = 8;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inline_and_heap_buffers_hold_the_same_values() {
        let two = with_buffer::<f64, 4, _>(2, 0.0, |i| i as f64, |b| b.to_vec());
        let small = with_buffer::<f64, 4, _>(3, 0.0, |i| i as f64, |b| b.to_vec());
        let large = with_buffer::<f64, 4, _>(6, 0.0, |i| i as f64, |b| b.to_vec());
        assert_eq!(two, [0.0, 1.0]);
        assert_eq!(small, [0.0, 1.0, 2.0]);
        assert_eq!(large, [0.0, 1.0, 2.0, 3.0, 4.0, 5.0]);
    }
}
