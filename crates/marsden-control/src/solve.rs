//! Solving a problem with a rule: transcription, SQP, and the result read off the last
//! iterate.

use marsden::{DiscreteAction, DiscreteForce, Lagrangian, Rule};

use crate::error::ControlError;
use crate::guess;
use crate::model::{ControlForce, FinalCost, PathConstraint, RunningCost};
use crate::problem::OptimalControl;
use crate::solution::{Infeasibility, Solution, Status};
use crate::sqp::{self, Program, SqpOptions, SqpOutcome, VariableBounds};
use crate::stages::StagedControls;
use crate::transcription::step::{Augmented, CostLagrangian, StepParts};
use crate::transcription::{Evaluation, Ingredients, Layout, Transcription, Unknown};

impl<L, A, FD, CD, P, G> Program for Transcription<'_, L, A, FD, CD, P, G>
where
    L: Lagrangian,
    A: DiscreteAction,
    FD: DiscreteForce,
    CD: DiscreteAction,
    P: FinalCost,
    G: PathConstraint,
{
    fn evaluate(&self, z: &[f64]) -> Evaluation {
        Transcription::evaluate(self, z)
    }
    fn hessian(&self, z: &[f64], lambda: &[f64]) -> Vec<(usize, usize, f64)> {
        Transcription::hessian(self, z, lambda)
    }
    fn rows(&self) -> usize {
        self.rows
    }
}

