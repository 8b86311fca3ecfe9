//! Named parameters of the Lagrangian, the forces and the constraints, as coordinates that do
//! not move.
//!
//! A model written once over the scalar, `L(t, q, v; θ)`, `f_L(t, q, v; θ)` and `φ(q; θ)`
//! ([`ParametricModel`]; constrained models are stepped by
//! [`super::parametric_constrained::ConstrainedParametricIntegrator`]), is stepped at fixed `θ` by an ordinary [`Integrator`] ([`AtValues`]:
//! `θ` enters as constants, so the run is the run of the model with those values). For the
//! derivative, the same model is read as a system on `ℝⁿ⁺ᴾ` whose last `P` coordinates are `θ`
//! ([`Frozen`]: `L̃(t, (q, θ), (v, ·)) = L(t, q, v; θ)`, forces zero on `θ`). With the offsets of
//! `θ` held at zero, `θ` enters the discrete action exactly as `q_k` does, so one hyper-dual
//! Hessian of the frozen action gives `∂R/∂θ` beside `∂R/∂q_k`, and the implicit function
//! theorem gives the parameter columns of the step Jacobian
//! ([`crate::analysis::certificate::variational::frozen_step_jacobian`]).
//!
//! Why this design: the core's [`Lagrangian`] and [`Force`] are generic over the scalar but
//! hold their constants as `f64`; seeding a parameter needs it to be a scalar of the
//! evaluation. Rather than change those traits, a parametric model states its parameters as
//! arguments, and every rule, force discretisation and Galerkin table applies to the frozen
//! system unchanged.

use super::step::{SensitiveStep, differentiable_by_run};
use crate::analysis::certificate::variational::{
    at_step, check_stage_offsets, frozen_step_jacobian,
};
use crate::discrete::rules::Rule;
use crate::error::Error;
use crate::integrator::{Integrator, StepReport};
use crate::mechanics::{Constraint, Force, Lagrangian, State};
use crate::numerics::newton::NewtonOptions;
use crate::scalar::{Scalar, constant};
use crate::symmetry::StepSpan;

/// A Lagrangian (and optional force) with `P` named parameters `θ`.
pub trait ParametricModel {
    /// Degrees of freedom `n`.
    fn dof(&self) -> usize;

    /// The names of the parameters (length `P`), in the order of `θ`.
    fn parameter_names(&self) -> Vec<String>;

    /// `L(t, q, v; θ)`.
    fn lagrangian_with<S: Scalar>(&self, theta: &[S], t: S, q: &[S], v: &[S]) -> S;

    /// Writes `f_L(t, q, v; θ)` into `out` (length n). Default: no force.
    fn force_with<S: Scalar>(&self, theta: &[S], t: S, q: &[S], v: &[S], out: &mut [S]) {
        let _ = (theta, t, q, v);
        out.iter_mut().for_each(|f| *f = constant(0.0));
    }

    /// Whether the model has a force (default `false`).
    fn is_forced(&self) -> bool {
        false
    }

    /// Number of holonomic constraints `φ(q; θ) = 0` (default none).
    fn constraints(&self) -> usize {
        0
    }

    /// Writes `φ(q; θ)` into `out` (length [`ParametricModel::constraints`]). Default: none.
    fn constraint_with<S: Scalar>(&self, theta: &[S], q: &[S], out: &mut [S]) {
        let _ = (theta, q, out);
    }
}

/// The model at fixed parameter values: an ordinary [`Lagrangian`] and [`Force`] on `ℝⁿ`.
#[derive(Debug, Clone, PartialEq)]
pub struct AtValues<M> {
    /// The model.
    pub model: M,
    /// The parameter values `θ`.
    pub theta: Vec<f64>,
}

impl<M: ParametricModel> AtValues<M> {
    fn lifted<S: Scalar>(&self) -> impl Iterator<Item = S> + '_ {
        self.theta.iter().map(|&x| constant::<S>(x))
    }
}

/// Parameters lifted to the scalar of an evaluation, without allocating for `P ≤ 8`.
const MAX_STACK: usize = 8;

fn with_theta<S: Scalar, R>(values: impl Iterator<Item = S>, f: impl FnOnce(&[S]) -> R) -> R {
    let mut stack = [constant::<S>(0.0); MAX_STACK];
    let mut heap = Vec::new();
    let mut len = 0;
    for x in values {
        if len < MAX_STACK {
            stack[len] = x;
        } else {
            if heap.is_empty() {
                heap.extend_from_slice(&stack);
            }
            heap.push(x);
        }
        len += 1;
    }
    if len <= MAX_STACK {
        f(&stack[..len])
    } else {
        f(&heap)
    }
}

impl<M: ParametricModel> Lagrangian for AtValues<M> {
    fn dof(&self) -> usize {
        self.model.dof()
    }
    fn lagrangian<S: Scalar>(&self, t: S, q: &[S], v: &[S]) -> S {
        with_theta(self.lifted(), |theta| {
            self.model.lagrangian_with(theta, t, q, v)
        })
    }
}

impl<M: ParametricModel> Force for AtValues<M> {
    fn force<S: Scalar>(&self, t: S, q: &[S], v: &[S], out: &mut [S]) {
        with_theta(self.lifted(), |theta| {
            self.model.force_with(theta, t, q, v, out);
        });
    }
    fn is_active(&self) -> bool {
        self.model.is_forced()
    }
}

