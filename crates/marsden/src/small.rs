//! The step for small systems, with sizes known at compile time.
//!
//! Same equations as [`crate::step`] for a two-point discrete Lagrangian (no internal stages)
//! without constraints, solved by the same Newton iteration — but for `n ≤ 4` degrees of freedom
//! every buffer is a stack array of length `N`, the hyper-dual numbers are `HyperDual64`
//! (n = 1) or [`crate::small_dual`]'s `HyperDual2`, `HyperDual3`, `HyperDual4`, seeded directly in offset form (`q₀` with eps₁ = eᵢ; the
//! displacement `Δ` with eps₁ = −eᵢ, eps₂ = eᵢ, so eps₁ differentiates along `Q₀` with `Q₁` fixed),
//! and the N × N Newton system is solved in place. The integrator dispatches here once per
//! step on `n`; the general path remains the reference (a test checks both agree to round-off).
//!
//! The last evaluation of a step, the one that finds the residual below tolerance, needs no
//! Jacobian: only the residual `p_k + ∂L_d/∂Q₀` and `p_{k+1} = ∂L_d/∂Q₁`, first derivatives —
//! a dual number with `2N` parts ([`SmallGradient`]) instead of a hyper-dual one with
//! `1 + 2N + N²`. After an update small enough that Newton's quadratic convergence should
//! leave only round-off ([`SPECULATE`]), the next evaluation takes the cheap form (should the
//! iteration go on after all, the Jacobian is evaluated at the same point); the iterates stay
//! exactly those of Newton's method with a fresh Jacobian per update.

use nalgebra::{Const, SVector, U1};
use num_dual::{Derivative, DualSVec64, HyperDual64, HyperDualSVec64};

use crate::dispatch::Dispatch;
use crate::linalg::solve_fixed;
use crate::newton::{NewtonFailure, NewtonOptions, NewtonReport};
use crate::small_dual::{
    Dual2x64, Dual4x64, Dual6x64, Dual8x64, HyperDual2x64, HyperDual3x64, HyperDual4x64,
};
use crate::{DiscreteAction, DiscreteForce, Scalar};

/// Relative update size below which the next evaluation is expected to end the iteration.
/// The step equations are nearly linear in the offset (their curvature is `O(h²)` relative to
/// `M/h`), so Newton's quadratic convergence leaves round-off after any update this small; a
/// wrong guess costs one cheap evaluation (145 in 20 000 double-pendulum steps, which take
/// 3 730 instructions per step against 4 150 with hyper-dual evaluations only, callgrind).
pub(crate) const SPECULATE: f64 = 1e-3;

/// A hyper-dual number with `N`-dimensional eps₁ and eps₂ parts.
pub(crate) trait SmallDual<const N: usize>: Scalar {
    /// `re` with eps₁ = `e1 · e_i1` and eps₂ = `e_i2` (either optional).
    fn seeded(re: f64, eps1: Option<(usize, f64)>, eps2: Option<usize>) -> Self;
    /// Real part.
    fn value(&self) -> f64;
    /// eps₁ component `i`.
    fn eps1(&self, i: usize) -> f64;
    /// eps₂ component `j`.
    fn eps2(&self, j: usize) -> f64;
    /// eps₁eps₂ component `(i, j)`.
    fn eps12(&self, i: usize, j: usize) -> f64;
}

impl SmallDual<1> for HyperDual64 {
    #[inline(always)]
    fn seeded(re: f64, eps1: Option<(usize, f64)>, eps2: Option<usize>) -> Self {
        HyperDual64::new(
            re,
            eps1.map_or(0.0, |e| e.1),
            eps2.map_or(0.0, |_| 1.0),
            0.0,
        )
    }
    #[inline(always)]
    fn value(&self) -> f64 {
        self.re
    }
    #[inline(always)]
    fn eps1(&self, _i: usize) -> f64 {
        self.eps1
    }
    #[inline(always)]
    fn eps2(&self, _j: usize) -> f64 {
        self.eps2
    }
    #[inline(always)]
    fn eps12(&self, _i: usize, _j: usize) -> f64 {
        self.eps1eps2
    }
}

