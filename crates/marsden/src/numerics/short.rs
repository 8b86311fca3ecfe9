//! Element-wise operations on the short vectors of most problems (one to three coordinates),
//! written out for those lengths.
//!
//! A step of a small system copies and combines a handful of numbers several times: at these
//! lengths a call of `memcpy`, or the set-up of a vectorised loop, costs more than the work
//! (measured on the pendulum's midpoint step: the predictor's extrapolation, its history and
//! the update of the state took about a fifth of the step's instructions before these were
//! written out; BENCHMARKS.md). Longer vectors take the general loop. The arithmetic is the
//! same in both, element by element, so the results are the same bit for bit.

/// `dst ← src` (slices of equal length; a longer one panics, as `copy_from_slice` does).
#[inline(always)]
pub fn copy(dst: &mut [f64], src: &[f64]) {
    match (dst, src) {
        ([d], [s]) => *d = *s,
        ([d0, d1], [s0, s1]) => (*d0, *d1) = (*s0, *s1),
        ([d0, d1, d2], [s0, s1, s2]) => (*d0, *d1, *d2) = (*s0, *s1, *s2),
        (dst, src) => dst.copy_from_slice(src),
    }
}

/// `dst ← dst + src`, element by element (over the shorter of the two).
#[inline(always)]
pub fn add(dst: &mut [f64], src: &[f64]) {
    match (dst, src) {
        ([d], [s]) => *d += s,
        ([d0, d1], [s0, s1]) => {
            *d0 += s0;
            *d1 += s1;
        }
        ([d0, d1, d2], [s0, s1, s2]) => {
            *d0 += s0;
            *d1 += s1;
            *d2 += s2;
        }
        (dst, src) => dst.iter_mut().zip(src).for_each(|(d, s)| *d += s),
    }
}

/// `dst[i] ← f(a[i], b[i], c[i])` (over the shortest of the four).
#[inline(always)]
pub fn combine3(
    dst: &mut [f64],
    a: &[f64],
    b: &[f64],
    c: &[f64],
    f: impl Fn(f64, f64, f64) -> f64,
) {
    match (dst, a, b, c) {
        ([d], [a], [b], [c]) => *d = f(*a, *b, *c),
        ([d0, d1], [a0, a1], [b0, b1], [c0, c1]) => {
            (*d0, *d1) = (f(*a0, *b0, *c0), f(*a1, *b1, *c1));
        }
        ([d0, d1, d2], [a0, a1, a2], [b0, b1, b2], [c0, c1, c2]) => {
            (*d0, *d1, *d2) = (f(*a0, *b0, *c0), f(*a1, *b1, *c1), f(*a2, *b2, *c2));
        }
        (dst, a, b, c) => {
            let sources = a.iter().zip(b).zip(c);
            for (d, ((a, b), c)) in dst.iter_mut().zip(sources) {
                *d = f(*a, *b, *c);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every length (the written-out ones and the general loop) gives the loop's values.
    #[test]
    fn written_out_lengths_give_the_general_loops_values() {
        for n in 1..=5 {
            let a: Vec<f64> = (0..n).map(|i| 0.1 * f64::from(i) + 1.0 / 3.0).collect();
            let b: Vec<f64> = (0..n).map(|i| f64::from(i * i) - 0.7).collect();
            let c: Vec<f64> = (0..n).map(|i| 1e-3 * f64::from(i) - 2.5).collect();
            let mut d = vec![0.0; n as usize];
            copy(&mut d, &a);
            assert_eq!(d, a);
            add(&mut d, &b);
            let sum: Vec<f64> = a.iter().zip(&b).map(|(x, y)| x + y).collect();
            assert_eq!(d, sum);
            combine3(&mut d, &a, &b, &c, |x, y, z| 3.0 * (x - y) + z);
            let want: Vec<f64> = (0..n as usize)
                .map(|i| 3.0 * (a[i] - b[i]) + c[i])
                .collect();
            assert_eq!(d, want);
        }
    }
}