impl<M: ParametricModel> Constraint for AtValues<M> {
    fn count(&self) -> usize {
        self.model.constraints()
    }
    fn constraint<S: Scalar>(&self, q: &[S], out: &mut [S]) {
        with_theta(self.lifted(), |theta| {
            self.model.constraint_with(theta, q, out);
        });
    }
}

/// The model on `ℝⁿ⁺ᴾ` with `θ` as its last `P` coordinates (never stepped; used for the
/// derivative only).
#[derive(Debug, Clone, PartialEq)]
pub struct Frozen<M> {
    /// The model.
    pub model: M,
    /// `P`.
    pub parameters: usize,
}

impl<M: ParametricModel> Lagrangian for Frozen<M> {
    fn dof(&self) -> usize {
        self.model.dof() + self.parameters
    }
    fn lagrangian<S: Scalar>(&self, t: S, q: &[S], v: &[S]) -> S {
        let n = self.model.dof();
        self.model.lagrangian_with(&q[n..], t, &q[..n], &v[..n])
    }
}

impl<M: ParametricModel> Force for Frozen<M> {
    fn force<S: Scalar>(&self, t: S, q: &[S], v: &[S], out: &mut [S]) {
        let n = self.model.dof();
        let (free, frozen) = out.split_at_mut(n);
        self.model.force_with(&q[n..], t, &q[..n], &v[..n], free);
        frozen.iter_mut().for_each(|f| *f = constant(0.0));
    }
    fn is_active(&self) -> bool {
        self.model.is_forced()
    }
}

/// `φ̃(q, θ) = φ(q; θ)`: a constant of the constraints is a coordinate like the others.
impl<M: ParametricModel> Constraint for Frozen<M> {
    fn count(&self) -> usize {
        self.model.constraints()
    }
    fn constraint<S: Scalar>(&self, q: &[S], out: &mut [S]) {
        let n = self.model.dof();
        self.model.constraint_with(&q[n..], &q[..n], out);
    }
}

type RunIntegrator<R, M> =
    Integrator<<R as Rule>::Discrete<AtValues<M>>, <R as Rule>::DiscreteForce<AtValues<M>>>;

/// A variational integrator of a [`ParametricModel`] at values `θ` that reports
/// `∂(q_{k+1}, p_{k+1})/∂(q_k, p_k, θ)` ([`SensitiveStep`] with `P` parameters).
pub struct ParametricIntegrator<R: Rule, M: ParametricModel + Clone> {
    run: RunIntegrator<R, M>,
    frozen: R::Discrete<Frozen<M>>,
    frozen_force: R::DiscreteForce<Frozen<M>>,
    theta: Vec<f64>,
    names: Vec<String>,
}

impl<R: Rule, M: ParametricModel + Clone> Clone for ParametricIntegrator<R, M>
where
    RunIntegrator<R, M>: Clone,
    R::Discrete<Frozen<M>>: Clone,
    R::DiscreteForce<Frozen<M>>: Clone,
{
    fn clone(&self) -> Self {
        Self {
            run: self.run.clone(),
            frozen: self.frozen.clone(),
            frozen_force: self.frozen_force.clone(),
            theta: self.theta.clone(),
            names: self.names.clone(),
        }
    }
}

impl<R: Rule, M: ParametricModel + Clone> ParametricIntegrator<R, M> {
    /// The integrator of `model` under `rule` at parameter values `theta`, with Newton
    /// `options`.
    pub fn new(rule: &R, model: M, theta: &[f64], options: NewtonOptions) -> Result<Self, Error> {
        let names = model.parameter_names();
        Error::check_len("parameters", theta, names.len())?;
        let n = model.dof();
        let at = AtValues {
            model: model.clone(),
            theta: theta.to_vec(),
        };
        let run = Integrator::new(rule.discretize(at.clone()))
            .with_force(rule.discretize_force(at, n))
            .with_options(options)?;
        let frozen = Frozen {
            model,
            parameters: theta.len(),
        };
        Ok(Self {
            run,
            frozen: rule.discretize(frozen.clone()),
            frozen_force: rule.discretize_force(frozen, n + theta.len()),
            theta: theta.to_vec(),
            names,
        })
    }

    /// The integrator that takes the steps.
    pub fn integrator(&self) -> &RunIntegrator<R, M> {
        &self.run
    }

    /// The parameter values.
    pub fn theta(&self) -> &[f64] {
        &self.theta
    }

    /// The parameter names.
    pub fn names(&self) -> &[String] {
        &self.names
    }
}

differentiable_by_run!(ParametricIntegrator);

impl<R: Rule, M: ParametricModel + Clone> SensitiveStep for ParametricIntegrator<R, M> {
    fn parameters(&self) -> usize {
        self.theta.len()
    }

    super::step::carried_by!(run);

    fn step_with_sensitivity(
        &mut self,
        state: &mut State,
        h: f64,
        jac: &mut [f64],
    ) -> Result<StepReport, Error> {
        check_stage_offsets(&self.run)?;
        let t0 = state.t;
        let report = self.run.step_keeping_start(state, h)?;
        let index = self.run.statistics().steps.saturating_sub(1);
        frozen_step_jacobian(
            &self.frozen,
            &self.frozen_force,
            StepSpan { t0, h },
            self.run.step_start(),
            &self.theta,
            self.run.stage_offsets(),
            jac,
        )
        .map_err(at_step(index, t0, report.iterations))?;
        Ok(report)
    }
}
