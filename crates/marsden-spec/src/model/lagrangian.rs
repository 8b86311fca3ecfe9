//! [`ExprLagrangian`]: `L(t, q, q̇)` from a compiled expression.

use marsden::{Lagrangian, Scalar};

use super::inputs::with_inputs;
use marsden_expr::Program;

/// A Lagrangian given as an expression over `[q, q̇, t]` (names `theta`, `theta_dot`, `t`).
///
/// ```
/// use marsden::Lagrangian;
/// use marsden_expr::{Program, Symbols};
/// use marsden_spec::model::ExprLagrangian;
///
/// let symbols = Symbols::with_inputs(["theta", "theta_dot", "t"]).unwrap();
/// let program = Program::compile("0.5*theta_dot^2 + cos(theta)", &symbols).unwrap();
/// let lagrangian = ExprLagrangian::new(program, 1);
/// assert_eq!(lagrangian.lagrangian(0.0, &[0.0], &[2.0]), 3.0);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ExprLagrangian {
    program: Program,
    dof: usize,
}

impl ExprLagrangian {
    /// Wraps a program compiled against the inputs `[q₁ … qₙ, q̇₁ … q̇ₙ, t]` (n = `dof`).
    pub fn new(program: Program, dof: usize) -> Self {
        Self { program, dof }
    }

    /// The compiled expression.
    pub fn program(&self) -> &Program {
        &self.program
    }
}

impl Lagrangian for ExprLagrangian {
    fn dof(&self) -> usize {
        self.dof
    }

    #[inline]
    fn lagrangian<S: Scalar>(&self, t: S, q: &[S], v: &[S]) -> S {
        with_inputs(q, v, t, |x| self.program.eval(x))
    }
}
