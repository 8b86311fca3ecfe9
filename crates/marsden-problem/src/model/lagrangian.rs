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
//! ([`marsden_jit`], the same values bit for bit), and so is the trapezoid rule's whole explicit
//! run with `∇V` inside its loop ([`VerletKernel`], for a diagonal mass: the state stays in
//! registers from step to step), and a compiled `∇²V` whose outputs are its whole upper
//! triangle writes it straight into the small Newton step's array
//! ([`Lagrangian::potential_hessian_packed`]); where that is not possible (no code
//! generator for the machine), or with the environment variable `MARSDEN_JIT=0` when the
//! Lagrangian is built, the tapes' interpreter evaluates them.
//!
//! Without the separable form (a mass matrix depending on `q`, velocity-linear terms), the
//! integrator takes the general path, whose small step kernels (up to four coordinates)
//! evaluate `L` at fixed-size dual numbers. There, with native code, `L`'s value, gradient and
//! Hessian in `[q, q̇, t]` ([`Jet`], symbolic, one tape each for first and second order) are
//! evaluated at the real parts and the dual number is composed from them by Taylor's formula,
//! exact for dual numbers ([`marsden::numerics::dual::compose::compose`]): the same values as
//! the program's own dual evaluation to round-off, without interpreting it over 9 to 25 parts
//! per operation. Every other scalar type (values, the general path's chunked duals) still runs
//! the program.

use std::cell::RefCell;
use std::sync::Arc;
#[cfg(feature = "jit")]
use std::sync::OnceLock;

use marsden::mechanics::kernel::VerletKernel;
use marsden::mechanics::lagrangian::{gradient_by_ad, hessian_by_ad};
use marsden::mechanics::{MassMatrix, Structure};
use marsden::numerics::banded::Banded;
#[cfg(feature = "jit")]
use marsden::numerics::dual::compose::{Order, compose};
#[cfg(feature = "jit")]
use marsden::numerics::scratch::with_slice;
use marsden::{Lagrangian, Scalar};

use super::inputs::with_inputs;
use marsden_expr::{Jet, Program, SeparableForm};

/// A Lagrangian given as an expression over `[q, q̇, t]` (names `theta`, `theta_dot`, `t`).
///
/// ```
/// use marsden::Lagrangian;
/// use marsden::mechanics::Structure;
/// use marsden_expr::{Program, Symbols};
/// use marsden_problem::model::ExprLagrangian;
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
    /// Without the separable form, for up to four degrees of freedom: the value, gradient and
    /// Hessian of `L` in `[q, q̇, t]`, from which the small step kernels' dual numbers are
    /// composed (`marsden::numerics::dual::compose`) by native code instead of interpreting the
    /// program over them.
    jet: Option<Arc<NativeJet>>,
}

/// Equal programs and forms (the native code is a function of the form's tapes).
impl PartialEq for ExprLagrangian {
    fn eq(&self, other: &Self) -> bool {
        (&self.program, self.dof, &self.separable) == (&other.program, other.dof, &other.separable)
    }
}

/// The separable form's gradient and Hessian tapes as native code, and the explicit run with
/// the gradient inside, each compiled at its first use (`None` inside: compilation failed, the
/// interpreter is used).
#[derive(Debug, Default)]
struct NativeTapes {
    /// Whether the Hessian tape's outputs are the whole upper triangle of `∇²V`, row by row
    /// ([`Lagrangian::potential_hessian_packed`]'s layout). Read by the native path only.
    #[cfg_attr(not(feature = "jit"), allow(dead_code))]
    hessian_packed: bool,
    #[cfg(feature = "jit")]
    gradient: OnceLock<Option<marsden_jit::CompiledTape>>,
    #[cfg(feature = "jit")]
    hessian: OnceLock<Option<marsden_jit::CompiledTape>>,
    #[cfg(feature = "jit")]
    verlet: OnceLock<Option<NativeVerlet>>,
}

/// The Taylor data of `L` ([`Jet`]) and its native code, compiled at the first use (`None`
/// inside: compilation failed, and the program is interpreted as without a jet).
#[derive(Debug)]
struct NativeJet {
    jet: Jet,
    #[cfg(feature = "jit")]
    native: OnceLock<Option<[marsden_jit::CompiledTape; 2]>>,
}

impl NativeJet {
    /// The jet of `program` over `[q, q̇, t]`, when native code may evaluate it.
    fn of(program: &Program, dof: usize) -> Option<Self> {
        let wanted = jit_wanted() && dof <= 4;
        Some(Self {
            jet: wanted.then(|| program.jet(2 * dof + 1)).flatten()?,
            #[cfg(feature = "jit")]
            native: OnceLock::new(),
        })
    }