impl<const N: usize> SmallDual<N> for HyperDualSVec64<N, N> {
    #[inline(always)]
    fn seeded(re: f64, eps1: Option<(usize, f64)>, eps2: Option<usize>) -> Self {
        let mut x = HyperDualSVec64::<N, N>::from_re(re);
        if let Some((i, c)) = eps1 {
            let mut d = Derivative::derivative_generic(Const::<N>, U1, i);
            if let Some(m) = d.0.as_mut() {
                m[i] = c;
            }
            x.eps1 = d;
        }
        if let Some(j) = eps2 {
            x.eps2 = Derivative::derivative_generic(U1, Const::<N>, j);
        }
        x
    }
    #[inline(always)]
    fn value(&self) -> f64 {
        self.re
    }
    #[inline(always)]
    fn eps1(&self, i: usize) -> f64 {
        self.eps1.0.as_ref().map_or(0.0, |m| m[i])
    }
    #[inline(always)]
    fn eps2(&self, j: usize) -> f64 {
        self.eps2.0.as_ref().map_or(0.0, |m| m[j])
    }
    #[inline(always)]
    fn eps12(&self, i: usize, j: usize) -> f64 {
        self.eps1eps2.0.as_ref().map_or(0.0, |m| m[(i, j)])
    }
}

/// A dual number with `2N` parts: `∂/∂Q₀` in parts `0 … N−1` and `∂/∂Q₁` in parts `N … 2N−1`
/// (the residual and `p_{k+1}` of the step, without its Jacobian).
pub(crate) trait SmallGradient<const N: usize>: Scalar {
    /// `q₀ᵢ`: part `i` is 1 (`Q₀` moves, `Q₁` stays).
    fn position(re: f64, i: usize) -> Self;
    /// `Δᵢ = Q₁ᵢ − Q₀ᵢ`: part `i` is −1 and part `N + i` is 1.
    fn offset(re: f64, i: usize) -> Self;
    /// Real part.
    fn value(&self) -> f64;
    /// Part `k`.
    fn part(&self, k: usize) -> f64;
}

macro_rules! small_gradient {
    ($n:literal, $m:literal) => {
        impl SmallGradient<$n> for DualSVec64<$m> {
            #[inline(always)]
            fn position(re: f64, i: usize) -> Self {
                DualSVec64::new(re, Derivative::some(SVector::<f64, $m>::ith(i, 1.0)))
            }
            #[inline(always)]
            fn offset(re: f64, i: usize) -> Self {
                let mut eps = SVector::<f64, $m>::zeros();
                eps[i] = -1.0;
                eps[$n + i] = 1.0;
                DualSVec64::new(re, Derivative::some(eps))
            }
            #[inline(always)]
            fn value(&self) -> f64 {
                self.re
            }
            #[inline(always)]
            fn part(&self, k: usize) -> f64 {
                self.eps.0.as_ref().map_or(0.0, |m| m[k])
            }
        }
    };
}
small_gradient!(1, 2);
small_gradient!(2, 4);
small_gradient!(3, 6);
small_gradient!(4, 8);

/// `∂L_d/∂Q₀ + f_d⁻` and `p_{k+1} = ∂L_d/∂Q₁ + f_d⁺` at `(q₀, Δ)`, by one first-order dual
/// evaluation ([`SmallGradient`]; the forces by one more), and `max |∂L_d/∂Q₀|` (the size of
/// the residual's terms). Shared by the unconstrained and the constrained ([`crate::small_constrained`])
/// kernels; the sums are formed in the order of their hyper-dual evaluations.
#[inline(always)]
pub(crate) fn first_derivatives<const N: usize, G, A, F>(
    action: &A,
    force: &F,
    (t0, h): (f64, f64),
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

/// Residual, Jacobian and `p_{k+1}` of one step at the offset `delta`.
struct Evaluation<const N: usize> {
    residual: [f64; N],
    jacobian: [[f64; N]; N],
    p_next: [f64; N],
}

/// The fixed data of one step.
pub(crate) struct SmallStep<'a, A, F> {
    pub action: &'a A,
    pub force: &'a F,
    pub t0: f64,
    pub h: f64,
    pub q0: &'a [f64],
    pub p0: &'a [f64],
}

