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
///
/// `body` is called at exactly one place: these buffers nest (a rule's node inside the step's
/// offsets inside an AD chunk), and a body inlined once per storage kind would be compiled
/// three times per level.
#[inline(always)]
pub fn with_buffer<S: Copy, const CAP: usize, R>(
    len: usize,
    fill: S,
    mut init: impl FnMut(usize) -> S,
    body: impl FnOnce(&mut [S]) -> R,
) -> R {
    let mut two;
    let mut inline;
    let mut heap;
    let buffer: &mut [S] = if len <= 2 {
        two = [fill; 2];
        &mut two[..len]
    } else if len <= CAP {
        inline = [fill; CAP];
        &mut inline[..len]
    } else {
        heap = vec![fill; len];
        &mut heap
    };
    for (i, slot) in buffer.iter_mut().enumerate() {
        *slot = init(i);
    }
    body(buffer)
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
