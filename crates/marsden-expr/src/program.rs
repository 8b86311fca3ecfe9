//! [`Program`]: one compiled expression, evaluated generically over [`Scalar`].
//!
//! A program is built by the pipeline ([`Expr::compile`](crate::Expr::compile) or
//! [`Program::compile`], in `pipeline`): this module holds only the compiled result.

use std::fmt;

use marsden::Scalar;

use crate::error::EvalError;
use crate::eval::evaluate;
use crate::ir::Node;
#[cfg(test)]
use crate::ops::Op;
use crate::ops::{Code, Leaf};

/// A compiled expression: constants folded, names resolved to input slots, ready to evaluate
/// at `f64` or at any dual number.
///
/// ```
/// use marsden_expr::{Program, Symbols};
/// let mut symbols = Symbols::with_inputs(["theta", "theta_dot"]).unwrap();
/// symbols.add_constant("m", 1.0).unwrap().add_constant("l", 2.0).unwrap();
/// symbols.add_constant("g", 9.81).unwrap();
/// let lagrangian =
///     Program::compile("0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)", &symbols).unwrap();
/// let value: f64 = lagrangian.eval(&[0.0, 1.0]);
/// assert!((value - (2.0 + 2.0 * 9.81)).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Program {
    code: Code,
    /// The folded tree the code was generated from (for symbolic work: [`Program::separable`]).
    tree: Node,
    text: String,
    names: Vec<String>,
    inputs_used: Vec<usize>,
}

impl Program {
    /// The program of `code`, generated from `tree` and compiled from `text`, using the
    /// declared `names` and reading the input slots `inputs_used` (sorted, no duplicates).
    pub(crate) fn new(
        code: Code,
        tree: Node,
        text: &str,
        names: Vec<String>,
        inputs_used: Vec<usize>,
    ) -> Self {
        Program {
            code,
            tree,
            text: text.to_owned(),
            names,
            inputs_used,
        }
    }

    /// Evaluate at `inputs` (indexed by the slots of the symbol table).
    ///
    /// # Panics
    ///
    /// If `inputs.len() < self.input_len()`, like indexing a slice out of bounds; use
    /// [`Program::try_eval`] to get an error instead.
    #[inline]
    pub fn eval<S: Scalar>(&self, inputs: &[S]) -> S {
        assert!(
            inputs.len() >= self.input_len(),
            "expression `{}` needs {} inputs, got {}",
            self.text,
            self.input_len(),
            inputs.len()
        );
        evaluate(&self.code, inputs)
    }

    /// Evaluate at `inputs`, or report that the slice is too short.
    #[inline]
    pub fn try_eval<S: Scalar>(&self, inputs: &[S]) -> Result<S, EvalError> {
        if inputs.len() < self.input_len() {
            return Err(EvalError::TooFewInputs {
                needed: self.input_len(),
                given: inputs.len(),
            });
        }
        Ok(evaluate(&self.code, inputs))
    }

    /// The source text.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// The declared names the source text uses (inputs and constants), sorted. Names whose
    /// contribution folded away (as in `x^0`) are still listed.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// The input slots the compiled program reads, sorted.
    pub fn inputs_used(&self) -> &[usize] {
        &self.inputs_used
    }

    /// The minimum length of the inputs slice: largest slot read + 1 (0 if none).
    #[inline]
    pub fn input_len(&self) -> usize {
        self.inputs_used.last().map_or(0, |slot| slot + 1)
    }

    /// Number of instructions, counting the initial load.
    pub fn op_count(&self) -> usize {
        1 + self.code.ops.len()
    }

    /// Largest number of values the evaluation stack holds besides the accumulator.
    pub fn stack_depth(&self) -> usize {
        self.code.depth
    }

    /// The value, if the whole expression folded to a constant.
    pub fn as_constant(&self) -> Option<f64> {
        match (self.code.first, self.code.ops.is_empty()) {
            (Leaf::Const(c), true) => Some(c),
            _ => None,
        }
    }

    /// The folded tree.
    pub(crate) fn tree(&self) -> &Node {
        &self.tree
    }

    #[cfg(test)]
    pub(crate) fn ops(&self) -> &[Op] {
        &self.code.ops
    }
}

/// A listing of the compiled instructions, one per line.
impl fmt::Display for Program {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.code.first)?;
        for op in &self.code.ops {
            write!(f, "\n{op}")?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Symbols;
    use crate::functions::Unary;

    fn pendulum_symbols() -> Symbols {
        let mut s = Symbols::with_inputs(["theta", "theta_dot"]).unwrap();
        s.add_constant("m", 2.0)
            .unwrap()
            .add_constant("l", 3.0)
            .unwrap();
        s.add_constant("g", 10.0).unwrap();
        s
    }

    #[test]
    fn pendulum_compiles_to_five_instructions() {
        let p = Program::compile(
            "0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)",
            &pendulum_symbols(),
        )
        .unwrap();
        assert_eq!(p.code.first, Leaf::Input(1));
        assert_eq!(
            p.ops(),
            [
                Op::Square,
                Op::MulConst(9.0),
                Op::PushCall(0, Unary::Cos),
                Op::MulConstAdd(60.0),
            ]
        );
        assert_eq!(p.op_count(), 5);
        assert_eq!(p.stack_depth(), 1);
        assert_eq!(p.to_string().lines().count(), 5);
        assert_eq!(p.names(), ["g", "l", "m", "theta", "theta_dot"]);
        assert_eq!(p.inputs_used(), [0, 1]);
    }

    #[test]
    fn scattered_constant_factors_are_merged() {
        let p = Program::compile("m*theta_dot*l*2", &pendulum_symbols()).unwrap();
        assert_eq!(p.code.first, Leaf::Input(1));
        assert_eq!(p.ops(), [Op::MulConst(12.0)]);
        let p = Program::compile("theta_dot^2*m*l^2/2", &pendulum_symbols()).unwrap();
        assert_eq!(p.ops(), [Op::Square, Op::MulConst(9.0)]);
    }

    #[test]
    fn operands_read_directly_from_inputs_and_constants() {
        let p = Program::compile("1 - theta*theta_dot", &pendulum_symbols()).unwrap();
        assert_eq!(p.ops(), [Op::MulInput(1), Op::ConstSub(1.0)]);
        let p = Program::compile("2/theta - theta_dot", &pendulum_symbols()).unwrap();
        assert_eq!(p.code.first, Leaf::Const(2.0));
        assert_eq!(p.ops(), [Op::DivInput(0), Op::SubInput(1)]);
    }

    #[test]
    fn constant_expressions_fold_completely() {
        let p = Program::compile("m*g*l + sin(pi/2)^2 - 2^3^2", &pendulum_symbols()).unwrap();
        assert_eq!(p.as_constant(), Some(60.0 + 1.0 - 512.0));
        assert_eq!(p.op_count(), 1);
        assert_eq!(p.input_len(), 0);
        assert_eq!(p.eval::<f64>(&[]), -451.0);
    }
}
