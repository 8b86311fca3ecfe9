//! [`ExprConstraint`]: holonomic constraints `φ(q) = 0`, one expression each.

use marsden::{Constraint, Scalar};

use marsden_expr::ProgramSet;

/// Holonomic constraints given as expressions over the coordinates; the empty set is
/// unconstrained (`count() = 0`, so the integrator adds no multipliers).
///
/// ```
/// use marsden::Constraint;
/// use marsden_expr::{ProgramSet, Symbols};
/// use marsden_problem::model::ExprConstraint;
///
/// let mut symbols = Symbols::with_inputs(["x", "y"]).unwrap();
/// symbols.add_constant("l", 1.0).unwrap();
/// let c = ExprConstraint::new(ProgramSet::compile(["x^2 + y^2 - l^2"], &symbols).unwrap());
/// let mut phi = [0.0_f64];
/// c.constraint(&[0.6, 0.8], &mut phi);
/// assert!(phi[0].abs() < 1e-15);
/// ```
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ExprConstraint {
    components: ProgramSet,
}

impl ExprConstraint {
    /// Wraps one program per constraint, compiled against the coordinates `[q₁ … qₙ]`.
    pub fn new(components: ProgramSet) -> Self {
        Self { components }
    }

    /// No constraints.
    pub fn none() -> Self {
        Self::default()
    }

    /// The compiled constraint functions.
    pub fn components(&self) -> &ProgramSet {
        &self.components
    }

    /// `max_i |φ_i(q)|` (0 without constraints): the residual written per sample.
    pub fn residual(&self, q: &[f64], scratch: &mut Vec<f64>) -> f64 {
        scratch.resize(self.count(), 0.0);
        self.constraint(q, scratch);
        marsden::numerics::dense::max_norm(scratch)
    }
}

impl Constraint for ExprConstraint {
    fn count(&self) -> usize {
        self.components.len()
    }

    #[inline]
    fn constraint<S: Scalar>(&self, q: &[S], out: &mut [S]) {
        self.components.eval_into(q, out);
    }
}
