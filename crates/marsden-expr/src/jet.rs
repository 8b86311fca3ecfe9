//! [`Jet`]: a program's value, gradient and Hessian as tapes, for evaluating it at dual numbers
//! through its Taylor data (`marsden::numerics::dual::compose`) instead of dual arithmetic.
//!
//! The derivatives are the symbolic ones of `derive` (every rule reusing the function's own
//! nodes), and each tape merges value and derivatives into one graph, so a subexpression
//! shared by them (`cos(θ₁ − θ₂)` in `L` and in its partials) is evaluated once.

use crate::derive::{depends, derivative};
use crate::ir::Node;
use crate::program::Program;
use crate::tape::{Tape, TapeBuilder};

/// The Taylor data of a program of `m` inputs as two tapes over the same inputs:
/// [`Jet::first`] `[f, ∂₀f, …, ∂ₘ₋₁f]` and [`Jet::second`] the same followed by `∂ₖₗf` for
/// `k ≤ l`, row by row.
///
/// ```
/// use marsden_expr::{Program, Symbols};
///
/// let symbols = Symbols::with_inputs(["x", "y"]).unwrap();
/// let program = Program::compile("x^2*y + sin(y)", &symbols).unwrap();
/// let jet = program.jet(2).unwrap();
/// let (mut regs, mut out) = (Vec::new(), vec![0.0_f64; jet.second().len()]);
/// jet.second().eval_into(&[3.0, 0.0], &mut regs, &mut out);
/// // f, ∂x f = 2xy, ∂y f = x² + cos y, ∂xx f = 2y, ∂xy f = 2x, ∂yy f = −sin y
/// assert_eq!(out, [0.0, 0.0, 10.0, 0.0, 6.0, 0.0]);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Jet {
    inputs: usize,
    first: Tape,
    second: Tape,
}

impl Jet {
    /// Number of inputs `m` the derivatives are taken in.
    pub fn input_len(&self) -> usize {
        self.inputs
    }

    /// `[f, ∂₀f, …, ∂ₘ₋₁f]`.
    pub fn first(&self) -> &Tape {
        &self.first
    }

    /// `[f, ∂₀f, …, ∂ₘ₋₁f, ∂₀₀f, ∂₀₁f, …, ∂₀,ₘ₋₁f, ∂₁₁f, …, ∂ₘ₋₁,ₘ₋₁f]`.
    pub fn second(&self) -> &Tape {
        &self.second
    }
}

impl Program {
    /// The value, gradient and Hessian in the first `inputs` input slots as tapes; `None` if
    /// the program reads a slot beyond them or uses a function without a symbolic derivative
    /// (`abs`).
    pub fn jet(&self, inputs: usize) -> Option<Jet> {
        if self.input_len() > inputs {
            return None;
        }
        let f = self.tree();
        let gradient: Vec<Node> = (0..inputs)
            .map(|k| derivative(f, k))
            .collect::<Option<_>>()?;
        let mut hessian = Vec::with_capacity(inputs * (inputs + 1) / 2);
        for (k, g) in gradient.iter().enumerate() {
            for l in k..inputs {
                hessian.push(derivative(g, l)?);
            }
        }
        let first = std::iter::once(f).chain(&gradient);
        Some(Jet {
            inputs,
            first: tape(first.clone()),
            second: tape(first.chain(&hessian)),
        })
    }
}

impl Program {
    /// The partial derivatives in the first `slots` input slots when none of them depends on
    /// any input (a program linear in those slots, with constant coefficients: `mgl*R33`), as
    /// numbers; `None` otherwise, or for a function without a symbolic derivative.
    ///
    /// ```
    /// use marsden_expr::{Program, Symbols};
    ///
    /// let symbols = Symbols::with_inputs(["a", "b", "t"]).unwrap();
    /// let linear = Program::compile("3*a - b/2 + t^2", &symbols).unwrap();
    /// assert_eq!(linear.constant_gradient(2), Some(vec![3.0, -0.5]));
    /// let curved = Program::compile("a*b", &symbols).unwrap();
    /// assert_eq!(curved.constant_gradient(2), None);
    /// ```
    pub fn constant_gradient(&self, slots: usize) -> Option<Vec<f64>> {
        let gradient: Vec<Node> = (0..slots)
            .map(|k| derivative(self.tree(), k))
            .collect::<Option<_>>()?;
        if gradient.iter().any(|g| depends(g, &|_| true)) {
            return None;
        }
        let tape = tape(gradient.iter());
        let (mut regs, mut out) = (Vec::new(), vec![0.0; slots]);
        tape.eval_into(&vec![0.0; tape.input_len()], &mut regs, &mut out);
        Some(out)
    }
}

fn tape<'a>(nodes: impl Iterator<Item = &'a Node>) -> Tape {
    let mut builder = TapeBuilder::default();
    nodes.for_each(|node| builder.output(node));
    builder.finish()
}
