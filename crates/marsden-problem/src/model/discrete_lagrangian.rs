//! [`ExprDiscreteLagrangian`]: a researcher's own discrete Lagrangian `L_d(q₀, q₁, h, t)` from
//! a compiled expression, stepped by the core's integrator through the discrete Legendre
//! transforms ([MW01] §1.3): `p_k = −D₁L_d(q_k, q_{k+1})` is solved for `q_{k+1}` by Newton's
//! method, then `p_{k+1} = D₂L_d(q_k, q_{k+1})`; the derivatives come from automatic
//! differentiation of the expression.
//!
//! The expression reads the coordinates at both ends of a step, `<q>_0` and `<q>_1`, the step
//! `h` and the step's initial time `t`. There is no continuous `L` behind it, so neither the
//! energy `⟨p, q̇⟩ − L` nor an initial velocity has a meaning for it.
//!
//! The integrator steps the displacement `Δ = q₁ − q₀`; the expression is evaluated in those
//! variables ([`marsden_expr::DisplacementForm`]: `(x_1 − x_0)/h` as `Δ·(1/h)`,
//! `(x_0 + x_1)/2` as `x_0 + Δ·0.5`, a leading `h*` as a factor `h`), which are the operations
//! of the built-in rules: the midpoint rule's `L_d` written by hand reproduces
//! `method = "midpoint"` (general path) bit for bit.
//!
//! [MW01]: marsden#references

use marsden::{DiscreteLagrangian, Scalar};
use marsden_expr::{DisplacementForm, Program};

/// A discrete Lagrangian given as an expression over `[q₀, q₁, h, t]` (names `theta_0`,
/// `theta_1`, `h`, `t`).
///
/// ```
/// use marsden::DiscreteLagrangian;
/// use marsden_expr::{Program, Symbols};
/// use marsden_problem::model::ExprDiscreteLagrangian;
/// use marsden_problem::model::discrete_lagrangian::endpoint_inputs;
///
/// let symbols = Symbols::with_inputs(endpoint_inputs(&["x".to_owned()])).unwrap();
/// let text = "h*(0.5*((x_1 - x_0)/h)^2 - 0.5*((x_0 + x_1)/2)^2)";
/// let ld = ExprDiscreteLagrangian::new(Program::compile(text, &symbols).unwrap(), 1);
/// let value: f64 = ld.discrete_lagrangian(0.0, 0.5, &[1.0], &[2.0]);
/// assert_eq!(value, 0.5 * (0.5 * 4.0 - 0.5 * 2.25));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ExprDiscreteLagrangian {
    program: Program,
    offset: DisplacementForm,
    dof: usize,
}

impl ExprDiscreteLagrangian {
    /// Wraps a program compiled against [`endpoint_inputs`] of `dof` coordinates, and rewrites
    /// it in the displacement the integrator steps ([`Program::displacement_form`]).
    pub fn new(program: Program, dof: usize) -> Self {
        let offset = program.displacement_form(dof);
        Self {
            program,
            offset,
            dof,
        }
    }

    /// The compiled expression.
    pub fn program(&self) -> &Program {
        &self.program
    }
}

impl DiscreteLagrangian for ExprDiscreteLagrangian {
    fn dof(&self) -> usize {
        self.dof
    }

    /// `L_d(q₀, q₁)`: the inputs `[q₀, q₁, h, t₀]` laid out on the stack for n ≤ 3.
    #[inline]
    fn discrete_lagrangian<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], q1: &[S]) -> S {
        let n = q0.len();
        let len = 2 * n + 2;
        let (mut inline, mut heap);
        let x: &mut [S] = if len <= 8 {
            inline = [S::from(h); 8];
            &mut inline[..len]
        } else {
            heap = vec![S::from(h); len];
            &mut heap
        };
        x[..n].copy_from_slice(q0);
        x[n..2 * n].copy_from_slice(q1);
        x[2 * n] = S::from(h);
        x[2 * n + 1] = S::from(t0);
        self.program.eval(x)
    }

    /// `L_d(q₀, q₀ + Δ)` from the expression rewritten in `(q₀, Δ)`: the midpoint, velocity
    /// and `h` factor the file writes are formed as the built-in rules form them, so a
    /// hand-written rule's `L_d` steps bit for bit like the rule.
    #[inline]
    fn discrete_lagrangian_offset<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], delta: &[S]) -> S {
        self.offset.eval(t0, h, q0, delta)
    }
}

/// The name of a coordinate at the start (`end = 0`) or the end (`end = 1`) of a step:
/// `theta` → `theta_0`, `theta_1`.
pub fn endpoint_name(coordinate: &str, end: u8) -> String {
    format!("{coordinate}_{end}")
}

/// Input names of a discrete Lagrangian in slot order: the coordinates at the start, at the
/// end, then `h` and `t`.
pub fn endpoint_inputs(coordinates: &[String]) -> Vec<String> {
    let at = |end: u8| coordinates.iter().map(move |c| endpoint_name(c, end));
    at(0)
        .chain(at(1))
        .chain(["h".to_owned(), "t".to_owned()])
        .collect()
}
