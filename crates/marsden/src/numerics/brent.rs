//! Brent's method for a root of `f(x) = 0` inside a bracket `[a, b]` with `f(a) f(b) ≤ 0`
//! ([Bre73] chapter 4, the algorithm `zeroin`).
//!
//! Each iteration keeps a bracket `[b, c]` around the root (`f(b) f(c) ≤ 0`, `|f(b)| ≤ |f(c)|`)
//! and the previous iterate `a`, and tries, in order, inverse quadratic interpolation through
//! `a, b, c`, the secant through `a, b`, and bisection of `[b, c]`; an interpolated step is
//! taken only if it lands well inside the bracket and shrinks the steps geometrically, so the
//! method never needs many more evaluations than bisection (at most about the square of its
//! count) and converges superlinearly on smooth functions. It stops when the bracket is within
//! `2ε|b| + tol/2` of `b` (`ε` the machine epsilon, `tol` the caller's absolute tolerance) or
//! `f(b) = 0`.
//!
//! Why a short implementation here rather than a crate: of the crates that offer Brent's method,
//! `roots` (0.0.8) re-evaluates `f` at both ends of the bracket every iteration (three
//! evaluations where one suffices) and returns the third point rather than the best one once
//! converged, and `argmin` brings `rand` and its own math layer for a one-dimensional problem.
//! The event detector ([`crate::run::events`]) calls this once per sign change, where each
//! evaluation costs an interpolation and a Legendre transform.
//!
//! [Bre73]: crate#references

use thiserror::Error;

/// Options of [`find_root`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BrentOptions {
    /// Absolute tolerance on the root (added to the relative `2ε|x|`; 0 is allowed away from
    /// `x = 0`).
    pub x_tolerance: f64,
    /// Evaluations of `f` allowed (besides the two at the ends, which the caller supplies).
    pub max_evaluations: usize,
}

impl Default for BrentOptions {
    fn default() -> Self {
        Self {
            x_tolerance: 0.0,
            max_evaluations: 200,
        }
    }
}

/// A root found by [`find_root`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Root {
    /// The root's best estimate (the end of the final bracket with the smaller `|f|`).
    pub x: f64,
    /// `f(x)`.
    pub value: f64,
    /// The other end of the final bracket (the root lies between `x` and `other`).
    pub other: f64,
    /// Evaluations of `f` made (not counting the two supplied ends).
    pub evaluations: usize,
}

/// Why [`find_root`] found no root.
#[derive(Debug, Clone, Copy, PartialEq, Error)]
pub enum RootError {
    /// `f(a)` and `f(b)` have the same strict sign (or one of them is not finite).
    #[error("[{a}, {b}] does not bracket a root: f(a) = {fa}, f(b) = {fb}")]
    NotBracketed {
        /// Left end.
        a: f64,
        /// Right end.
        b: f64,
        /// `f(a)`.
        fa: f64,
        /// `f(b)`.
        fb: f64,
    },
    /// `f` returned a non-finite value inside the bracket.
    #[error("f({x}) = {value} is not finite")]
    NonFinite {
        /// Where.
        x: f64,
        /// The value.
        value: f64,
    },
    /// The evaluation budget was spent before the bracket shrank to the tolerance.
    #[error("no convergence in {evaluations} evaluations: the root lies in [{low}, {high}]")]
    Budget {
        /// Evaluations made.
        evaluations: usize,
        /// Lower end of the last bracket.
        low: f64,
        /// Upper end of the last bracket.
        high: f64,
    },
}

/// The bracket `[a, b]` of a root, with `fa = f(a)` and `fb = f(b)` of opposite signs (or one
/// of them zero), which the caller has evaluated already.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bracket {
    /// One end.
    pub a: f64,
    /// `f(a)`.
    pub fa: f64,
    /// The other end.
    pub b: f64,
    /// `f(b)`.
    pub fb: f64,
}

