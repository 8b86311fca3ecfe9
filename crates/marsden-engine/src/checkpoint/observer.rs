//! The observer that checkpoints a run: it forwards every call to the observers of the run
//! and, every `checkpoint_every` steps, asks them for what they carry, adds what the
//! integrator carries and the state, and writes the checkpoint file atomically.

use std::ops::ControlFlow;

use marsden::integrator::IntegratorCheckpoint;
use marsden::run::next_multiple;
use marsden::{Constraint, Lagrangian, Observer, StepView, Termination};

use super::{BalancesCheckpoint, Carried, CheckpointPlan, RunCheckpoint, file};
use crate::balance::Balanced;
use crate::events::Watched;
use crate::noether_balance::NoetherBalanced;
use crate::observer::StreamObserver;
use marsden::discrete::DiscreteForce;
use marsden::symmetry::GroupAction;
use marsden_problem::model::MomentumMap;

/// Observers whose accumulated state can be saved into a checkpoint.
pub trait Carries {
    /// What they carry to the next step, their files flushed.
    ///
    /// # Errors
    /// A write error of a flush, as text.
    fn carried(&mut self) -> Result<Carried, String>;
    /// Whether the run was stopped from outside (a signal): it is then checkpointed where it
    /// stopped.
    fn interrupted(&self) -> bool;
}

impl<L, C, M> Carries for Watched<'_, '_, L, StreamObserver<'_, '_, L, C, M>>
where
    L: Lagrangian,
    C: Constraint,
    M: MomentumMap,
{
    fn carried(&mut self) -> Result<Carried, String> {
        Ok(Carried {
            stream: self.inner.checkpoint()?,
            events: self.checkpoint()?,
            balances: None,
            samples: self.samples_checkpoint()?,
        })
    }
    fn interrupted(&self) -> bool {
        self.inner.interrupted
    }
}

/// The balances of a forced run around the run's own observers: theirs, with the balances'.
impl<L, F, T, G, F2, O> Carries for Balanced<'_, L, F, T, NoetherBalanced<'_, G, F2, O>>
where
    L: Lagrangian,
    F: DiscreteForce,
    T: DiscreteForce,
    G: GroupAction,
    F2: DiscreteForce,
    O: Observer + Carries + ?Sized,
{
    fn carried(&mut self) -> Result<Carried, String> {
        let energy = Balanced::carried(self);
        let noether = self.inner_mut().carried();
        let mut carried = self.inner_mut().inner_mut().carried()?;
        carried.balances = Some(BalancesCheckpoint { energy, noether });
        Ok(carried)
    }
    fn interrupted(&self) -> bool {
        self.inner().inner().interrupted()
    }
}

/// `inner`, checkpointed as `plan` says.
pub struct Checkpointing<'o, O> {
    inner: &'o mut O,
    plan: &'o CheckpointPlan,
    /// Why a checkpoint could not be written (the run stopped there).
    pub error: Option<String>,
}

impl<'o, O: Observer + Carries> Checkpointing<'o, O> {
    /// Checkpoints the run `inner` watches every `plan.every` steps into `plan.path`.
    pub fn new(inner: &'o mut O, plan: &'o CheckpointPlan) -> Self {
        Self {
            inner,
            plan,
            error: None,
        }
    }

    fn save(&mut self, view: &StepView<'_>, carried: &IntegratorCheckpoint) -> Result<(), String> {
        let Carried {
            stream,
            events,
            balances,
            samples,
        } = self.inner.carried()?;
        let checkpoint = RunCheckpoint {
            identity: self.plan.identity.clone(),
            step: view.step,
            t: view.t,
            q: view.q.to_vec(),
            p: view.p.to_vec(),
            integrator: carried.clone(),
            stream,
            events,
            balances,
            samples,
        };
        file::save(&self.plan.path, &checkpoint)
    }
}

impl<O: Observer + Carries> Observer for Checkpointing<'_, O> {
    fn start(&mut self, initial: &StepView<'_>) {
        self.inner.start(initial);
    }

    fn observe(&mut self, view: &StepView<'_>) -> ControlFlow<()> {
        self.inner.observe(view)
    }

    fn every_step(&self) -> bool {
        self.inner.every_step()
    }

    /// The inner observers' next stop, or the next checkpoint's step if it comes first.
    fn next_stop(&self, step: usize) -> usize {
        (self.inner.next_stop(step)).min(next_multiple(step, self.plan.every))
    }

    fn termination(&self) -> Option<Termination> {
        self.inner.termination()
    }

    fn watches_steps(&self) -> bool {
        self.inner.watches_steps()
    }

    fn watch_steps<W: marsden::run::WatchedSteps>(&mut self, steps: &mut W) {
        self.inner.watch_steps(steps);
    }

    fn landing(&self, step: usize, t: f64, next: f64) -> Option<f64> {
        self.inner.landing(step, t, next)
    }

    fn landed(&mut self, reached: Result<&StepView<'_>, &marsden::Error>) -> ControlFlow<()> {
        self.inner.landed(reached)
    }

    fn checkpoint_due(&self, step: usize) -> bool {
        step.is_multiple_of(self.plan.every)
    }

    /// A signal's stop is checkpointed where it happened (a resume continues from there); an
    /// event's is not (the run has ended).
    fn checkpoint_at_stop(&self) -> bool {
        self.inner.interrupted()
    }

    fn checkpoint(
        &mut self,
        view: &StepView<'_>,
        carried: &IntegratorCheckpoint,
    ) -> ControlFlow<()> {
        match self.save(view, carried) {
            Ok(()) => ControlFlow::Continue(()),
            Err(e) => {
                self.error = Some(e);
                ControlFlow::Break(())
            }
        }
    }
}
