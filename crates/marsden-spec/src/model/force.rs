//! [`ExprForce`]: a generalised force `f(t, q, q̇)`, one expression per coordinate.

use marsden::{Force, Scalar};

use super::inputs::with_inputs;
use marsden_expr::ProgramSet;

/// A generalised force given as expressions over `[q, q̇, t]`; the empty set is no force
/// ([`Force::is_active`] is false, so the integrator skips all force work).
///
/// ```
/// use marsden::Force;
/// use marsden_expr::{ProgramSet, Symbols};
/// use marsden_spec::model::ExprForce;
///
/// let mut symbols = Symbols::with_inputs(["x", "x_dot", "t"]).unwrap();
/// symbols.add_constant("c", 0.5).unwrap();
/// let force = ExprForce::new(ProgramSet::compile(["-c*x_dot"], &symbols).unwrap());
/// let mut f = [0.0];
/// force.force(0.0, &[1.0], &[2.0], &mut f);
/// assert_eq!(f, [-1.0]);
/// ```
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ExprForce {
    components: ProgramSet,
}

impl ExprForce {
    /// Wraps one program per coordinate, compiled against `[q, q̇, t]`.
    pub fn new(components: ProgramSet) -> Self {
        Self { components }
    }

    /// No force.
    pub fn none() -> Self {
        Self::default()
    }

    /// The compiled components.
    pub fn components(&self) -> &ProgramSet {
        &self.components
    }
}

impl Force for ExprForce {
    #[inline]
    fn force<S: Scalar>(&self, t: S, q: &[S], v: &[S], out: &mut [S]) {
        if self.components.is_empty() {
            out.iter_mut().for_each(|f| *f = S::from(0.0));
        } else {
            with_inputs(q, v, t, |x| self.components.eval_into(x, out));
        }
    }

    fn is_active(&self) -> bool {
        !self.components.is_empty()
    }
}