/// A root of `f` in `bracket`, by Brent's method ([Bre73] ch. 4, `zeroin`; see the [module](self) docs).
///
/// ```
/// use marsden::numerics::brent::{Bracket, BrentOptions, find_root};
/// let f = |x: f64| x.cos() - x;
/// let bracket = Bracket { a: 0.0, fa: f(0.0), b: 1.0, fb: f(1.0) };
/// let root = find_root(f, bracket, &BrentOptions::default()).unwrap();
/// assert!((root.x - 0.739_085_133_215_160_6).abs() < 2e-16);
/// ```
///
/// [Bre73]: crate#references
pub fn find_root<F: FnMut(f64) -> f64>(
    mut f: F,
    bracket: Bracket,
    options: &BrentOptions,
) -> Result<Root, RootError> {
    let Bracket { a, fa, b, fb } = bracket;
    if !(fa.is_finite() && fb.is_finite()) || fa * fb > 0.0 {
        return Err(RootError::NotBracketed { a, b, fa, fb });
    }
    let root = |x, value, other, evaluations| Root {
        x,
        value,
        other,
        evaluations,
    };
    if fa == 0.0 {
        return Ok(root(a, fa, a, 0));
    }
    if fb == 0.0 {
        return Ok(root(b, fb, b, 0));
    }
    let mut s = Search::new(bracket);
    for evaluations in 0..=options.max_evaluations {
        s.keep_best_in_b();
        let tol = 2.0 * f64::EPSILON * s.b.abs() + 0.5 * options.x_tolerance;
        let half = 0.5 * (s.c - s.b);
        if half.abs() <= tol || s.fb == 0.0 {
            return Ok(root(s.b, s.fb, s.c, evaluations));
        }
        if evaluations == options.max_evaluations {
            break;
        }
        let step = s.step(half, tol);
        s.a = s.b;
        s.fa = s.fb;
        s.b += if step.abs() > tol {
            step
        } else {
            tol.copysign(half)
        };
        s.fb = f(s.b);
        if !s.fb.is_finite() {
            return Err(RootError::NonFinite {
                x: s.b,
                value: s.fb,
            });
        }
        if (s.fb > 0.0) == (s.fc > 0.0) {
            s.restart_bracket();
        }
    }
    Err(RootError::Budget {
        evaluations: options.max_evaluations,
        low: s.b.min(s.c),
        high: s.b.max(s.c),
    })
}

/// The state of `zeroin`: the best iterate `b`, the other end `c` of the bracket, the previous
/// iterate `a`, and the last two steps `d`, `e`.
struct Search {
    a: f64,
    fa: f64,
    b: f64,
    fb: f64,
    c: f64,
    fc: f64,
    d: f64,
    e: f64,
}

impl Search {
    fn new(bracket: Bracket) -> Self {
        let Bracket { a, fa, b, fb } = bracket;
        let mut s = Self {
            a,
            fa,
            b,
            fb,
            c: a,
            fc: fa,
            d: 0.0,
            e: 0.0,
        };
        s.restart_bracket();
        s
    }

    /// `c = a`: the previous iterate becomes the other end of the bracket.
    fn restart_bracket(&mut self) {
        self.c = self.a;
        self.fc = self.fa;
        self.d = self.b - self.a;
        self.e = self.d;
    }

    /// Swaps so that `b` is the end with the smaller `|f|`.
    fn keep_best_in_b(&mut self) {
        if self.fc.abs() < self.fb.abs() {
            self.a = self.b;
            self.b = self.c;
            self.c = self.a;
            self.fa = self.fb;
            self.fb = self.fc;
            self.fc = self.fa;
        }
    }

