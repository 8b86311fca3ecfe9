//! The SHAKE step for small constrained systems, with sizes known at compile time.
//!
//! Same equations as [`crate::integrator::equations`] with holonomic constraints (two-point
//! discrete Lagrangian, `n ≤ 4` degrees of freedom, `d ≤ 4` constraints; the crate's
//! [conventions](crate#conventions), [`crate::holonomic`]):
//!
//! ```text
//!     p_k + D₁L_d(q_k, q_k + Δ) + f_d⁻ − h Dφ(q_k)ᵀ λ = 0,      φ(q_k + Δ) = 0,
//! ```
//!
//! solved by the same Newton iteration for `(Δ, λ)`, but with stack arrays and the hyper-dual
//! numbers of [`crate::integrator::small::unconstrained`] seeded directly in offset form (`q₀` with eps₁ = eᵢ, `Δ` with
//! eps₁ = −eᵢ and eps₂ = eᵢ): one evaluation of `L_d` gives `D₁L_d`, its Jacobian in `Δ` and
//! `p_{k+1} = D₂L_d`, and `φ` at `q₀ + Δ` (whose eps₁ parts cancel) gives `φ` and `Dφ` there.
//! The integrator dispatches here once per step on `n`; the general path remains the reference
//! (a test checks both agree to round-off). As in [`crate::integrator::small::unconstrained`], an evaluation expected to
//! end the iteration takes first-order duals ([`SmallGradient`]: residual and `p_{k+1}`, no
//! Jacobian), and the iterates are those of Newton's method with a fresh Jacobian per update.

use super::{SPECULATE, SmallKernel, first_derivatives};
use crate::discrete::{DiscreteAction, DiscreteForce};
use crate::mechanics::Constraint;
use crate::numerics::dense::{max_norm, solve_in_place};
use crate::numerics::dual::{SmallDual, SmallGradient};
use crate::numerics::newton::{Convergence, NewtonFailure, NewtonOptions, NewtonReport};

/// Largest number of constraints handled here (as by the static constraint Jacobian).
pub(crate) use crate::mechanics::constraint_jacobian::MAX_CONSTRAINTS;
/// Largest number of unknowns `n + d`.
const MAX_UNKNOWNS: usize = 8;

/// Residual, Jacobian (row-major `m × m`, `m = n + d`) and `p_{k+1}` of one step.
struct Evaluation<const N: usize> {
    /// `max |∂L_d/∂Q₀|`, the size of the residual's terms (as in `StepSystem`).
    term_scale: f64,
    residual: [f64; MAX_UNKNOWNS],
    jacobian: [f64; MAX_UNKNOWNS * MAX_UNKNOWNS],
    p_next: [f64; N],
}

/// The fixed data of one constrained step.
pub(crate) struct SmallConstrainedStep<'a, A, F, C> {
    pub action: &'a A,
    pub force: &'a F,
    pub constraint: &'a C,
    pub t0: f64,
    pub h: f64,
    pub q0: &'a [f64],
    pub p0: &'a [f64],
    /// `Dφ(q_k)`, row-major d × n.
    pub dphi0: &'a [f64],
    /// Number of constraints `d ≤ MAX_CONSTRAINTS`.
    pub d: usize,
}

impl<A: DiscreteAction, F: DiscreteForce, C: Constraint> SmallConstrainedStep<'_, A, F, C> {
    #[inline(always)]
    fn evaluate<const N: usize, D: SmallDual<N>>(&self, z: &[f64]) -> Evaluation<N> {
        let m = N + self.d;
        let q: [D; N] = std::array::from_fn(|i| D::seeded(self.q0[i], Some((i, 1.0)), None));
        let delta: [D; N] = std::array::from_fn(|i| D::seeded(z[i], Some((i, -1.0)), Some(i)));
        let l = self.action.action(self.t0, self.h, &q, &delta);
        let mut e = Evaluation {
            term_scale: 0.0,
            residual: [0.0; MAX_UNKNOWNS],
            jacobian: [0.0; MAX_UNKNOWNS * MAX_UNKNOWNS],
            p_next: std::array::from_fn(|j| l.eps2(j)),
        };
        for i in 0..N {
            e.residual[i] = l.eps1(i);
            e.term_scale = e.term_scale.max(e.residual[i].abs());
            for j in 0..N {
                e.jacobian[i * m + j] = l.eps12(i, j);
            }
        }
        if self.force.is_active() {
            self.add_forces::<N, D>(&q, &delta, m, &mut e);
        }
        // Momentum balance: + p_k − h Dφ(q_k)ᵀλ, in the order of the general path.
        let lambda = &z[N..m];
        for i in 0..N {
            e.residual[i] += self.p0[i];
            for (c, l) in lambda.iter().enumerate() {
                let g = self.dphi0[c * N + i];
                e.residual[i] -= self.h * g * l;
                e.jacobian[i * m + N + c] = -self.h * g;
            }
        }
        self.add_constraints::<N, D>(&q, &delta, m, &mut e);
        e
    }

    /// The residual and `p_{k+1}` only (the Jacobian is left zero): first-order duals for
    /// `L_d` and `f_d`, plain numbers for `φ`.
    #[inline(always)]
    fn evaluate_residual<const N: usize, G: SmallGradient<N>>(&self, z: &[f64]) -> Evaluation<N> {
        let m = N + self.d;
        let (t0, h) = (self.t0, self.h);
        let (d_q0, p_next, term_scale) =
            first_derivatives::<N, G, A, F>(self.action, self.force, t0, h, self.q0, &z[..N]);
        let mut e = Evaluation {
            term_scale,
            residual: [0.0; MAX_UNKNOWNS],
            jacobian: [0.0; MAX_UNKNOWNS * MAX_UNKNOWNS],
            p_next,
        };
        e.residual[..N].copy_from_slice(&d_q0);
        let lambda = &z[N..m];
        for i in 0..N {
            e.residual[i] += self.p0[i];
            for (c, l) in lambda.iter().enumerate() {
                e.residual[i] -= self.h * self.dphi0[c * N + i] * l;
            }
        }
        let q_end: [f64; N] = std::array::from_fn(|i| self.q0[i] + z[i]);
        self.constraint.constraint(&q_end, &mut e.residual[N..m]);
        e
    }

    /// Adds `f_d⁻` (and its Jacobian) to the residual and `f_d⁺` to `p_{k+1}`.
    #[inline(always)]
    fn add_forces<const N: usize, D: SmallDual<N>>(
        &self,
        q: &[D; N],
        delta: &[D; N],
        m: usize,
        e: &mut Evaluation<N>,
    ) {
        let mut f = [D::from(0.0); 8];
        self.force
            .discrete_force(self.t0, self.h, q, delta, &mut f[..2 * N]);
        for i in 0..N {
            e.residual[i] += f[i].value();
            e.p_next[i] += f[N + i].value();
            for j in 0..N {
                e.jacobian[i * m + j] += f[i].eps2(j);
            }
        }
    }

    /// Rows `N..m`: `φ(q₀ + Δ)` and `Dφ(q₀ + Δ)` (the eps₁ parts of `q₀` and `Δ` cancel).
    #[inline(always)]
    fn add_constraints<const N: usize, D: SmallDual<N>>(
        &self,
        q: &[D; N],
        delta: &[D; N],
        m: usize,
        e: &mut Evaluation<N>,
    ) {
        let q_end: [D; N] = std::array::from_fn(|i| q[i] + delta[i]);
        let mut phi = [D::from(0.0); MAX_CONSTRAINTS];
        self.constraint.constraint(&q_end, &mut phi[..self.d]);
        for (c, value) in phi[..self.d].iter().enumerate() {
            e.residual[N + c] = value.value();
            for j in 0..N {
                e.jacobian[(N + c) * m + j] = value.eps2(j);
            }
        }
    }
}