impl<A: DiscreteAction, F: DiscreteForce> SmallStep<'_, A, F> {
    /// The evaluation and the size of `∂L_d/∂Q₀` (the scale of the residual's terms).
    #[inline(always)]
    fn evaluate<const N: usize, D: SmallDual<N>>(&self, delta: &[f64; N]) -> (Evaluation<N>, f64) {
        let q: [D; N] = std::array::from_fn(|i| D::seeded(self.q0[i], Some((i, 1.0)), None));
        let d: [D; N] = std::array::from_fn(|i| D::seeded(delta[i], Some((i, -1.0)), Some(i)));
        let l = self.action.action(self.t0, self.h, &q, &d);
        // Summed as (∂L_d/∂Q₀ + f_d⁻) + p_k, in the order of the general path.
        let mut e = Evaluation {
            residual: std::array::from_fn(|i| l.eps1(i)),
            jacobian: std::array::from_fn(|i| std::array::from_fn(|j| l.eps12(i, j))),
            p_next: std::array::from_fn(|j| l.eps2(j)),
        };
        let term_scale = e.residual.iter().fold(0.0_f64, |m, r| m.max(r.abs()));
        if self.force.is_active() {
            self.add_forces::<N, D>(&q, &d, &mut e);
        }
        e.residual
            .iter_mut()
            .zip(self.p0)
            .for_each(|(r, p)| *r += p);
        (e, term_scale)
    }

    /// The residual and `p_{k+1}` only ([`SmallGradient`]; the Jacobian is left zero), and the
    /// size of `∂L_d/∂Q₀`.
    #[inline(always)]
    fn evaluate_residual<const N: usize, G: SmallGradient<N>>(
        &self,
        delta: &[f64; N],
    ) -> (Evaluation<N>, f64) {
        let step = (self.t0, self.h);
        let (mut residual, p_next, term_scale) =
            first_derivatives::<N, G, A, F>(self.action, self.force, step, self.q0, delta);
        residual.iter_mut().zip(self.p0).for_each(|(r, p)| *r += p);
        let jacobian = [[0.0; N]; N];
        let e = Evaluation {
            residual,
            jacobian,
            p_next,
        };
        (e, term_scale)
    }

    /// Adds `f_d⁻` (and its Jacobian) to the residual and `f_d⁺` to `p_{k+1}`.
    #[inline(always)]
    fn add_forces<const N: usize, D: SmallDual<N>>(
        &self,
        q: &[D; N],
        d: &[D; N],
        e: &mut Evaluation<N>,
    ) {
        let mut f = [D::from(0.0); 8];
        self.force
            .discrete_force(self.t0, self.h, q, d, &mut f[..2 * N]);
        for i in 0..N {
            e.residual[i] += f[i].value();
            e.p_next[i] += f[N + i].value();
            for j in 0..N {
                e.jacobian[i][j] += f[i].eps2(j);
            }
        }
    }
}

/// A statically sized Newton step ([`SmallStep`], [`crate::small_constrained::SmallConstrainedStep`]):
/// solved for `N` degrees of freedom with hyper-duals `D` and the cheaper duals `G` of the
/// confirming evaluation; returns the report and `p_{k+1}`.
pub(crate) trait SmallKernel {
    /// Newton's method on the step equations from `z` (overwritten with the solution).
    fn solve<const N: usize, D: SmallDual<N>, G: SmallGradient<N>>(
        &self,
        z: &mut [f64],
        options: &NewtonOptions,
    ) -> Result<(NewtonReport, [f64; N]), NewtonFailure>;
}

