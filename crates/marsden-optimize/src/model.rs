//! The expressions of a problem file as the DMOC core's model ([`marsden_control::model`]):
//! the forces with controls `f(t, q, q̇, u)`, the running cost `C(t, q, q̇, u)`, the path
//! inequalities `g(t, q, q̇, u) ≤ 0` and the final cost `Φ(q_N, p_N)`, evaluated at `f64` and at the dual numbers the transcription
//! differentiates with ([OJM11] §3).
//!
//! The forces, the running cost and the path inequalities read the inputs `[q₁ … qₙ, q̇₁ … q̇ₙ, t, u₁ … u_m]`, the
//! final cost `[q₁ … qₙ, p₁ … pₙ, t]` at `t = t_end`; the slice is filled on the stack for
//! small systems ([`with_slice`]).
//!
//! [OJM11]: marsden_control#references

use marsden::Scalar;
use marsden::numerics::scratch::with_slice;
use marsden_control::{ControlForce, FinalCost, PathConstraint, RunningCost};
use marsden_expr::{Program, ProgramSet};

/// Calls `body` with `[q, v, t, u]`.
#[inline]
fn with_controlled_inputs<S: Scalar, R>(
    t: S,
    q: &[S],
    v: &[S],
    u: &[S],
    body: impl FnOnce(&[S]) -> R,
) -> R {
    let n = q.len();
    with_slice(2 * n + 1 + u.len(), t, |x| {
        x[..n].copy_from_slice(q);
        x[n..2 * n].copy_from_slice(v);
        x[2 * n + 1..].copy_from_slice(u);
        body(x)
    })
}

/// `[system] forces` with the controls as inputs: one program per coordinate.
///
/// ```
/// use marsden_control::ControlForce;
/// use marsden_expr::{ProgramSet, Symbols};
/// use marsden_optimize::model::ExprControlForce;
///
/// let symbols = Symbols::with_inputs(["x", "x_dot", "t", "u"]).unwrap();
/// let programs = ProgramSet::compile(["u - x_dot"], &symbols).unwrap();
/// let force = ExprControlForce { programs: &programs, controls: 1 };
/// let mut f = [0.0];
/// force.force(0.0, &[1.0], &[0.5], &[2.0], &mut f);
/// assert_eq!(f, [1.5]);
/// ```
#[derive(Debug, Clone, Copy)]
pub struct ExprControlForce<'a> {
    /// The compiled forces over `[q, q̇, t, u]`.
    pub programs: &'a ProgramSet,
    /// The number of controls `m`.
    pub controls: usize,
}

impl ControlForce for ExprControlForce<'_> {
    fn controls(&self) -> usize {
        self.controls
    }

    fn force<S: Scalar>(&self, t: S, q: &[S], v: &[S], u: &[S], out: &mut [S]) {
        with_controlled_inputs(t, q, v, u, |x| self.programs.eval_into(x, out));
    }
}

/// The running cost `C(t, q, q̇, u)` over `[q, q̇, t, u]`.
#[derive(Debug, Clone, Copy)]
pub struct ExprCost<'a> {
    /// The compiled cost.
    pub program: &'a Program,
}

impl RunningCost for ExprCost<'_> {
    fn cost<S: Scalar>(&self, t: S, q: &[S], v: &[S], u: &[S]) -> S {
        with_controlled_inputs(t, q, v, u, |x| self.program.eval(x))
    }
}

/// `[optimal_control] path`: the inequalities `g(t, q, q̇, u) ≤ 0` over `[q, q̇, t, u]`.
#[derive(Debug, Clone, Copy)]
pub struct ExprPath<'a> {
    /// The compiled inequalities (empty: none).
    pub programs: &'a ProgramSet,
}

impl PathConstraint for ExprPath<'_> {
    fn count(&self) -> usize {
        self.programs.len()
    }

    fn eval<S: Scalar>(&self, t: S, q: &[S], v: &[S], u: &[S], out: &mut [S]) {
        with_controlled_inputs(t, q, v, u, |x| self.programs.eval_into(x, out));
    }
}

/// The final cost `Φ(q, p)` over `[q, p, t]` at `t = t_end`; none is `Φ = 0`.
#[derive(Debug, Clone, Copy)]
pub struct ExprFinalCost<'a> {
    /// The compiled cost, if the file gives one.
    pub program: Option<&'a Program>,
    /// The final time.
    pub t_end: f64,
}

impl FinalCost for ExprFinalCost<'_> {
    fn cost<S: Scalar>(&self, q: &[S], p: &[S]) -> S {
        match self.program {
            None => S::from(0.0),
            Some(program) => {
                marsden_problem::model::inputs::with_inputs(q, p, S::from(self.t_end), |x| {
                    program.eval(x)
                })
            }
        }
    }
}