impl<A: DiscreteAction, F: DiscreteForce, C: Constraint> SmallKernel
    for SmallConstrainedStep<'_, A, F, C>
{
    const APPLIES: bool = A::MAY_BE_TWO_POINT && C::MAY_CONSTRAIN;
    const FIXED_DOF: Option<usize> = A::FIXED_DOF;

    /// Newton's method on the step equations from `z = (Δ, λ)` (overwritten with the solution);
    /// returns the report and `p_{k+1}`. An evaluation expected to end the iteration takes the
    /// cheaper duals `G` (see [`crate::integrator::small::unconstrained`]).
    #[inline(always)]
    fn solve<const N: usize, D: SmallDual<N>, G: SmallGradient<N>>(
        &self,
        z: &mut [f64],
        options: &NewtonOptions,
    ) -> Result<(NewtonReport, [f64; N]), NewtonFailure> {
        let m = N + self.d;
        let mut x = [0.0; MAX_UNKNOWNS];
        x[..m].copy_from_slice(&z[..m]);
        // Scale-free criteria, as in `StepSystem`: the residual relative to its terms
        // `max(|p_k|, |∂L_d/∂Q₀|)`, the update relative to the positions and unknowns.
        let p_scale = self.p0.iter().fold(0.0_f64, |s, p| s.max(p.abs())).max(
            crate::integrator::equations::constraint_term_scale(self.q0, self.dphi0),
        );
        let q_scale = self
            .q0
            .iter()
            .fold(f64::MIN_POSITIVE, |s, q| s.max(q.abs()));
        let mut report = NewtonReport::default();
        let mut convergence = Convergence::new(options);
        let mut expect_convergence = false;
        loop {
            let mut e = if expect_convergence {
                self.evaluate_residual::<N, G>(&x[..m])
            } else {
                self.evaluate::<N, D>(&x[..m])
            };
            report.evaluations += 1;
            report.residual = max_norm(&e.residual[..m]);
            match convergence.check(&report, p_scale.max(e.term_scale)) {
                Ok(false) => {}
                verdict => {
                    // Converged or failed: the last iterate goes back (a failure names φ there).
                    z[..m].copy_from_slice(&x[..m]);
                    return verdict.map(|_| (report, e.p_next));
                }
            }
            if expect_convergence {
                // The speculation failed: the Jacobian at this iterate.
                e = self.evaluate::<N, D>(&x[..m]);
                report.evaluations += 1;
            }
            let mut update = [0.0; MAX_UNKNOWNS];
            update[..m]
                .iter_mut()
                .zip(&e.residual)
                .for_each(|(u, r)| *u = -r);
            if let Err(s) = solve_in_place(&mut e.jacobian[..m * m], &mut update[..m], m) {
                z[..m].copy_from_slice(&x[..m]);
                return Err(NewtonFailure::Singular {
                    iteration: report.iterations,
                    pivot: s.pivot,
                });
            }
            report.iterations += 1;
            let size = max_norm(&update[..m]);
            x[..m].iter_mut().zip(&update).for_each(|(a, u)| *a += u);
            let xnorm = x[..m].iter().fold(q_scale, |s, a| s.max(a.abs()));
            convergence.record_update(size, xnorm);
            expect_convergence = size <= SPECULATE * xnorm;
        }
    }
}