impl<A: DiscreteAction, F: DiscreteForce> SmallKernel for SmallStep<'_, A, F> {
    /// Newton's method on the step equations from the offset `z` (overwritten with the
    /// solution); returns the report and `p_{k+1}`.
    ///
    /// Every update uses a fresh Jacobian (hyper-dual `D`), so the iterates are those of the
    /// general path. An evaluation that is expected to end the iteration — after an update
    /// below [`SPECULATE`] — only needs the residual and `p_{k+1}` and takes the cheaper dual
    /// `G`; should it not end the iteration after all, the Jacobian is evaluated at the same
    /// point.
    #[inline(always)]
    fn solve<const N: usize, D: SmallDual<N>, G: SmallGradient<N>>(
        &self,
        z: &mut [f64],
        options: &NewtonOptions,
    ) -> Result<(NewtonReport, [f64; N]), NewtonFailure> {
        let mut delta: [f64; N] = std::array::from_fn(|i| z[i]);
        let p_scale = self.p0.iter().fold(0.0_f64, |m, p| m.max(p.abs()));
        let q_scale = self
            .q0
            .iter()
            .fold(f64::MIN_POSITIVE, |m, q| m.max(q.abs()));
        let mut report = NewtonReport::default();
        let mut update_converged = false;
        let mut expect_convergence = false;
        loop {
            let (mut e, term_scale) = if expect_convergence {
                self.evaluate_residual::<N, G>(&delta)
            } else {
                self.evaluate::<N, D>(&delta)
            };
            report.evaluations += 1;
            report.residual = e.residual.iter().fold(0.0_f64, |m, r| m.max(r.abs()));
            // Relative to the size of the residual's terms, as in `StepSystem`.
            let tol = options.residual_tolerance * p_scale.max(term_scale);
            if !report.residual.is_finite() {
                return Err(NewtonFailure::NonFinite(report));
            }
            if report.residual <= tol || update_converged {
                z[..N].copy_from_slice(&delta);
                return Ok((report, e.p_next));
            }
            if report.iterations >= options.max_iterations {
                return Err(NewtonFailure::NotConverged(report));
            }
            if expect_convergence {
                // The speculation failed: the Jacobian at this iterate.
                e = self.evaluate::<N, D>(&delta).0;
                report.evaluations += 1;
            }
            let mut update = e.residual.map(|r| -r);
            solve_fixed(&mut e.jacobian, &mut update).map_err(|s| NewtonFailure::Singular {
                iteration: report.iterations,
                pivot: s.pivot,
            })?;
            report.iterations += 1;
            report.factorizations += 1;
            let size = update.iter().fold(0.0_f64, |m, u| m.max(u.abs()));
            delta.iter_mut().zip(&update).for_each(|(d, u)| *d += u);
            let znorm = delta.iter().fold(q_scale, |m, d| m.max(d.abs()));
            update_converged = size <= options.step_tolerance * znorm;
            // Quadratic convergence: the next error is about ‖δ‖²/‖Δ‖ in relative terms.
            expect_convergence = size <= SPECULATE * znorm;
        }
    }
}

/// `kernel` for the run-time `n ≤ 4` (the duals of each size: `HyperDual64`/`Dual2` for n = 1,
/// [`crate::small_dual`]'s for n = 2…4) in the instruction set `dispatch` chose
/// ([`crate::dispatch`]); writes `p_{k+1}` into `p_next`.
#[inline(always)]
pub(crate) fn solve_sized<K: SmallKernel>(
    dispatch: Dispatch,
    kernel: &K,
    n: usize,
    z: &mut [f64],
    options: &NewtonOptions,
    p_next: &mut [f64],
) -> Result<NewtonReport, NewtonFailure> {
    let mut keep = |(report, p): (NewtonReport, &[f64])| {
        p_next.copy_from_slice(p);
        report
    };
    dispatch.run(
        #[inline(always)]
        || match n {
            1 => kernel
                .solve::<1, HyperDual64, Dual2x64>(z, options)
                .map(|(r, p)| keep((r, &p))),
            2 => kernel
                .solve::<2, HyperDual2x64, Dual4x64>(z, options)
                .map(|(r, p)| keep((r, &p))),
            3 => kernel
                .solve::<3, HyperDual3x64, Dual6x64>(z, options)
                .map(|(r, p)| keep((r, &p))),
            _ => kernel
                .solve::<4, HyperDual4x64, Dual8x64>(z, options)
                .map(|(r, p)| keep((r, &p))),
        },
    )
}
