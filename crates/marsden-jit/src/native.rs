//! [`CompiledTape`]: a tape as native code, [`CompiledVerlet`]: a Verlet run with a gradient
//! tape inside, and the only `unsafe` code of marsden — the calls of that code
//! ([`CompiledTape::call`], [`CompiledVerlet::call`]) and the release of its memory (`Code`'s `Drop`).

use std::fmt;
use std::sync::Mutex;

use cranelift_jit::JITModule;
use cranelift_module::FuncId;
use marsden_expr::Tape;

use crate::compile::{self, JitError};
use crate::verlet;

/// The compiled function: `(head, last, out)` (see `compile`).
type Entry = unsafe extern "C" fn(*const f64, f64, *mut f64);

/// A [`Tape`] compiled to native code: the same outputs, bit for bit, as
/// [`Tape::eval_into`] at `f64`.
pub struct CompiledTape {
    /// The function, an [`Entry`].
    code: Code,
    inputs: usize,
    outputs: usize,
    /// Where the inputs are split: registers below are read from `head`, this one is `last`.
    split: usize,
}

impl CompiledTape {
    /// Compiles `tape` for this machine, to be called with all its inputs in one slice
    /// ([`CompiledTape::eval`]).
    ///
    /// # Errors
    ///
    /// [`JitError`] if the machine has no Cranelift back end or compilation fails.
    pub fn compile(tape: &Tape) -> Result<Self, JitError> {
        Self::compile_split(tape, tape.input_len())
    }

    /// Compiles `tape` for this machine, to be called with its inputs as `[head, last]` where
    /// `head` has `head_len` values ([`CompiledTape::eval_split`]; the `[q, t]` of a potential
    /// without copying `q`).
    ///
    /// # Errors
    ///
    /// [`JitError::Inputs`] if the tape reads more than `head_len + 1` inputs; otherwise as
    /// [`CompiledTape::compile`].
    pub fn compile_split(tape: &Tape, head_len: usize) -> Result<Self, JitError> {
        crate::timing::timed(|| {
            let mut module = compile::host_module()?;
            let id = compile::define(&mut module, tape, head_len)?;
            Ok(Self {
                code: Code::finalize(module, id)?,
                inputs: tape.input_len(),
                outputs: tape.len(),
                split: head_len,
            })
        })
    }

    /// Number of inputs (the tape's [`Tape::input_len`]).
    pub fn input_len(&self) -> usize {
        self.inputs
    }

    /// Number of outputs (the tape's [`Tape::len`]).
    pub fn len(&self) -> usize {
        self.outputs
    }

    /// Whether the tape has no outputs.
    pub fn is_empty(&self) -> bool {
        self.outputs == 0
    }

    /// Evaluates every output at `inputs` into `out`.
    ///
    /// # Panics
    ///
    /// If `inputs` is shorter than [`CompiledTape::input_len`] or `out` than
    /// [`CompiledTape::len`].
    #[inline]
    pub fn eval(&self, inputs: &[f64], out: &mut [f64]) {
        assert!(
            inputs.len() >= self.inputs,
            "a tape needs {} inputs",
            self.inputs
        );
        let last = inputs.get(self.split).copied().unwrap_or(0.0);
        self.eval_split(inputs, last, out);
    }

    /// Evaluates every output at the inputs `[head, last]` split where it was compiled
    /// ([`CompiledTape::compile_split`]; `head` may be longer).
    ///
    /// # Panics
    ///
    /// If `head` has fewer values than the tape reads from it or `out` is shorter than
    /// [`CompiledTape::len`].
    #[inline]
    pub fn eval_split(&self, head: &[f64], last: f64, out: &mut [f64]) {
        assert!(
            head.len() >= self.head_reads() && out.len() >= self.outputs,
            "a tape needs {} inputs before the last and room for {} outputs",
            self.head_reads(),
            self.outputs
        );
        self.call(head, last, out);
    }

    /// How many values the code reads from `head`.
    #[inline]
    fn head_reads(&self) -> usize {
        self.inputs.min(self.split)
    }

    /// Runs the compiled code.
    ///
    /// Safety argument: `address` is the entry of a function that `compile::define` built with
    /// the signature of [`Entry`] in the host's default calling convention (the C one) and
    /// that its `Code` still owns (it is freed only on drop, which `&self` excludes). The code
    /// reads `head[i]` for `i < head_reads()` (`compile::define`: input registers below both
    /// the tape's inputs and the split) and writes `out[k]` for `k < outputs`, nothing else; both slices are that long (checked by the only caller, `eval_split`), and `out`
    /// is borrowed mutably, so the writes alias nothing. It calls only the safe functions of
    /// `functions`.
    #[allow(unsafe_code)]
    #[inline]
    fn call(&self, head: &[f64], last: f64, out: &mut [f64]) {
        debug_assert!(head.len() >= self.head_reads() && out.len() >= self.outputs);
        // SAFETY: see above.
        unsafe {
            let entry = std::mem::transmute::<usize, Entry>(self.code.address);
            entry(head.as_ptr(), last, out.as_mut_ptr());
        }
    }
}

/// The compiled Verlet run: `(q, p, g, d, t₀, h, steps) → steps done` (see `verlet`).
type VerletEntry =
    unsafe extern "C" fn(*mut f64, *mut f64, *mut f64, *const f64, f64, f64, i64) -> i64;

