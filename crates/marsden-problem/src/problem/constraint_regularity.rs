//! Constraints whose gradient vanishes on their zero set (`φ = (x² + y² − 1)²`), refused when
//! the file is read, with or without `project = true`.
//!
//! The constraint forces are `−Dφ(q)ᵀλ` ([MW01] §3.5, [HLW06] §VII.1): where `∇φ_i = 0` on
//! `φ_i = 0` they cannot act, the multipliers are undetermined and every step's Newton matrix
//! is singular. Without `project` the start is on the zero set; with it the projection still
//! reaches the zero set (linearly, not quadratically), and the run failed at step 0.
//!
//! The check follows each constraint from `q₀` to its zero set by scalar Newton steps
//! `q ← q − φ_i(q) ∇φ_i(q)/|∇φ_i(q)|²` (the minimum-norm correction, as the projection takes),
//! to their fixed point `q*`. There it compares `|∇φ_i(q*)|` with `|∇φ_i|` at `q* ± δ n`
//! (`n` the unit normal, `δ = 10⁻⁴ max(|q₀|∞, |q*|∞)`): at a simple root the two agree to
//! `O(δ |D²φ_i| / |∇φ_i|)`; at a root of multiplicity `m ≥ 2` the gradient vanishes with `φ_i`
//! (`∇(g^m) = m g^{m−1} ∇g`), and the ratio is round-off. A constraint whose steps find no zero
//! set near `q₀` is left to the projection and the start checks, which say so.
//!
//! [MW01]: marsden#references
//! [HLW06]: marsden#references

use marsden::Constraint;
use marsden::numerics::ad::{MultiFunction, jacobian};
use marsden::numerics::dense::{max_norm, max_or_nan};

use crate::model::ExprConstraint;

/// Most Newton steps towards the zero set (a double root halves the distance per step: from
/// 1 to round-off in about 60).
const MAX_STEPS: usize = 200;
/// Relative offset `δ` of the points beside the root.
const BESIDE: f64 = 1e-4;
/// `|∇φ_i|` at the root below this fraction of its value beside it: the gradient vanishes.
const VANISHING: f64 = 1e-3;

/// A constraint whose gradient vanishes on its zero set, with the numbers that show it.
#[derive(Debug, Clone, PartialEq)]
pub struct VanishingGradient {
    /// Which constraint.
    pub index: usize,
    /// The point `q*` of the zero set reached from `q₀`.
    pub at: Vec<f64>,
    /// `|∇φ_i(q*)|`.
    pub gradient: f64,
    /// `max |∇φ_i(q* ± δ n)|`.
    pub beside: f64,
    /// `δ`.
    pub offset: f64,
}

/// The first constraint of `c` whose gradient vanishes on the zero set it reaches from `q0`.
pub fn vanishing_gradient(c: &ExprConstraint, q0: &[f64]) -> Option<VanishingGradient> {
    let probe = Probe::new(c, q0.len());
    (0..c.count()).find_map(|i| probe.check(i, q0))
}

/// `φ` and `Dφ` of the constraints at a point.
struct Probe<'a> {
    constraint: &'a ExprConstraint,
    n: usize,
}

impl MultiFunction for Probe<'_> {
    fn inputs(&self) -> usize {
        self.n
    }
    fn outputs(&self) -> usize {
        self.constraint.count()
    }
    fn eval<S: marsden::Scalar>(&self, x: &[S], out: &mut [S]) {
        self.constraint.constraint(x, out);
    }
}

impl<'a> Probe<'a> {
    fn new(constraint: &'a ExprConstraint, n: usize) -> Self {
        Self { constraint, n }
    }

    /// `(φ_i(q), ∇φ_i(q))`.
    fn at(&self, i: usize, q: &[f64]) -> (f64, Vec<f64>) {
        let (d, n) = (self.constraint.count(), self.n);
        let (mut phi, mut jac) = (vec![0.0; d], vec![0.0; d * n]);
        jacobian(self, q, 0..n, &mut phi, &mut jac);
        (phi[i], jac[i * n..(i + 1) * n].to_vec())
    }

