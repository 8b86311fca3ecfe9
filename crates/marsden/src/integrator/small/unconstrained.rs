//! The step for small systems, with sizes known at compile time.
//!
//! Same equations as [`crate::integrator::equations`] for a two-point discrete Lagrangian (no internal stages)
//! without constraints, solved by the same Newton iteration — but for `n ≤ 4` degrees of freedom
//! every buffer is a stack array of length `N`, the hyper-dual numbers are `HyperDual64`
//! (n = 1) or [`crate::numerics::dual`]'s `HyperDual2`, `HyperDual3`, `HyperDual4`, seeded directly in offset form (`q₀` with eps₁ = eᵢ; the
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

use super::{SPECULATE, SmallKernel, first_derivatives};
use crate::discrete::{DiscreteAction, DiscreteForce};
use crate::numerics::dense::{max_norm, solve_fixed};
use crate::numerics::dual::{SmallDual, SmallGradient};
use crate::numerics::newton::{Convergence, NewtonFailure, NewtonOptions, NewtonReport};

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
        let (t0, h) = (self.t0, self.h);
        let (mut residual, p_next, term_scale) =
            first_derivatives::<N, G, A, F>(self.action, self.force, t0, h, self.q0, delta);
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

impl<A: DiscreteAction, F: DiscreteForce> SmallKernel for SmallStep<'_, A, F> {
    const APPLIES: bool = A::MAY_BE_TWO_POINT;
    const FIXED_DOF: Option<usize> = A::FIXED_DOF;

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
        let mut convergence = Convergence::new(options);
        let mut expect_convergence = false;
        loop {
            let (mut e, term_scale) = if expect_convergence {
                self.evaluate_residual::<N, G>(&delta)
            } else {
                self.evaluate::<N, D>(&delta)
            };
            report.evaluations += 1;
            report.residual = max_norm(&e.residual);
            // Relative to the size of the residual's terms, as in `StepSystem`.
            if convergence.check(&report, p_scale.max(term_scale))? {
                z[..N].copy_from_slice(&delta);
                return Ok((report, e.p_next));
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
            let size = max_norm(&update);
            delta.iter_mut().zip(&update).for_each(|(d, u)| *d += u);
            let znorm = delta.iter().fold(q_scale, |m, d| m.max(d.abs()));
            convergence.record_update(size, znorm);
            // Quadratic convergence: the next error is about ‖δ‖²/‖Δ‖ in relative terms.
            expect_convergence = size <= SPECULATE * znorm;
        }
    }
}
