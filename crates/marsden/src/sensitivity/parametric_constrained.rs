//! Named parameters of a constrained system: of the Lagrangian, of the forces and of the
//! constraints `φ(q; θ) = 0` (a rod length in `|q|² − l²`), with SHAKE + RATTLE.
//!
//! The run is that of the model at fixed `θ` ([`AtValues`]: Lagrangian, forces and constraints
//! with `θ` as constants, under [`Rattle`]). For the derivative the model is read on `ℝⁿ⁺ᴾ`
//! with `θ` as frozen coordinates ([`Frozen`]), so `θ` enters the step equations of
//! [`super::constrained`] — the discrete action, the forces, `φ(Q₀)`, `φ(Q_s)`, `φ(X_i)` — and
//! the projection's KKT system (`super::projection`) as `q_k` does, and the implicit function
//! theorem gives `dy/dθ = −(∂R/∂y)⁻¹ ∂R/∂θ` with the same factored matrix as the state columns
//! ([MW01] §1.5, §3.5; [LMO08] §3).
//!
//! Reading the parameter columns: the step equations impose `φ(·; θ) = 0` at the new point, so
//! after the first step the state lies on `T*N(θ)` for every `θ`; `∂x_k/∂θ` then satisfies the
//! derivatives of both constraints including their explicit dependence on `θ`,
//! `Dφ δq + ∂φ/∂θ = 0` and `δ(Dφ(q; θ) FH(q, p; θ)) = 0`.
//!
//! [MW01]: crate#references
//! [LMO08]: crate#references

use super::constrained::{Model, TakenStep, constrained_jacobian};
use super::parametric::{AtValues, Frozen, ParametricModel};
use super::step::{SensitiveStep, differentiable_by_run};
use crate::analysis::certificate::variational::{
    at_step, check_stage_offsets, frozen_step_jacobian,
};
use crate::discrete::rules::Rule;
use crate::error::{Error, InputError};
use crate::holonomic::Rattle;
use crate::integrator::{Integrator, StepReport};
use crate::mechanics::{Constraint as _, State};
use crate::numerics::newton::NewtonOptions;
use crate::symmetry::StepSpan;

type RunIntegrator<R, M> = Integrator<
    <R as Rule>::Discrete<AtValues<M>>,
    <R as Rule>::DiscreteForce<AtValues<M>>,
    AtValues<M>,
    Rattle<AtValues<M>, AtValues<M>>,
>;

/// A SHAKE + RATTLE integrator of a constrained [`ParametricModel`] at values `θ` that reports
/// `∂(q_{k+1}, p_{k+1})/∂(q_k, p_k, θ)` ([`SensitiveStep`] with `P` parameters; meaningful on
/// tangent vectors of `T*N`, as [`super::constrained`] explains).
pub struct ConstrainedParametricIntegrator<R: Rule, M: ParametricModel + Clone> {
    run: RunIntegrator<R, M>,
    frozen: R::Discrete<Frozen<M>>,
    frozen_force: R::DiscreteForce<Frozen<M>>,
    model: Frozen<M>,
    theta: Vec<f64>,
    names: Vec<String>,
}

impl<R: Rule, M: ParametricModel + Clone> Clone for ConstrainedParametricIntegrator<R, M>
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
            model: self.model.clone(),
            theta: self.theta.clone(),
            names: self.names.clone(),
        }
    }
}

impl<R: Rule, M: ParametricModel + Clone> ConstrainedParametricIntegrator<R, M> {
    /// The integrator of `model` (with its constraints and the RATTLE projection) under `rule`
    /// at parameter values `theta`, with Newton `options`.
    ///
    /// # Errors
    /// A parameter list of the wrong length, invalid options, and
    /// [`InputError::UnconstrainableMethod`] for a rule without stage constraints (Gauss).
    pub fn new(rule: &R, model: M, theta: &[f64], options: NewtonOptions) -> Result<Self, Error> {
        let names = model.parameter_names();
        Error::check_len("parameters", theta, names.len())?;
        let n = model.dof();
        let at = AtValues {
            model: model.clone(),
            theta: theta.to_vec(),
        };
        at.validate(n)?;
        let rattle = Rattle::new(at.clone(), at.clone()).with_options(options);
        let run = Integrator::new(rule.discretize(at.clone()))
            .with_force(rule.discretize_force(at.clone(), n))
            .with_constraint(at)
            .with_projection(rattle)
            .with_options(options)?;
        if let Some(reason) = run.stage_constraint_refusal() {
            return Err(Error::Input(InputError::UnconstrainableMethod {
                method: rule.name(),
                reason,
            }));
        }
        let frozen = Frozen {
            model,
            parameters: theta.len(),
        };
        Ok(Self {
            run,
            frozen: rule.discretize(frozen.clone()),
            frozen_force: rule.discretize_force(frozen.clone(), n + theta.len()),
            model: frozen,
            theta: theta.to_vec(),
            names,
        })
    }

    /// Gives the first step's predictor the initial velocity `v₀` (as
    /// [`crate::run::Problem::integrator`] does).
    pub fn with_velocity_hint(mut self, v: &[f64]) -> Self {
        self.run.set_velocity_hint(v);
        self
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

// `step_with_jacobian` refuses active constraints; the constrained Jacobian is
// `step_with_sensitivity`'s.
differentiable_by_run!(ConstrainedParametricIntegrator);

impl<R: Rule, M: ParametricModel + Clone> SensitiveStep for ConstrainedParametricIntegrator<R, M> {
    fn parameters(&self) -> usize {
        self.theta.len()
    }

    super::step::carried_by!(run);

    /// One SHAKE + RATTLE step and `∂(q_{k+1}, p_{k+1})/∂(q_k, p_k, θ)`; without active
    /// constraints, the unconstrained parametric step's.
    fn step_with_sensitivity(
        &mut self,
        state: &mut State,
        h: f64,
        jac: &mut [f64],
    ) -> Result<StepReport, Error> {
        let n = self.run.shape().n;
        Error::check_len("jacobian", jac, 2 * n * (2 * n + self.theta.len()))?;
        check_stage_offsets(&self.run)?;
        let t0 = state.t;
        let report = self.run.step_keeping_start(state, h)?;
        if self.run.shape().d == 0 {
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
            return Ok(report);
        }
        let model = Model {
            action: &self.frozen,
            force: &self.frozen_force,
            constraint: &self.model,
            lagrangian: &self.model,
            theta: &self.theta,
        };
        let taken = TakenStep {
            t0,
            h,
            q0: self.run.step_start(),
            state: &*state,
            iterations: report.iterations,
        };
        constrained_jacobian(&self.run, &model, taken, jac)?;
        Ok(report)
    }
}
