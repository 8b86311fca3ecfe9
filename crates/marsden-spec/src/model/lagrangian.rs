//! [`ExprLagrangian`]: `L(t, q, q̇)` from a compiled expression, with the structure read off
//! the expression.
//!
//! When the expression is `½ q̇ᵀ M q̇ − V(t, q)` with a constant mass matrix (recognised exactly
//! by [`Program::separable`]), the Lagrangian declares [`Structure::Separable`], so the
//! integrator takes the paths of the catalog systems (explicit Störmer–Verlet, the separable
//! α-rule Newton, banded Jacobians), and `∇V`, `∇²V` come from the symbolically differentiated
//! tapes of [`SeparableForm`] instead of automatic differentiation.

use std::cell::RefCell;
use std::sync::Arc;

use marsden::mechanics::lagrangian::{gradient_by_ad, hessian_by_ad};
use marsden::mechanics::{MassMatrix, Structure};
use marsden::numerics::banded::Banded;
use marsden::{Lagrangian, Scalar};

use super::inputs::with_inputs;
use marsden_expr::{Program, SeparableForm};

/// A Lagrangian given as an expression over `[q, q̇, t]` (names `theta`, `theta_dot`, `t`).
///
/// ```
/// use marsden::Lagrangian;
/// use marsden::mechanics::Structure;
/// use marsden_expr::{Program, Symbols};
/// use marsden_spec::model::ExprLagrangian;
///
/// let symbols = Symbols::with_inputs(["theta", "theta_dot", "t"]).unwrap();
/// let program = Program::compile("0.5*theta_dot^2 + cos(theta)", &symbols).unwrap();
/// let lagrangian = ExprLagrangian::new(program, 1);
/// assert_eq!(lagrangian.lagrangian(0.0, &[0.0], &[2.0]), 3.0);
/// assert!(matches!(lagrangian.structure(), Structure::Separable { .. }));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ExprLagrangian {
    program: Program,
    dof: usize,
    separable: Option<Arc<SeparableForm>>,
}

thread_local! {
    /// Registers and outputs of the Hessian tape (`potential_hessian` has no scratch argument).
    static REGISTERS: RefCell<(Vec<f64>, Vec<f64>)> = const { RefCell::new((Vec::new(), Vec::new())) };
}

impl ExprLagrangian {
    /// Wraps a program compiled against the inputs `[q₁ … qₙ, q̇₁ … q̇ₙ, t]` (n = `dof`), and
    /// reads its structure.
    pub fn new(program: Program, dof: usize) -> Self {
        let separable = program.separable(dof).map(Arc::new);
        Self {
            program,
            dof,
            separable,
        }
    }

    /// The same Lagrangian declaring no structure (the general path; for comparisons).
    pub fn without_structure(mut self) -> Self {
        self.separable = None;
        self
    }

    /// The compiled expression.
    pub fn program(&self) -> &Program {
        &self.program
    }

    /// The separable form, if the expression has one.
    pub fn separable_form(&self) -> Option<&SeparableForm> {
        self.separable.as_deref()
    }
}

/// Fills `regs` with the tape inputs `[q, t]`.
#[inline(always)]
fn load(q: &[f64], t: f64, regs: &mut Vec<f64>) {
    regs.clear();
    regs.extend_from_slice(q);
    regs.push(t);
}

impl Lagrangian for ExprLagrangian {
    fn dof(&self) -> usize {
        self.dof
    }

    #[inline]
    fn lagrangian<S: Scalar>(&self, t: S, q: &[S], v: &[S]) -> S {
        with_inputs(q, v, t, |x| self.program.eval(x))
    }

    fn structure(&self) -> Structure {
        match self.separable.as_deref() {
            Some(form) => Structure::Separable {
                mass: match form.diagonal_mass() {
                    Some(d) => MassMatrix::Diagonal(d),
                    None => MassMatrix::Dense(form.mass().to_vec()),
                },
            },
            None => Structure::General,
        }
    }

    /// `∇V` from the symbolic gradient's tape (registers in `scratch`); AD without one.
    #[inline]
    fn potential_gradient(&self, t: f64, q: &[f64], grad: &mut [f64], scratch: &mut Vec<f64>) {
        match self.separable.as_deref().and_then(SeparableForm::gradient) {
            Some(tape) => {
                load(q, t, scratch);
                tape.eval_in_place(scratch, grad);
            }
            None => gradient_by_ad(self, t, q, grad),
        }
    }

    /// The half-bandwidth of the symbolic `∇²V` when it is narrower than dense.
    fn potential_bandwidth(&self) -> Option<usize> {
        let form = self.separable.as_deref()?;
        form.hessian()?;
        (form.bandwidth() + 1 < self.dof).then_some(form.bandwidth())
    }

    /// `∇²V` from the symbolic Hessian's tape; AD without one.
    fn potential_hessian(&self, t: f64, q: &[f64], hess: &mut Banded) {
        let Some(form) = self.separable.as_deref() else {
            return hessian_by_ad(self, t, q, hess);
        };
        let Some(tape) = form.hessian() else {
            return hessian_by_ad(self, t, q, hess);
        };
        REGISTERS.with_borrow_mut(|(regs, entries)| {
            entries.resize(tape.len(), 0.0);
            load(q, t, regs);
            tape.eval_in_place(regs, entries);
            hess.fill_zero();
            for (&(i, j), &value) in form.hessian_entries().iter().zip(entries.iter()) {
                hess.set(i, j, value);
                hess.set(j, i, value);
            }
        });
    }
}
