//! Solving a problem with a rule: transcription, SQP, and the result read off the last
//! iterate.

use marsden::{DiscreteAction, DiscreteForce, Lagrangian, Rule};

use crate::error::ControlError;
use crate::guess;
use crate::model::{ControlForce, FinalCost, RunningCost};
use crate::problem::OptimalControl;
use crate::solution::{Infeasibility, Solution, Status};
use crate::sqp::{self, Program, SqpOptions, SqpOutcome, VariableBounds};
use crate::transcription::step::{Augmented, CostLagrangian, StepParts};
use crate::transcription::{Evaluation, Layout, Transcription};

impl<L, A, FD, CD, P> Program for Transcription<'_, L, A, FD, CD, P>
where
    L: Lagrangian,
    A: DiscreteAction,
    FD: DiscreteForce,
    CD: DiscreteAction,
    P: FinalCost,
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

impl<L, F, C, P> OptimalControl<L, F, C, P>
where
    L: Lagrangian,
    F: ControlForce,
    C: RunningCost,
    P: FinalCost,
{
    /// Solves the problem transcribed with `rule` (a two-point rule: midpoint, trapezoid, the
    /// α and symmetrised α rules).
    ///
    /// A solve that does not converge is not an error: the [`Solution`] carries its status and
    /// the last iterate.
    ///
    /// # Errors
    /// [`ControlError::UnsupportedRule`] for rules with internal stages,
    /// [`ControlError::Option`] for tolerances that are not positive.
    pub fn solve<R: Rule>(&self, rule: &R, options: &SqpOptions) -> Result<Solution, ControlError> {
        check_options(options)?;
        self.with_program(rule, |program| {
            let z0 = guess::initial(self, rule, &program.layout);
            let bounds = self.variable_bounds(&program.layout);
            let outcome = sqp::solve(program, z0, &bounds, options);
            self.solution(program, outcome)
        })
    }

    /// Builds the transcription of the problem with `rule` and hands it to `f`.
    ///
    /// # Errors
    /// [`ControlError::UnsupportedRule`] for rules with internal stages.
    #[allow(clippy::type_complexity)]
    pub(crate) fn with_program<'s, R: Rule, T>(
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
            >,
        ) -> T,
    ) -> Result<T, ControlError> {
        let (n, m) = (self.dof(), self.controls());
        let ld = rule.discretize(&self.lagrangian);
        let stages = ld.internal_stages();
        if stages != 0 {
            return Err(ControlError::UnsupportedRule {
                rule: rule.name(),
                stages,
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
            n,
            m,
        };
        let boundaries = (&self.start, &self.end);
        let program = Transcription::new(
            &self.lagrangian,
            parts,
            &self.final_cost,
            self.grid,
            boundaries,
        );
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
                let u = layout.u(k);
                bounds.lower[u..u + layout.m].copy_from_slice(&self.control_bounds.lower);
                bounds.upper[u..u + layout.m].copy_from_slice(&self.control_bounds.upper);
            }
        }
        bounds
    }

    fn solution<A, FD, CD>(
        &self,
        program: &Transcription<'_, L, A, FD, CD, P>,
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
        let u = (0..steps)
            .map(|k| z[layout.u(k)..layout.u(k) + layout.m].to_vec())
            .collect();
        // p_0 = −m_0, p_{k+1} = P_k.
        let mut p = vec![e.momenta[..n].iter().map(|x| -x).collect::<Vec<f64>>()];
        p.extend((0..steps).map(|k| e.momenta[2 * n * k + n..2 * n * (k + 1)].to_vec()));
        let (start_multipliers, end_multipliers) = program.boundary_multipliers(&outcome.lambda);
        let status = match (outcome.status, &outcome.certificate) {
            (Status::Infeasible(mut infeasibility), Some(certificate)) => {
                locate(&mut infeasibility, &layout, &certificate.bounded);
                Status::Infeasible(infeasibility)
            }
            (status, _) => status,
        };
        Solution {
            status,
            cost: e.cost,
            iterations: outcome.history.len(),
            kkt_residual: outcome.kkt,
            constraint_violation: e.constraints.iter().fold(0.0, |m, c| m.max(c.abs())),
            t: (0..=steps).map(|k| self.grid.time(k)).collect(),
            q,
            p,
            u,
            costates: program.costates(&outcome.lambda),
            start_multipliers,
            end_multipliers,
            history: outcome.history,
        }
    }
}

/// The controls and coordinates of the bounded unknowns `variables` of `layout`.
fn locate(infeasibility: &mut Infeasibility, layout: &Layout, variables: &[usize]) {
    let block = layout.n + layout.m;
    for &i in variables {
        let within = i % block;
        let list = match within < layout.n {
            true => (&mut infeasibility.coordinates, within),
            false => (&mut infeasibility.controls, within - layout.n),
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
