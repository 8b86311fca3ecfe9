//! [`SeparableForm`]: a Lagrangian expression recognised as `L = ½ vᵀ M v − V(t, q)`, with the
//! gradient and Hessian of `V` by symbolic differentiation.
//!
//! The recognition is exact (`quadratic`): a constant symmetric positive definite `M`, no term
//! linear in the velocities, no mass depending on `q` or `t`. `∇V` and the entries of `∇²V`
//! that are not identically zero are differentiated symbolically (`derive`) and laid out in
//! one [`Tape`] each, so their common subexpressions are evaluated once; the structural zeros
//! of `∇²V` give its bandwidth. An expression using `abs` has no symbolic derivative: its
//! gradient and Hessian are then left to automatic differentiation (`None` below).

use crate::derive::derivative;
use crate::ir::Node;
use crate::program::Program;
use crate::quadratic::split;
use crate::tape::{Tape, TapeBuilder};

/// The separable form of a Lagrangian expression (see [`Program::separable`]).
#[derive(Debug, Clone, PartialEq)]
pub struct SeparableForm {
    n: usize,
    mass: Vec<f64>,
    potential: Tape,
    gradient: Option<Tape>,
    hessian: Option<Tape>,
    entries: Vec<(usize, usize)>,
    bandwidth: usize,
}

impl SeparableForm {
    /// Degrees of freedom.
    pub fn dof(&self) -> usize {
        self.n
    }

    /// `M`, dense row-major `n × n`.
    pub fn mass(&self) -> &[f64] {
        &self.mass
    }

    /// The diagonal of `M`, if `M` is diagonal.
    pub fn diagonal_mass(&self) -> Option<Vec<f64>> {
        let n = self.n;
        let off_diagonal = (0..n).any(|i| (0..n).any(|j| i != j && self.mass[i * n + j] != 0.0));
        (!off_diagonal).then(|| (0..n).map(|i| self.mass[i * n + i]).collect())
    }

    /// `V(t, q)`, one output, over the inputs `[q₁ … qₙ, t]`.
    pub fn potential(&self) -> &Tape {
        &self.potential
    }

    /// `∇V(t, q)`, n outputs over `[q₁ … qₙ, t]`; `None` without a symbolic derivative.
    pub fn gradient(&self) -> Option<&Tape> {
        self.gradient.as_ref()
    }

    /// The entries of `∇²V(t, q)` listed by [`SeparableForm::hessian_entries`], over
    /// `[q₁ … qₙ, t]`; `None` without a symbolic derivative.
    pub fn hessian(&self) -> Option<&Tape> {
        self.hessian.as_ref()
    }

    /// The entries `(i, j)`, `i ≤ j`, of `∇²V` that are not identically zero, in the order of
    /// the outputs of [`SeparableForm::hessian`].
    pub fn hessian_entries(&self) -> &[(usize, usize)] {
        &self.entries
    }

    /// Half-bandwidth of `∇²V`: the largest `j − i` of a non-zero entry (`n − 1` when the
    /// Hessian has no symbolic form).
    pub fn bandwidth(&self) -> usize {
        self.bandwidth
    }
}