impl<L, F, C, P, G> OptimalControl<L, F, C, P, G>
where
    L: Lagrangian,
    F: ControlForce,
    C: RunningCost,
    P: FinalCost,
    G: PathConstraint,
{
    /// Solves the problem transcribed with `rule`: a two-point rule (midpoint, trapezoid, the
    /// α and symmetrised α rules) with one control value per step, a Galerkin rule (`gauss-s`,
    /// `lobatto-s`) with one per quadrature node, or a composition of either with one per step
    /// ([`crate::stages`]).
    ///
    /// A solve that does not converge is not an error: the [`Solution`] carries its status and
    /// the last iterate.
    ///
    /// # Errors
    /// [`ControlError::Option`] for tolerances that are not positive,
    /// [`ControlError::UnsupportedRule`] if the rule's steps do not have the control points its
    /// [`StagedControls`] describe.
    pub fn solve<R: Rule + StagedControls>(
        &self,
        rule: &R,
        options: &SqpOptions,
    ) -> Result<Solution, ControlError> {
        check_options(options)?;
        self.with_program(rule, |program| {
            let z0 = guess::initial(self, rule, program.stages(), &program.layout);
            let bounds = self.variable_bounds(&program.layout);
            let outcome = sqp::solve(program, z0, &bounds, options);
            self.solution(program, outcome)
        })
    }

    /// Builds the transcription of the problem with `rule` and hands it to `f`.
    ///
    /// # Errors
    /// [`ControlError::UnsupportedRule`] if the rule's steps do not have the control points its
    /// [`StagedControls`] describe.
    #[allow(clippy::type_complexity)]
    pub(crate) fn with_program<'s, R: Rule + StagedControls, T>(
        &'s self,
        rule: &R,
        f: impl FnOnce(
            &Transcription<
                '_,
                L,
                R::Discrete<&'s L>,
                R::DiscreteForce<Augmented<&'s F>>,
                R::Discrete<CostLagrangian<&'s C>>,
                P,
                G,
            >,
        ) -> T,
    ) -> Result<T, ControlError> {
        let (n, m) = (self.dof(), self.controls());
        let ld = rule.discretize(&self.lagrangian);
        let stages = rule.control_stages();
        if stages.inner() != ld.internal_stages() {
            return Err(ControlError::UnsupportedRule {
                rule: rule.name(),
                reason: format!(
                    "its steps have {} inner control points, its control stages describe {}",
                    ld.internal_stages(),
                    stages.inner()
                ),
            });
        }
        let fd = rule.discretize_force(
            Augmented {
                force: &self.force,
                n,
            },
            n + m,
        );
        let cd = rule.discretize(CostLagrangian {
            cost: &self.cost,
            n,
            m,
        });
        let parts = StepParts {
            ld: &ld,
            fd: &fd,
            cd: &cd,
            final_cost: None,
            stages: &stages,
            n,
            m,
        };
        let ingredients = Ingredients {
            lagrangian: &self.lagrangian,
            final_cost: &self.final_cost,
            path: &self.path,
            grid: self.grid,
            ends: (&self.start, &self.end),
        };
        let program = Transcription::new(parts, ingredients);
        Ok(f(&program))
    }

    /// Per-unknown bounds from the control and state bounds.
    fn variable_bounds(&self, layout: &Layout) -> VariableBounds {
        let mut bounds = VariableBounds {
            lower: vec![f64::NEG_INFINITY; layout.unknowns()],
            upper: vec![f64::INFINITY; layout.unknowns()],
        };
        for k in 0..=layout.steps {
            let q = layout.q(k);
            bounds.lower[q..q + layout.n].copy_from_slice(&self.state_bounds.lower);
            bounds.upper[q..q + layout.n].copy_from_slice(&self.state_bounds.upper);
            if k < layout.steps {
                for stage in 0..layout.stages {
                    let u = layout.u(k) + stage * layout.m;
                    bounds.lower[u..u + layout.m].copy_from_slice(&self.control_bounds.lower);
                    bounds.upper[u..u + layout.m].copy_from_slice(&self.control_bounds.upper);
                }
            }
        }
        bounds
    }

    fn solution<A, FD, CD>(
        &self,
        program: &Transcription<'_, L, A, FD, CD, P, G>,
        outcome: SqpOutcome,
    ) -> Solution
    where
        A: DiscreteAction,
        FD: DiscreteForce,
        CD: DiscreteAction,
    {
        let layout = program.layout;
        let (n, steps) = (layout.n, layout.steps);
        let z = &outcome.z;
        let e = &outcome.evaluation;
        let q = (0..=steps)
            .map(|k| z[layout.q(k)..layout.q(k) + n].to_vec())
            .collect();
        let (sigma, m, h) = (layout.stages, layout.m, self.grid.h);
        let u = (0..steps * sigma)
            .map(|r| layout.u(r / sigma) + (r % sigma) * m)
            .map(|i| z[i..i + m].to_vec())
            .collect();
        let stages = program.stages();
        let control_times = (0..steps * sigma)
            .map(|r| self.grid.time(r / sigma) + stages.times[r % sigma] * h)
            .collect();
        let inner = (0..steps)
            .map(|k| z[layout.inner_points(k)..layout.q(k + 1)].to_vec())
            .collect();
        // p_0 = −m_0, p_{k+1} = P_k.
        let mut p = vec![e.momenta[..n].iter().map(|x| -x).collect::<Vec<f64>>()];
        p.extend((0..steps).map(|k| e.momenta[2 * n * k + n..2 * n * (k + 1)].to_vec()));
        let (start_multipliers, end_multipliers) = program.boundary_multipliers(&outcome.lambda);
        let status = match (outcome.status, &outcome.certificate) {
            (Status::Infeasible(mut infeasibility), Some(certificate)) => {
                locate(&mut infeasibility, &layout, &certificate.bounded);
                let count = self.path.count().max(1);
                infeasibility.path = certificate.inequalities.iter().map(|r| r % count).collect();
                infeasibility.path.sort_unstable();
                infeasibility.path.dedup();
                Status::Infeasible(infeasibility)
            }
            (status, _) => status,
        };
        Solution {
            status,
            cost: e.cost,
            iterations: outcome.history.len(),
            kkt_residual: outcome.kkt,
            constraint_violation: e.max_violation(),
            t: (0..=steps).map(|k| self.grid.time(k)).collect(),
            q,
            p,
            u,
            control_times,
            stages: stages.clone(),
            inner,
            costates: program.costates(&outcome.lambda),
            start_multipliers,
            end_multipliers,
            path_values: program.path_rows_by_step(&e.constraints),
            path_multipliers: program.path_rows_by_step(&outcome.lambda),
            history: outcome.history,
        }
    }
}

/// The controls and coordinates of the bounded unknowns `variables` of `layout`.
fn locate(infeasibility: &mut Infeasibility, layout: &Layout, variables: &[usize]) {
    for &i in variables {
        let list = match layout.unknown(i) {
            Unknown::Coordinate(c) | Unknown::Inner(c) => (&mut infeasibility.coordinates, c),
            Unknown::Control(j) => (&mut infeasibility.controls, j),
        };
        if !list.0.contains(&list.1) {
            list.0.push(list.1);
        }
    }
    infeasibility.controls.sort_unstable();
    infeasibility.coordinates.sort_unstable();
}

fn check_options(options: &SqpOptions) -> Result<(), ControlError> {
    for (name, value) in [
        ("kkt_tolerance", options.kkt_tolerance),
        ("constraint_tolerance", options.constraint_tolerance),
    ] {
        if !(value > 0.0 && value.is_finite()) {
            return Err(ControlError::Option {
                name,
                value,
                reason: "must be positive and finite",
            });
        }
    }
    Ok(())
}
