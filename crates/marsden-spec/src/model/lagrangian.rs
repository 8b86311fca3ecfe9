//! [`ExprLagrangian`]: `L(t, q, q̇)` from a compiled expression, with the structure read off
//! the expression.
//!
//! When the expression is `½ q̇ᵀ M q̇ − V(t, q)` with a constant mass matrix (recognised exactly
//! by [`Program::separable`]), the Lagrangian declares [`Structure::Separable`], so the
//! integrator takes the paths of the catalog systems (explicit Störmer–Verlet, the separable
//! α-rule Newton, banded Jacobians), and `∇V`, `∇²V` come from the symbolically differentiated
//! tapes of [`SeparableForm`] instead of automatic differentiation.
//!
//! With the `jit` feature (default), those tapes are compiled to native code at their first use
//! ([`marsden_jit`], the same values bit for bit); where that is not possible (no code
//! generator for the machine), or with the environment variable `MARSDEN_JIT=0` when the
//! Lagrangian is built, the tapes' interpreter evaluates them.

use std::cell::RefCell;
use std::sync::Arc;
#[cfg(feature = "jit")]
use std::sync::OnceLock;

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
#[derive(Debug, Clone)]
pub struct ExprLagrangian {
    program: Program,
    dof: usize,
    separable: Option<Arc<SeparableForm>>,
    /// Native code for the separable form's tapes; `None` to interpret them.
    native: Option<Arc<NativeTapes>>,
}

/// Equal programs and forms (the native code is a function of the form's tapes).
impl PartialEq for ExprLagrangian {
    fn eq(&self, other: &Self) -> bool {
        (&self.program, self.dof, &self.separable) == (&other.program, other.dof, &other.separable)
    }
}

/// The separable form's gradient and Hessian tapes as native code, each compiled at its first
/// use (`None` inside: compilation failed, the interpreter is used).
#[derive(Debug, Default)]
struct NativeTapes {
    #[cfg(feature = "jit")]
    gradient: OnceLock<Option<marsden_jit::CompiledTape>>,
    #[cfg(feature = "jit")]
    hessian: OnceLock<Option<marsden_jit::CompiledTape>>,
}

/// The native code of `tape` (over `[q, t]`, `q` of length `dof`) in `cell`, compiled now if
/// this is its first use.
#[cfg(feature = "jit")]
#[inline]
fn native<'a>(
    cell: &'a OnceLock<Option<marsden_jit::CompiledTape>>,
    tape: &marsden_expr::Tape,
    dof: usize,
) -> Option<&'a marsden_jit::CompiledTape> {
    cell.get_or_init(|| marsden_jit::CompiledTape::compile_split(tape, dof).ok())
        .as_ref()
}

/// Whether native code is wanted: built with the `jit` feature and not switched off by
/// `MARSDEN_JIT=0`.
fn jit_wanted() -> bool {
    cfg!(feature = "jit") && std::env::var_os("MARSDEN_JIT").is_none_or(|v| v != "0")
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
        let native = (separable.is_some() && jit_wanted()).then(Arc::default);
        Self {
            program,
            dof,
            separable,
            native,
        }
    }

    /// The same Lagrangian declaring no structure (the general path; for comparisons).
    pub fn without_structure(mut self) -> Self {
        self.separable = None;
        self.native = None;
        self
    }

    /// The same Lagrangian with its tapes interpreted, never compiled (what `MARSDEN_JIT=0`
    /// gives; for comparisons).
    pub fn interpreted(mut self) -> Self {
        self.native = None;
        self
    }

    /// Whether `∇V` is evaluated by native code (compiling it now if it has not been yet).
    pub fn gradient_is_native(&self) -> bool {
        self.native_gradient().is_some()
    }

    /// The native code of `∇V`, if there is one.
    #[cfg(feature = "jit")]
    #[inline]
    fn native_gradient(&self) -> Option<&marsden_jit::CompiledTape> {
        let tape = self.separable.as_deref()?.gradient()?;
        native(&self.native.as_deref()?.gradient, tape, self.dof)
    }

    #[cfg(not(feature = "jit"))]
    #[inline]
    fn native_gradient(&self) -> Option<&NeverNative> {
        None
    }

    /// The native code of `∇²V`, if there is one.
    #[cfg(feature = "jit")]
    #[inline]
    fn native_hessian(&self) -> Option<&marsden_jit::CompiledTape> {
        let tape = self.separable.as_deref()?.hessian()?;
        native(&self.native.as_deref()?.hessian, tape, self.dof)
    }

    #[cfg(not(feature = "jit"))]
    #[inline]
    fn native_hessian(&self) -> Option<&NeverNative> {
        None
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
        // Once compiled, the native code is one atomic load away: no look-up of the form.
        #[cfg(feature = "jit")]
        if let Some(native) = (self.native.as_deref())
            .and_then(|n| n.gradient.get())
            .and_then(Option::as_ref)
        {
            return native.eval_split(q, t, grad);
        }
        match self.separable.as_deref().and_then(SeparableForm::gradient) {
            Some(tape) => match self.native_gradient() {
                Some(native) => native.eval_split(q, t, grad),
                None => {
                    load(q, t, scratch);
                    tape.eval_in_place(scratch, grad);
                }
            },
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
            match self.native_hessian() {
                Some(native) => native.eval_split(q, t, entries),
                None => {
                    load(q, t, regs);
                    tape.eval_in_place(regs, entries);
                }
            }
            hess.fill_zero();
            for (&(i, j), &value) in form.hessian_entries().iter().zip(entries.iter()) {
                hess.set(i, j, value);
                hess.set(j, i, value);
            }
        });
    }
}

/// Stands for the native code when the `jit` feature is off (never constructed).
#[cfg(not(feature = "jit"))]
enum NeverNative {}

#[cfg(not(feature = "jit"))]
impl NeverNative {
    fn eval_split(&self, _: &[f64], _: f64, _: &mut [f64]) {
        match *self {}
    }
}