/// The uniform time grid of a [`CompiledVerlet`] run: `steps` steps of size `h` from `t0`, at
/// the times `t_k = t₀ + k·h`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VerletGrid {
    /// The initial time `t₀`.
    pub t0: f64,
    /// The time step `h`.
    pub h: f64,
    /// The number of steps asked for.
    pub steps: usize,
}

/// A velocity Störmer–Verlet run with a potential's gradient tape compiled into its loop
/// (`crate::verlet`'s equations): the same numbers, bit for bit, as the generic loop of
/// `marsden::separable::explicit` calling the tape's interpreter once per step.
pub struct CompiledVerlet {
    /// The function, a [`VerletEntry`].
    code: Code,
    dof: usize,
}

impl CompiledVerlet {
    /// Compiles the run for the gradient tape `gradient` of a potential over `[q, t]` with
    /// `dof` coordinates.
    ///
    /// # Errors
    ///
    /// [`JitError`] if the tape does not have `dof` outputs or reads more than `[q, t]`, the
    /// machine has no Cranelift back end, or compilation fails.
    pub fn compile(gradient: &Tape, dof: usize) -> Result<Self, JitError> {
        crate::timing::timed(|| {
            let mut module = compile::host_module()?;
            let id = verlet::define(&mut module, gradient, dof)?;
            Ok(Self {
                code: Code::finalize(module, id)?,
                dof,
            })
        })
    }

    /// The degrees of freedom `n` it was compiled for.
    pub fn dof(&self) -> usize {
        self.dof
    }

    /// Up to `grid.steps` steps from `(q, p)` at `t₀ = grid.t0` with step `h = grid.h`, in
    /// place; `drift[i] = h/mᵢ`; `grad` is `∇V(t₀, q)` on entry and `∇V` at the final state on
    /// exit. Stops before the first step whose new state is not finite; returns the steps done.
    ///
    /// # Panics
    ///
    /// If a slice's length is not [`CompiledVerlet::dof`].
    pub fn run(
        &self,
        grid: VerletGrid,
        drift: &[f64],
        q: &mut [f64],
        p: &mut [f64],
        grad: &mut [f64],
    ) -> usize {
        let n = self.dof;
        assert!(
            q.len() == n && p.len() == n && grad.len() == n && drift.len() == n,
            "a Verlet run of {n} degrees of freedom needs slices of that length"
        );
        let done = self.call(grid, drift, q, p, grad);
        usize::try_from(done).unwrap_or(0)
    }

    /// Runs the compiled code.
    ///
    /// Safety argument: `address` is the entry of a function that `verlet::define` built with
    /// the signature of [`VerletEntry`] in the host's default calling convention (the C one)
    /// and that its `Code` still owns (freed only on drop, which `&self` excludes). The code
    /// reads `q[i]`, `p[i]`, `grad[i]`, `drift[i]` and writes `q[i]`, `p[i]`, `grad[i]` for
    /// `i < dof`, nothing else (`verlet::emit_run`: one load and one store per index below
    /// `dof`); all four slices have that length (checked by the only caller, `run`), and the
    /// three written ones are distinct mutable borrows, so nothing aliases. It calls only the
    /// safe functions of `functions`.
    #[allow(unsafe_code)]
    fn call(
        &self,
        grid: VerletGrid,
        drift: &[f64],
        q: &mut [f64],
        p: &mut [f64],
        grad: &mut [f64],
    ) -> i64 {
        let VerletGrid { t0, h, steps } = grid;
        // More steps than `i64::MAX` cannot be run anyway; the loop stops at the bound.
        let steps = i64::try_from(steps).unwrap_or(i64::MAX);
        // SAFETY: see above.
        unsafe {
            let entry = std::mem::transmute::<usize, VerletEntry>(self.code.address);
            entry(
                q.as_mut_ptr(),
                p.as_mut_ptr(),
                grad.as_mut_ptr(),
                drift.as_ptr(),
                t0,
                h,
                steps,
            )
        }
    }
}

impl fmt::Debug for CompiledVerlet {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("CompiledVerlet")
            .field("dof", &self.dof)
            .finish_non_exhaustive()
    }
}

/// A finalized function and the module that owns its memory.
struct Code {
    /// The address of the function, valid while `module` is.
    address: usize,
    /// The owner of the code's memory; only ever touched again to free it. (In a mutex to be
    /// `Sync`: a `JITModule` is `Send` but not `Sync`.)
    module: Mutex<Option<JITModule>>,
}

impl Code {
    /// Finalizes `module` and takes the address of its function `id`.
    fn finalize(mut module: JITModule, id: FuncId) -> Result<Self, JitError> {
        module
            .finalize_definitions()
            .map_err(|e| JitError::Codegen(e.to_string()))?;
        let address = module.get_finalized_function(id) as usize;
        Ok(Self {
            address,
            module: Mutex::new(Some(module)),
        })
    }
}

impl Drop for Code {
    /// Frees the code's memory. Safety argument: nothing can call the code any more (every
    /// call borrows the [`CompiledTape`] or [`CompiledVerlet`] that owns this) and the address
    /// is dropped with `self`.
    #[allow(unsafe_code)]
    fn drop(&mut self) {
        let module = match self.module.get_mut() {
            Ok(module) => module.take(),
            Err(poisoned) => poisoned.into_inner().take(),
        };
        if let Some(module) = module {
            // SAFETY: see above.
            unsafe { module.free_memory() };
        }
    }
}

impl fmt::Debug for CompiledTape {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("CompiledTape")
            .field("inputs", &self.inputs)
            .field("outputs", &self.outputs)
            .finish_non_exhaustive()
    }
}
