//! Fence 2: the step for small systems, with sizes known at compile time.
//!
//! Two-point steps (no internal stages) of up to four degrees of freedom — unconstrained
//! ([`unconstrained`]) or with up to four holonomic constraints ([`constrained`]) — are solved by
//! the same Newton iteration as the general path ([`crate::integrator::equations`]), with stack
//! arrays and the fixed-size dual numbers of [`crate::numerics::dual`] seeded directly in offset
//! form. [`dispatch`] runs them in code compiled for x86-64-v3 when the CPU has it. The general
//! path stays the reference: tests compare both to round-off, and the wide and the baseline
//! copies bit for bit.

pub(crate) mod constrained;
pub(crate) mod dispatch;
pub(crate) mod unconstrained;

use num_dual::HyperDual64;

use self::dispatch::Dispatch;
use crate::discrete::{DiscreteAction, DiscreteForce};
use crate::numerics::dual::{
    Dual2x64, Dual4x64, Dual6x64, Dual8x64, HyperDual2x64, HyperDual3x64, HyperDual4x64, SmallDual,
    SmallGradient,
};
use crate::numerics::newton::{NewtonFailure, NewtonOptions, NewtonReport};

/// Relative update size below which the next evaluation is expected to end the iteration.
/// The step equations are nearly linear in the offset (their curvature is `O(h²)` relative to
/// `M/h`), so Newton's quadratic convergence leaves round-off after any update this small; a
/// wrong guess costs one cheap evaluation (how often, and what it saves: BENCHMARKS.md).
pub(crate) const SPECULATE: f64 = 1e-3;

/// `∂L_d/∂Q₀ + f_d⁻` and `p_{k+1} = ∂L_d/∂Q₁ + f_d⁺` at `(q₀, Δ)`, by one first-order dual
/// evaluation ([`SmallGradient`]; the forces by one more), and `max |∂L_d/∂Q₀|` (the size of
/// the residual's terms). Shared by the unconstrained and the constrained ([`crate::integrator::small::constrained`])
/// kernels; the sums are formed in the order of their hyper-dual evaluations.
#[inline(always)]
pub(crate) fn first_derivatives<const N: usize, G, A, F>(
    action: &A,
    force: &F,
    t0: f64,
    h: f64,
    q0: &[f64],
    delta: &[f64],
) -> ([f64; N], [f64; N], f64)
where
    G: SmallGradient<N>,
    A: DiscreteAction,
    F: DiscreteForce,
{
    let q: [G; N] = std::array::from_fn(|i| G::position(q0[i], i));
    let d: [G; N] = std::array::from_fn(|i| G::offset(delta[i], i));
    let l = action.action(t0, h, &q, &d);
    let mut d_q0: [f64; N] = std::array::from_fn(|i| l.part(i));
    let mut p_next: [f64; N] = std::array::from_fn(|j| l.part(N + j));
    let term_scale = d_q0.iter().fold(0.0_f64, |m, r| m.max(r.abs()));
    if force.is_active() {
        let mut f = [G::from(0.0); 8];
        force.discrete_force(t0, h, &q, &d, &mut f[..2 * N]);
        for i in 0..N {
            d_q0[i] += f[i].value();
            p_next[i] += f[N + i].value();
        }
    }
    (d_q0, p_next, term_scale)
}

/// A statically sized Newton step ([`SmallStep`], [`crate::integrator::small::SmallConstrainedStep`]):
/// solved for `N` degrees of freedom with hyper-duals `D` and the cheaper duals `G` of the
/// confirming evaluation; returns the report and `p_{k+1}`.
pub(crate) trait SmallKernel {
    /// Whether the kernel can apply to the types it is made of (a composition is never
    /// two-point; [`crate::mechanics::Unconstrained`] needs no SHAKE kernel): when not, none of
    /// its sizes is compiled.
    const APPLIES: bool;
    /// The degrees of freedom the types fix, if they do: only that size is compiled.
    const FIXED_DOF: Option<usize>;

    /// Newton's method on the step equations from `z` (overwritten with the solution).
    fn solve<const N: usize, D: SmallDual<N>, G: SmallGradient<N>>(
        &self,
        z: &mut [f64],
        options: &NewtonOptions,
    ) -> Result<(NewtonReport, [f64; N]), NewtonFailure>;
}

/// Which sizes of a kernel are compiled: each is a constant of the monomorphised kernel, so the
/// code of the other sizes is never generated (a branch on a constant is not lowered).
struct Sizes<K>(std::marker::PhantomData<K>);

impl<K: SmallKernel> Sizes<K> {
    const ONE: bool = compiled::<K>(1);
    const TWO: bool = compiled::<K>(2);
    const THREE: bool = compiled::<K>(3);
    const FOUR: bool = compiled::<K>(4);
}

/// Whether the kernel `K` of size `n` is compiled.
const fn compiled<K: SmallKernel>(n: usize) -> bool {
    K::APPLIES
        && match K::FIXED_DOF {
            Some(dof) => dof == n,
            None => true,
        }
}

/// `kernel` for the run-time `n ≤ 4` (the duals of each size: `HyperDual64`/`Dual2` for n = 1,
/// [`crate::numerics::dual`]'s for n = 2…4) in the instruction set `dispatch` chose
/// ([`crate::integrator::small::dispatch`]); writes `p_{k+1}` into `p_next`. `None` when the
/// kernel of size `n` is not compiled for these types ([`SmallKernel::APPLIES`],
/// [`SmallKernel::FIXED_DOF`]): the caller takes the general path.
#[inline(always)]
pub(crate) fn solve_sized<K: SmallKernel>(
    dispatch: Dispatch,
    kernel: &K,
    n: usize,
    z: &mut [f64],
    options: &NewtonOptions,
    p_next: &mut [f64],
) -> Option<Result<NewtonReport, NewtonFailure>> {
    let mut keep = |(report, p): (NewtonReport, &[f64])| {
        p_next.copy_from_slice(p);
        report
    };
    dispatch.run(
        #[inline(always)]
        || match n {
            1 => {
                if Sizes::<K>::ONE {
                    let solved = kernel.solve::<1, HyperDual64, Dual2x64>(z, options);
                    Some(solved.map(|(r, p)| keep((r, &p))))
                } else {
                    None
                }
            }
            2 => {
                if Sizes::<K>::TWO {
                    let solved = kernel.solve::<2, HyperDual2x64, Dual4x64>(z, options);
                    Some(solved.map(|(r, p)| keep((r, &p))))
                } else {
                    None
                }
            }
            3 => {
                if Sizes::<K>::THREE {
                    let solved = kernel.solve::<3, HyperDual3x64, Dual6x64>(z, options);
                    Some(solved.map(|(r, p)| keep((r, &p))))
                } else {
                    None
                }
            }
            _ => {
                if Sizes::<K>::FOUR {
                    let solved = kernel.solve::<4, HyperDual4x64, Dual8x64>(z, options);
                    Some(solved.map(|(r, p)| keep((r, &p))))
                } else {
                    None
                }
            }
        },
    )
}