impl Program {
    /// The separable form of this Lagrangian, compiled over `[q₁ … qₙ, q̇₁ … q̇ₙ, t]` with
    /// `n = dof`: `Some` exactly when the folded expression is `½ q̇ᵀ M q̇ − V(t, q)` with a
    /// constant symmetric positive definite `M` (see the module documentation of what is
    /// recognised).
    ///
    /// ```
    /// use marsden_expr::{Program, Symbols};
    /// let symbols = Symbols::with_inputs(["x", "y", "x_dot", "y_dot", "t"]).unwrap();
    /// let kepler = Program::compile("0.5*(x_dot^2 + y_dot^2) + 1/sqrt(x^2 + y^2)", &symbols).unwrap();
    /// let form = kepler.separable(2).unwrap();
    /// assert_eq!(form.diagonal_mass(), Some(vec![1.0, 1.0]));
    /// let (mut grad, mut regs) = ([0.0_f64; 2], Vec::new());
    /// form.gradient().unwrap().eval_into(&[3.0, 4.0, 0.0], &mut regs, &mut grad);
    /// assert!((grad[0] - 3.0 / 125.0).abs() < 1e-15 && (grad[1] - 4.0 / 125.0).abs() < 1e-15);
    ///
    /// let magnetic = Program::compile("0.5*(x_dot^2 + y_dot^2) + x*y_dot", &symbols).unwrap();
    /// assert!(magnetic.separable(2).is_none());
    /// ```
    pub fn separable(&self, dof: usize) -> Option<SeparableForm> {
        let n = dof;
        if self.input_len() > 2 * n + 1 {
            return None;
        }
        let split = split(self.tree(), n)?;
        // Inputs `[q, t]`: the time slot moves from 2n to n.
        let potential = remap(&split.potential, n);
        let mut builder = TapeBuilder::default();
        builder.output(&potential);
        let gradient: Option<Vec<Node>> = (0..n).map(|i| derivative(&potential, i)).collect();
        let hessian = gradient.as_ref().and_then(|g| hessian_entries(g, n));
        let entries: Vec<(usize, usize)> = match &hessian {
            Some(h) => h.iter().map(|(ij, _)| *ij).collect(),
            None => Vec::new(),
        };
        let bandwidth = match &hessian {
            Some(_) => entries.iter().map(|(i, j)| j - i).max().unwrap_or(0),
            None => n.saturating_sub(1),
        };
        Some(SeparableForm {
            n,
            mass: split.mass,
            potential: builder.finish(),
            gradient: gradient.map(|g| tape(g.iter())),
            hessian: hessian.map(|h| tape(h.iter().map(|(_, node)| node))),
            entries,
            bandwidth,
        })
    }
}

/// The entries `(i, j)`, `i ≤ j`, of the Jacobian of `gradient` that are not identically zero;
/// `None` if one has no symbolic derivative.
fn hessian_entries(gradient: &[Node], n: usize) -> Option<Vec<((usize, usize), Node)>> {
    let mut entries = Vec::new();
    for (i, g) in gradient.iter().enumerate() {
        for j in i..n {
            let d = derivative(g, j)?;
            if d.as_const() != Some(0.0) {
                entries.push(((i, j), d));
            }
        }
    }
    Some(entries)
}

fn tape<'a>(nodes: impl Iterator<Item = &'a Node>) -> Tape {
    let mut builder = TapeBuilder::default();
    nodes.for_each(|node| builder.output(node));
    builder.finish()
}

/// `node` over `[q, t]` instead of `[q, v, t]` (it reads no velocity).
fn remap(node: &Node, n: usize) -> Node {
    let b = |a: &Node| Box::new(remap(a, n));
    match node {
        Node::Const(c) => Node::Const(*c),
        Node::Input(slot) => Node::Input(if *slot == 2 * n { n } else { *slot }),
        Node::Neg(a) => Node::Neg(b(a)),
        Node::Bin(op, x, y) => Node::Bin(*op, b(x), b(y)),
        Node::Unary(f, a) => Node::Unary(*f, b(a)),
        Node::Powi(a, k) => Node::Powi(b(a), *k),
        Node::Powf(a, e) => Node::Powf(b(a), *e),
        Node::Powd(x, y) => Node::Powd(b(x), b(y)),
        Node::Atan2(y, x) => Node::Atan2(b(y), b(x)),
    }
}

impl Program {
    /// The program as a one-output [`Tape`] over the same inputs (a register machine with
    /// common subexpressions shared; for comparisons with [`Program::eval`]).
    pub fn tape(&self) -> Tape {
        tape(std::iter::once(self.tree()))
    }
}