    /// The native code of the first- and second-order tapes, compiled now if this is the first
    /// use.
    #[cfg(feature = "jit")]
    #[inline]
    fn native(&self) -> Option<&[marsden_jit::CompiledTape; 2]> {
        let compile = |tape| marsden_jit::CompiledTape::compile(tape).ok();
        let both = || Some([compile(self.jet.first())?, compile(self.jet.second())?]);
        self.native.get_or_init(both).as_ref()
    }

    /// `L` at the small kernels' dual numbers `(t, q, q̇)` from the native Taylor data;
    /// `None` for other scalar types or without native code.
    #[inline(always)]
    fn compose<S: Scalar>(&self, t: S, q: &[S], v: &[S]) -> Option<S> {
        #[cfg(feature = "jit")]
        {
            let mut native = true;
            let value = compose(q, v, t, |a, order, out| match (self.native(), order) {
                (Some([first, _]), Order::First) => first.eval(a, out),
                (Some([_, second]), Order::Second) => second.eval(a, out),
                (None, _) => native = false,
            });
            value.filter(|_| native)
        }
        #[cfg(not(feature = "jit"))]
        {
            let _ = (t, q, v, &self.jet);
            None
        }
    }
}

/// The compiled Verlet run as the core's [`VerletKernel`].
#[cfg(feature = "jit")]
#[derive(Debug)]
struct NativeVerlet(marsden_jit::CompiledVerlet);

#[cfg(feature = "jit")]
impl VerletKernel for NativeVerlet {
    #[inline]
    fn run(
        &self,
        grid: marsden::mechanics::kernel::RunGrid,
        drift: &[f64],
        q: &mut [f64],
        p: &mut [f64],
        grad: &mut [f64],
    ) -> usize {
        let grid = marsden_jit::VerletGrid {
            t0: grid.t0,
            h: grid.h,
            steps: grid.steps,
        };
        self.0.run(grid, drift, q, p, grad)
    }

    fn dof(&self) -> usize {
        self.0.dof()
    }
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

/// Whether `entries` are every `(i, j)`, `i ≤ j < n`, row by row.
fn is_packed_triangle(entries: &[(usize, usize)], n: usize) -> bool {
    let triangle = (0..n).flat_map(|i| (i..n).map(move |j| (i, j)));
    entries.iter().copied().eq(triangle)
}

/// Seconds this thread has spent compiling expressions to native code (`0` without the `jit`
/// feature). Tapes are compiled at their first use, inside a run: a run reads this before and
/// after to report the compilation apart from its time per step.
pub fn jit_compile_seconds() -> f64 {
    #[cfg(feature = "jit")]
    {
        marsden_jit::compile_seconds()
    }
    #[cfg(not(feature = "jit"))]
    {
        0.0
    }
}

/// Whether native code is wanted: built with the `jit` feature and not switched off by
/// `MARSDEN_JIT=0`.
pub(crate) fn jit_wanted() -> bool {
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
        // Without the `jit` feature the struct has no other field to fill.
        #[cfg_attr(not(feature = "jit"), allow(clippy::needless_update))]
        let native = separable.as_deref().filter(|_| jit_wanted()).map(|form| {
            Arc::new(NativeTapes {
                hessian_packed: is_packed_triangle(form.hessian_entries(), dof),
                ..NativeTapes::default()
            })
        });
        let jet = match separable {
            Some(_) => None,
            None => NativeJet::of(&program, dof).map(Arc::new),
        };
        Self {
            program,
            dof,
            separable,
            native,
            jet,
        }
    }

    /// The same Lagrangian declaring no structure (the general path; for comparisons).
    pub fn without_structure(mut self) -> Self {
        self.separable = None;
        self.native = None;
        self.jet = None;
        self
    }

    /// The same Lagrangian with its tapes interpreted, never compiled (what `MARSDEN_JIT=0`
    /// gives; for comparisons).
    pub fn interpreted(mut self) -> Self {
        self.native = None;
        self.jet = None;
        self
    }