    /// The next step from `b`: interpolation when it is safe, else bisection (`half`).
    fn step(&mut self, half: f64, tol: f64) -> f64 {
        if self.e.abs() >= tol && self.fa.abs() > self.fb.abs() {
            let s = self.fb / self.fa;
            let (mut p, mut q) = if self.a == self.c {
                // Secant through a and b.
                (2.0 * half * s, 1.0 - s)
            } else {
                // Inverse quadratic interpolation through a, b and c.
                let q = self.fa / self.fc;
                let r = self.fb / self.fc;
                let p = s * (2.0 * half * q * (q - r) - (self.b - self.a) * (r - 1.0));
                (p, (q - 1.0) * (r - 1.0) * (s - 1.0))
            };
            if p > 0.0 {
                q = -q;
            }
            p = p.abs();
            if 2.0 * p < 3.0 * half * q - (tol * q).abs() && p < (0.5 * self.e * q).abs() {
                self.e = self.d;
                self.d = p / q;
                return self.d;
            }
        }
        self.d = half;
        self.e = half;
        half
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    fn solve(f: impl FnMut(f64) -> f64 + Copy, a: f64, b: f64) -> Result<Root, RootError> {
        let mut g = f;
        let bracket = Bracket {
            a,
            fa: g(a),
            b,
            fb: g(b),
        };
        find_root(f, bracket, &BrentOptions::default())
    }

    /// The bracket `[a, b]` of `f`.
    fn ends(f: impl Fn(f64) -> f64, a: f64, b: f64) -> Bracket {
        Bracket {
            a,
            fa: f(a),
            b,
            fb: f(b),
        }
    }

    /// `x³ − 2x − 5` (Wallis's equation, Brent's own example): root 2.0945514815423265…
    #[test]
    fn wallis_cubic_to_round_off_in_few_evaluations() {
        let root = solve(|x| x * x * x - 2.0 * x - 5.0, 2.0, 3.0).unwrap();
        assert!((root.x - 2.094_551_481_542_326_5).abs() <= 4.0 * f64::EPSILON * 2.1);
        // Bisection needs ~52 halvings of [2, 3] for the same tolerance.
        assert!(root.evaluations <= 12, "{} evaluations", root.evaluations);
        let (lo, hi) = (root.x.min(root.other), root.x.max(root.other));
        assert!(lo <= 2.094_551_481_542_326_5 && 2.094_551_481_542_326_5 <= hi);
    }

    /// A root at an end of the bracket is returned without evaluation; so is the other end.
    #[test]
    fn zero_at_an_end() {
        let root = solve(|x| x - 1.0, 1.0, 2.0).unwrap();
        assert_eq!((root.x, root.evaluations), (1.0, 0));
        let root = solve(|x| x - 2.0, 1.0, 2.0).unwrap();
        assert_eq!((root.x, root.evaluations), (2.0, 0));
    }

    /// A function that is flat and then steep (`x^9` about 0.3) still converges, within the
    /// absolute tolerance asked for.
    #[test]
    fn flat_function_converges_to_the_tolerance() {
        let options = BrentOptions {
            x_tolerance: 1e-12,
            ..BrentOptions::default()
        };
        let f = |x: f64| (x - 0.3).powi(9);
        let root = find_root(f, ends(f, -1.0, 1.0), &options).unwrap();
        assert!((root.x - 0.3).abs() <= 1e-12, "{}", root.x);
    }

    /// A discontinuous sign change (a step function) is located like bisection would: the
    /// bracket shrinks to the jump.
    #[test]
    fn sign_jump_is_bracketed() {
        let f = |x: f64| if x < 0.123 { -1.0 } else { 1.0 };
        let root = solve(f, 0.0, 1.0).unwrap();
        assert!((root.x - 0.123).abs() <= 1e-15, "{}", root.x);
    }

    #[test]
    fn errors_are_values() {
        assert!(matches!(
            solve(|x| x * x + 1.0, -1.0, 1.0),
            Err(RootError::NotBracketed {
                fa: 2.0,
                fb: 2.0,
                ..
            })
        ));
        let f = |x: f64| if x > 0.25 { f64::NAN } else { x - 0.5 };
        let bracket = Bracket {
            a: 0.0,
            fa: -0.5,
            b: 1.0,
            fb: 0.5,
        };
        let error = find_root(f, bracket, &BrentOptions::default()).unwrap_err();
        assert!(matches!(error, RootError::NonFinite { .. }), "{error:?}");
        let options = BrentOptions {
            x_tolerance: 0.0,
            max_evaluations: 3,
        };
        let f = |x: f64| x.cos() - x;
        let error = find_root(f, ends(f, 0.0, 1.0), &options).unwrap_err();
        let RootError::Budget { low, high, .. } = error else {
            panic!("{error:?}")
        };
        assert!(low <= 0.739_085_133_215_160_6 && 0.739_085_133_215_160_6 <= high);
    }
}