    /// Follows constraint `i` from `q0` to its zero set and compares the gradient there with
    /// the gradient beside it.
    fn check(&self, i: usize, q0: &[f64]) -> Option<VanishingGradient> {
        let (q, normal) = self.zero_of(i, q0)?;
        let (_, g) = self.at(i, &q);
        let gradient = norm(&g);
        // Along the normal; where no gradient was ever seen (a start on the zero set with
        // `∇φ_i = 0` exactly), along each coordinate axis.
        let directions: Vec<Vec<f64>> = match (gradient > 0.0, normal) {
            (true, _) => vec![g.iter().map(|x| x / gradient).collect()],
            (false, Some(normal)) => vec![normal],
            (false, None) => (0..self.n)
                .map(|k| (0..self.n).map(|j| f64::from(u8::from(j == k))).collect())
                .collect(),
        };
        let scale = max_norm(q0).max(max_norm(&q));
        let offset = BESIDE * if scale > 0.0 { scale } else { 1.0 };
        let beside_along = |direction: &Vec<f64>, sign: f64| -> f64 {
            let shifted: Vec<f64> = (q.iter().zip(direction))
                .map(|(x, n)| x + sign * offset * n)
                .collect();
            norm(&self.at(i, &shifted).1)
        };
        let beside = (directions.iter())
            .flat_map(|d| [beside_along(d, 1.0), beside_along(d, -1.0)])
            // A NaN beside the zero propagates (`f64::max` would drop it and judge the
            // gradient against the finite samples only); the refusal then needs a finite one.
            .fold(0.0, max_or_nan);
        let vanishes = gradient <= VANISHING * beside || gradient == 0.0;
        (vanishes && beside.is_finite()).then_some(VanishingGradient {
            index: i,
            at: q,
            gradient,
            beside,
            offset,
        })
    }

    /// The fixed point of the scalar Newton steps of constraint `i` from `q0`, and the last
    /// unit normal seen; `None` if the steps leave the finite numbers or do not settle.
    fn zero_of(&self, i: usize, q0: &[f64]) -> Option<(Vec<f64>, Option<Vec<f64>>)> {
        let mut q = q0.to_vec();
        let mut normal = None;
        let settled = 1e-10 * max_norm(q0).max(1.0);
        for _ in 0..MAX_STEPS {
            let (value, g) = self.at(i, &q);
            let g2: f64 = g.iter().map(|x| x * x).sum();
            if !value.is_finite() || !g2.is_finite() {
                return None;
            }
            if value == 0.0 || g2 == 0.0 {
                return (value == 0.0).then_some((q, normal));
            }
            let length = g2.sqrt();
            normal = Some(g.iter().map(|x| x / length).collect());
            let step = value / g2;
            for (x, gi) in q.iter_mut().zip(&g) {
                *x -= step * gi;
            }
            if step.abs() * length <= f64::EPSILON * 1e-3 * max_norm(&q).max(f64::MIN_POSITIVE) {
                break;
            }
        }
        // Settled: the last step was negligible (a root reached, simple or multiple).
        let (value, g) = self.at(i, &q);
        let g2: f64 = g.iter().map(|x| x * x).sum();
        let last = if g2 > 0.0 {
            value.abs() / g2.sqrt()
        } else {
            0.0
        };
        (last <= settled && value.is_finite()).then_some((q, normal))
    }
}

/// Euclidean norm.
fn norm(x: &[f64]) -> f64 {
    x.iter().map(|v| v * v).sum::<f64>().sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use marsden_expr::{ProgramSet, Symbols};

    fn constraint(text: &str) -> ExprConstraint {
        let symbols = Symbols::with_inputs(["x", "y"]).unwrap();
        ExprConstraint::new(ProgramSet::compile([text], &symbols).unwrap())
    }

    /// A square, a cube and `y²` vanish to higher order on their zero sets: refused from a start
    /// off the manifold (`project = true`) and from one on it.
    #[test]
    fn multiple_roots_are_found_from_on_and_off_the_manifold() {
        for text in ["(x^2 + y^2 - 1)^2", "(x^2 + y^2 - 1)^3", "y^2"] {
            let c = constraint(text);
            for q0 in [[0.6, -0.9], [0.6, -0.8], [0.0, 0.0]] {
                if text != "y^2" && q0 == [0.0, 0.0] {
                    continue;
                }
                let found = vanishing_gradient(&c, &q0);
                let v = found.unwrap_or_else(|| panic!("{text} from {q0:?}"));
                assert_eq!(v.index, 0);
                assert!(v.gradient <= 1e-6 * v.beside, "{text}: {v:?}");
            }
        }
    }

    /// Simple roots pass: the circle (on and off it), a line through the origin, a small
    /// circle in small units, and a constraint with no zero near the start (left to the
    /// projection).
    #[test]
    fn simple_roots_pass() {
        let cases: [(&str, [f64; 2]); 6] = [
            ("x^2 + y^2 - 1", [0.6, -0.9]),
            ("x^2 + y^2 - 1", [0.6, -0.8]),
            ("y", [0.3, 0.0]),
            ("x - y", [0.0, 0.0]),
            ("x^2 + y^2 - 1e-14", [1e-7, 0.0]),
            ("x^2 + y^2 + 1", [0.5, 0.5]),
        ];
        for (text, q0) in cases {
            assert_eq!(vanishing_gradient(&constraint(text), &q0), None, "{text}");
        }
    }
}