    /// Whether the small step kernels' dual numbers are composed from native Taylor data
    /// (compiling it now if it has not been yet): a Lagrangian without the separable form, of
    /// at most four degrees of freedom, with native code.
    pub fn jet_is_native(&self) -> bool {
        #[cfg(feature = "jit")]
        return self
            .jet
            .as_deref()
            .is_some_and(|jet| jet.native().is_some());
        #[cfg(not(feature = "jit"))]
        false
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

    /// The native code of `∇V` once it has been compiled: no look-up of the separable form,
    /// one atomic load (what every call after the first takes).
    #[cfg(feature = "jit")]
    #[inline(always)]
    fn compiled_gradient(&self) -> Option<&marsden_jit::CompiledTape> {
        self.native.as_deref()?.gradient.get()?.as_ref()
    }

    /// The native code of `∇²V` once it has been compiled (as [`Self::compiled_gradient`]).
    #[cfg(feature = "jit")]
    #[inline(always)]
    fn compiled_hessian(&self) -> Option<&marsden_jit::CompiledTape> {
        self.native.as_deref()?.hessian.get()?.as_ref()
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

    // No closures between the caller and the evaluation: at the small kernels' dual numbers
    // each call boundary copies the argument and the result (hundreds of bytes), and without
    // link-time optimisation the closures stayed calls (BENCHMARKS.md, "Build time").
    #[inline]
    fn lagrangian<S: Scalar>(&self, t: S, q: &[S], v: &[S]) -> S {
        if let Some(jet) = self.jet.as_deref()
            && let Some(value) = jet.compose(t, q, v)
        {
            return value;
        }
        with_inputs(
            q,
            v,
            t,
            #[inline(always)]
            |x| self.program.eval(x),
        )
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
        #[cfg(feature = "jit")]
        if let Some(native) = self.compiled_gradient() {
            return native.eval_split(q, t, grad);
        }
        self.gradient_first_or_interpreted(t, q, grad, scratch);
    }

    /// The half-bandwidth of the symbolic `∇²V` when it is narrower than dense.
    fn potential_bandwidth(&self) -> Option<usize> {
        let form = self.separable.as_deref()?;
        form.hessian()?;
        (form.bandwidth() + 1 < self.dof).then_some(form.bandwidth())
    }

    /// `∇²V` from the symbolic Hessian's tape; AD without one.
    #[inline]
    fn potential_hessian(&self, t: f64, q: &[f64], hess: &mut Banded) {
        #[cfg(feature = "jit")]
        if let (Some(native), Some(form)) = (self.compiled_hessian(), self.separable.as_deref()) {
            return with_slice(native.len(), 0.0, |entries| {
                native.eval_split(q, t, entries);
                scatter(form, entries, hess);
            });
        }
        self.hessian_first_or_interpreted(t, q, hess);
    }

    /// The whole upper triangle of `∇²V` straight from the compiled Hessian, when its outputs
    /// are that triangle (every entry not identically zero) and it has been compiled.
    #[inline]
    fn potential_hessian_packed(&self, t: f64, q: &[f64], packed: &mut [f64]) -> bool {
        #[cfg(feature = "jit")]
        if let Some(native) = self
            .native
            .as_deref()
            .filter(|native| native.hessian_packed)
            && let Some(Some(compiled)) = native.hessian.get()
        {
            compiled.eval_split(q, t, packed);
            return true;
        }
        let _ = (t, q, packed);
        false
    }

    /// The explicit run with the compiled gradient inside its loop (compiled now if this is
    /// its first use); `None` without native code.
    fn verlet_kernel(&self) -> Option<&dyn VerletKernel> {
        #[cfg(feature = "jit")]
        {
            let tape = self.separable.as_deref()?.gradient()?;
            let cell = &self.native.as_deref()?.verlet;
            let compile = || marsden_jit::CompiledVerlet::compile(tape, self.dof).ok();
            cell.get_or_init(|| compile().map(NativeVerlet))
                .as_ref()
                .map(|kernel| kernel as &dyn VerletKernel)
        }
        #[cfg(not(feature = "jit"))]
        None
    }
}

/// The Hessian's entries `∂²V/∂qᵢ∂qⱼ` (in the order of [`SeparableForm::hessian_entries`])
/// written into `hess` at `(i, j)` and `(j, i)`; the other entries are left at the zero they
/// start at ([`Lagrangian::potential_hessian`]'s contract).
#[inline]
fn scatter(form: &SeparableForm, entries: &[f64], hess: &mut Banded) {
    for (&(i, j), &value) in form.hessian_entries().iter().zip(entries) {
        hess.set(i, j, value);
        if i != j {
            hess.set(j, i, value);
        }
    }
}

impl ExprLagrangian {
    /// `∇V` the first time (compiling the native code) or by the interpreter or AD: kept out
    /// of `potential_gradient` so that its common case is a few instructions.
    #[inline(never)]
    fn gradient_first_or_interpreted(
        &self,
        t: f64,
        q: &[f64],
        grad: &mut [f64],
        scratch: &mut Vec<f64>,
    ) {
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

    /// `∇²V` the first time (compiling the native code) or by the interpreter or AD (as
    /// [`Self::gradient_first_or_interpreted`]).
    #[inline(never)]
    fn hessian_first_or_interpreted(&self, t: f64, q: &[f64], hess: &mut Banded) {
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
            scatter(form, entries, hess);
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
