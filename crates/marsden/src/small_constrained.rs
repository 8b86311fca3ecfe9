//! The SHAKE step for small constrained systems, with sizes known at compile time.
//!
//! Same equations as [`crate::step`] with holonomic constraints (two-point discrete Lagrangian,
//! `n ≤ 4` degrees of freedom, `d ≤ 4` constraints; DESIGN.md §3, [`crate::holonomic`]):
//!
//! ```text
//!     p_k + D₁L_d(q_k, q_k + Δ) + f_d⁻ − h Dφ(q_k)ᵀ λ = 0,      φ(q_k + Δ) = 0,
//! ```
//!
//! solved by the same Newton iteration for `(Δ, λ)`, but with stack arrays and the hyper-dual
//! numbers of [`crate::small`] seeded directly in offset form (`q₀` with eps₁ = eᵢ, `Δ` with
//! eps₁ = −eᵢ and eps₂ = eᵢ): one evaluation of `L_d` gives `D₁L_d`, its Jacobian in `Δ` and
//! `p_{k+1} = D₂L_d`, and `φ` at `q₀ + Δ` (whose eps₁ parts cancel) gives `φ` and `Dφ` there.
//! The integrator dispatches here once per step on `n`; the general path remains the reference
//! (a test checks both agree to round-off). As in [`crate::small`], an evaluation expected to
//! end the iteration takes first-order duals ([`SmallGradient`]: residual and `p_{k+1}`, no
//! Jacobian), and the iterates are those of Newton's method with a fresh Jacobian per update.

use nalgebra::{Const, U1};
use num_dual::{Derivative, Dual64, DualSVec64};

use crate::linalg::solve_in_place;
use crate::newton::{NewtonFailure, NewtonOptions, NewtonReport};
use crate::small::{SPECULATE, SmallDual, SmallGradient, SmallKernel, first_derivatives};
use crate::{Constraint, DiscreteAction, DiscreteForce, Scalar};

/// Largest number of constraints handled here.
pub(crate) const MAX_CONSTRAINTS: usize = 4;
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
        let step = (self.t0, self.h);
        let (d_q0, p_next, term_scale) =
            first_derivatives::<N, G, A, F>(self.action, self.force, step, self.q0, &z[..N]);
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

/// A first-order dual number with an `N`-dimensional derivative part.
trait SmallFirstDual<const N: usize>: Scalar {
    /// `re` with derivative `e_i`.
    fn seeded(re: f64, i: usize) -> Self;
    /// Derivative component `j`.
    fn eps(&self, j: usize) -> f64;
}

impl SmallFirstDual<1> for Dual64 {
    #[inline(always)]
    fn seeded(re: f64, _i: usize) -> Self {
        Dual64::new(re, 1.0)
    }
    #[inline(always)]
    fn eps(&self, _j: usize) -> f64 {
        self.eps
    }
}

impl<const N: usize> SmallFirstDual<N> for DualSVec64<N> {
    #[inline(always)]
    fn seeded(re: f64, i: usize) -> Self {
        let mut x = DualSVec64::<N>::from_re(re);
        x.eps = Derivative::derivative_generic(Const::<N>, U1, i);
        x
    }
    #[inline(always)]
    fn eps(&self, j: usize) -> f64 {
        self.eps.0.as_ref().map_or(0.0, |m| m[j])
    }
}

fn small_constraint_jacobian<const N: usize, D: SmallFirstDual<N>, C: Constraint>(
    c: &C,
    q: &[f64],
    values: &mut [f64],
    jac: &mut [f64],
) {
    let x: [D; N] = std::array::from_fn(|i| D::seeded(q[i], i));
    let mut phi = [D::from(0.0); MAX_CONSTRAINTS];
    let d = values.len();
    c.constraint(&x, &mut phi[..d]);
    for (k, value) in phi[..d].iter().enumerate() {
        values[k] = value.re();
        for j in 0..N {
            jac[k * N + j] = value.eps(j);
        }
    }
}

/// `φ(q)` and `Dφ(q)` (row-major d × n) by one first-order dual evaluation with static sizes
/// for `n ≤ 4`, `d ≤ 4`; the general [`crate::step`] driver otherwise.
pub(crate) fn constraint_jacobian<C: Constraint>(
    c: &C,
    q: &[f64],
    values: &mut [f64],
    jac: &mut [f64],
) {
    if values.len() > MAX_CONSTRAINTS {
        return crate::step::constraint_jacobian(c, q, values, jac);
    }
    match q.len() {
        1 => small_constraint_jacobian::<1, Dual64, C>(c, q, values, jac),
        2 => small_constraint_jacobian::<2, DualSVec64<2>, C>(c, q, values, jac),
        3 => small_constraint_jacobian::<3, DualSVec64<3>, C>(c, q, values, jac),
        4 => small_constraint_jacobian::<4, DualSVec64<4>, C>(c, q, values, jac),
        _ => crate::step::constraint_jacobian(c, q, values, jac),
    }
}

impl<A: DiscreteAction, F: DiscreteForce, C: Constraint> SmallKernel
    for SmallConstrainedStep<'_, A, F, C>
{
    /// Newton's method on the step equations from `z = (Δ, λ)` (overwritten with the solution);
    /// returns the report and `p_{k+1}`. An evaluation expected to end the iteration takes the
    /// cheaper duals `G` (see [`crate::small`]).
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
        let p_scale = self
            .p0
            .iter()
            .fold(0.0_f64, |s, p| s.max(p.abs()))
            .max(crate::step::constraint_term_scale(self.q0, self.dphi0));
        let q_scale = self
            .q0
            .iter()
            .fold(f64::MIN_POSITIVE, |s, q| s.max(q.abs()));
        let mut report = NewtonReport::default();
        let mut update_converged = false;
        let mut expect_convergence = false;
        loop {
            let mut e = if expect_convergence {
                self.evaluate_residual::<N, G>(&x[..m])
            } else {
                self.evaluate::<N, D>(&x[..m])
            };
            report.evaluations += 1;
            report.residual = e.residual[..m].iter().fold(0.0_f64, |s, r| s.max(r.abs()));
            let tol = options.residual_tolerance * p_scale.max(e.term_scale);
            if !report.residual.is_finite() {
                z[..m].copy_from_slice(&x[..m]);
                return Err(NewtonFailure::NonFinite(report));
            }
            if report.residual <= tol || update_converged {
                z[..m].copy_from_slice(&x[..m]);
                return Ok((report, e.p_next));
            }
            if report.iterations >= options.max_iterations {
                z[..m].copy_from_slice(&x[..m]);
                return Err(NewtonFailure::NotConverged(report));
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
            let size = update[..m].iter().fold(0.0_f64, |s, u| s.max(u.abs()));
            x[..m].iter_mut().zip(&update).for_each(|(a, u)| *a += u);
            let xnorm = x[..m].iter().fold(q_scale, |s, a| s.max(a.abs()));
            update_converged = size <= options.step_tolerance * xnorm;
            expect_convergence = size <= SPECULATE * xnorm;
        }
    }
}
