//! Runtime choice of a wider instruction set for the small kernels.
//!
//! The build stays portable (baseline x86-64), but on a CPU with the x86-64-v3 extensions
//! (AVX2, FMA, BMI; x86-64 CPUs since 2013–2015) `Dispatch::run` executes its closure in a
//! copy of the code compiled for them, through `pulp`'s [`Arch::dispatch`](pulp::Arch::dispatch);
//! elsewhere, or when switched off ([`crate::integrator::Integrator::with_wide_instructions`]), the closure
//! runs as baseline code. Three-operand VEX instructions drop the register copies of SSE2 code;
//! fewer instructions matter most when the core is shared with another busy thread (figures in
//! BENCHMARKS.md). Rust never contracts
//! `a * b + c` into a fused multiply–add and never reassociates floating-point sums, so both
//! copies give the same bits (tests `fast_paths/small_kernels.rs` and
//! `fast_paths/small_constrained_kernels.rs` compare them).
//!
//! Only code inlined into the dispatched copy is compiled for the wider set. The small kernels
//! ([`crate::integrator::small::unconstrained`], [`crate::integrator::small::constrained`]) and the layers between them and the user's
//! Lagrangian (the α rules' `discrete_lagrangian_offset` and forces, `rules::at_node`, the
//! built-in systems of up to four degrees of freedom) are therefore `#[inline(always)]`,
//! closures included; a user's own Lagrangian is inlined at LLVM's discretion (mark it
//! `#[inline(always)]` to be sure).

/// The instruction set the small kernels run in: detected once, when an integrator is built.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Dispatch(pulp::Arch);

impl Dispatch {
    /// The widest set `pulp` finds on this CPU (x86-64-v3 or baseline).
    pub fn detect() -> Self {
        Self(pulp::Arch::new())
    }

    /// Baseline code only.
    pub fn baseline() -> Self {
        Self(pulp::Arch::Scalar)
    }

    /// Runs `f` in the chosen instruction set (`f` should be an `#[inline(always)]` closure,
    /// so that its body is compiled into the dispatched copy).
    #[inline(always)]
    pub fn run<R>(self, f: impl FnOnce() -> R) -> R {
        self.0.dispatch(f)
    }
}

impl Default for Dispatch {
    fn default() -> Self {
        Self::detect()
    }
}
