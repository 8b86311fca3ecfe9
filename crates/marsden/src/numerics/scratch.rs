//! Scratch buffers for the hot path.
//!
//! Rules and the step build short vectors of dual numbers (node positions and velocities,
//! offsets, AD inputs) on every evaluation. A [`Buffer`] keeps up to `CAP` of them in a plain
//! array in the frame that declares it; longer vectors go to the heap, so small systems never
//! allocate and large ones still work.
//!
//! A `Buffer` is a local, not a scope: the code that uses it is written where it is declared.
//! (An earlier form took the using code as a closure, which compiled the buffer's set-up once
//! per closure type — a fifth of the problem-file layer's code; BENCHMARKS.md, "Build time".)
//!
//! [`with_slice`] is the same idea for callers outside the core (the inputs slice of a compiled
//! expression, `[q, q̇, t, θ]` and the like): its stack array is the smallest of a few sizes
//! that fits, so the unused tail that must be initialised stays short even for large dual
//! numbers.

/// Room for `len` values of `S` in the frame that declares it: an array of `CAP` if
/// `len ≤ CAP`, else the heap. Up to two values take an array of two, so that small systems do
/// not pay for filling a long array of hyper-dual numbers.
///
/// Declared empty, then filled in place ([`Buffer::filled`], [`Buffer::from_fn`]), which
/// hands out the slice: the storage is never returned or moved, so its array (hundreds of bytes
/// for dual numbers) is never copied — a constructor returning the filled buffer cost a
/// `memcpy` of the whole array per buffer where the build does not optimise across crates.
///
/// ```
/// use marsden::numerics::scratch::Buffer;
///
/// let mut squares = Buffer::<f64, 4>::empty();
/// let x = squares.from_fn(3, 0.0, |i| (i * i) as f64);
/// x[0] = 7.0;
/// assert_eq!(x, [7.0, 1.0, 4.0]);
/// ```
pub struct Buffer<S, const CAP: usize> {
    storage: Storage<S, CAP>,
}

/// Where a [`Buffer`]'s values live.
enum Storage<S, const CAP: usize> {
    Empty,
    Two([S; 2]),
    Inline([S; CAP]),
    Heap(Vec<S>),
}

impl<S: Copy, const CAP: usize> Buffer<S, CAP> {
    /// No values yet.
    #[inline(always)]
    pub const fn empty() -> Self {
        Buffer {
            storage: Storage::Empty,
        }
    }

    /// `len` copies of `fill` (which also pads the unused part of the array).
    #[inline(always)]
    pub fn filled(&mut self, len: usize, fill: S) -> &mut [S] {
        self.storage = if len <= 2 {
            Storage::Two([fill; 2])
        } else if len <= CAP {
            Storage::Inline([fill; CAP])
        } else {
            Storage::Heap(vec![fill; len])
        };
        match &mut self.storage {
            Storage::Empty => &mut [],
            Storage::Two(two) => &mut two[..len],
            Storage::Inline(inline) => &mut inline[..len],
            Storage::Heap(heap) => heap,
        }
    }

    /// The values `init(0) … init(len − 1)`; `fill` pads the unused part of the array.
    #[inline(always)]
    pub fn from_fn(&mut self, len: usize, fill: S, mut init: impl FnMut(usize) -> S) -> &mut [S] {
        let values = self.filled(len, fill);
        // A plain counted loop: this body is compiled once per `init` closure, and an
        // iterator chain would bring its adapters' code into every copy.
        let mut i = 0;
        while i < values.len() {
            values[i] = init(i);
            i += 1;
        }
        values
    }
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
        let values = |len| {
            Buffer::<f64, 4>::empty()
                .from_fn(len, 0.0, |i| i as f64)
                .to_vec()
        };
        let (two, small, large) = (values(2), values(3), values(6));
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
