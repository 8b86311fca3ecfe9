//! Scratch buffers for the hot path, scoped to a closure.
//!
//! Rules and the step build short vectors of dual numbers (node positions and velocities,
//! offsets, AD inputs) on every evaluation. [`with_buffer`] keeps up to `CAP` of them in a plain
//! local array — never returned or moved, so no copies of inline storage — and hands a slice to
//! the closure; longer vectors go to the heap, so small systems never allocate and large ones
//! still work.
//!
//! [`with_slice`] is the same idea for callers outside the core (the inputs slice of a compiled
//! expression, `[q, q̇, t, θ]` and the like): its stack array is the smallest of a few sizes
//! that fits, so the unused tail that must be initialised stays short even for large dual
//! numbers.

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

/// Runs `body` on a buffer of `len` copies of `fill`, held in a stack array of 3, 5, 9, 17 or
/// 33 values (the smallest that fits) and on the heap above 33.
///
/// `body` is called at one place only: it is inlined, and a body inlined once per array size
/// would be compiled once per size.
///
/// ```
/// use marsden::numerics::scratch::with_slice;
///
/// let q = [1.0, 2.0];
/// let total = with_slice(3, 0.5, |x| {
///     x[..2].copy_from_slice(&q);
///     x.iter().sum::<f64>()
/// });
/// assert_eq!(total, 3.5);
/// ```
#[inline(always)]
pub fn with_slice<S: Copy, R>(len: usize, fill: S, body: impl FnOnce(&mut [S]) -> R) -> R {
    let (mut three, mut five, mut nine, mut seventeen, mut thirty_three, mut heap);
    let x: &mut [S] = match len {
        0..=3 => {
            three = [fill; 3];
            &mut three[..len]
        }
        4..=5 => {
            five = [fill; 5];
            &mut five[..len]
        }
        6..=9 => {
            nine = [fill; 9];
            &mut nine[..len]
        }
        10..=17 => {
            seventeen = [fill; 17];
            &mut seventeen[..len]
        }
        18..=33 => {
            thirty_three = [fill; 33];
            &mut thirty_three[..len]
        }
        _ => {
            heap = vec![fill; len];
            &mut heap
        }
    };
    body(x)
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

    #[test]
    fn slices_of_every_size_have_the_asked_length_and_fill() {
        for len in [0, 1, 3, 4, 5, 6, 9, 10, 17, 18, 33, 34, 100] {
            let got = with_slice(len, 7.0, |x| {
                x[len.saturating_sub(1)..]
                    .iter_mut()
                    .for_each(|v| *v = -1.0);
                x.to_vec()
            });
            assert_eq!(got.len(), len);
            assert!(got[..len.saturating_sub(1)].iter().all(|&v| v == 7.0));
        }
    }
}
