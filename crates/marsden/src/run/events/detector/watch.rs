//! The detector as the stepper's watch inside a stretch of steps ([`StepWatch`]): the loop
//! that takes the stretch's steps and scans `g` at each new state.

use super::{At, EventDetector, Scan, Values, scan};
use crate::mechanics::{Lagrangian, State};
use crate::numerics::short;
use crate::run::events::EventFunction;
use crate::run::observer::{StepWatch, WatchedSteps};
use crate::run::trajectory::Termination;

/// What the watch's loop saw last ([`EventDetector::watch_positions`]).
#[derive(Debug, Clone, Copy)]
struct LastScan {
    /// What the last scan found: a sign change or a `g` that is not finite ends the loop at
    /// that step; `Quiet` when the stretch is done (or a step failed).
    found: Scan,
    /// The step of that state and its time.
    step: usize,
    t: f64,
    /// Whether the slices of `g` ended up traded (`g_before`'s values in the vector
    /// `g_after`).
    traded: bool,
}

/// The detector as the stepper's watch inside a stretch of steps: `g` evaluated at each new
/// state and the state kept as the next step's start, as
/// [`Observer::observe`](crate::run::Observer::observe) does; at a sign change (or a `g` that
/// is not finite) the stretch ends there, and the crossing is located when the run loop shows
/// the step. The run is then not taken step by step through the run loop: watching costs one
/// evaluation of `g` and a copy of the state per step.
impl<L: Lagrangian, G: EventFunction> StepWatch for EventDetector<'_, L, G> {
    fn watch(&mut self, steps: &mut dyn WatchedSteps) {
        if self.ending.is_some() || self.pending {
            // Shown to the observer after one step, which ends the run or locates the crossing.
            steps.next_step();
            return;
        }
        if self.velocities_every_step {
            while let Some((step, state)) = steps.next_step() {
                if self.watch_with_velocities(step, state) {
                    return;
                }
            }
            return;
        }
        let last = self.watch_positions(steps);
        if last.traded {
            std::mem::swap(&mut self.g_before, &mut self.g_after);
        }
        match last.found {
            Scan::Quiet => {}
            Scan::Crossed => self.pending = true,
            Scan::NotFinite(i) => {
                let error = self.not_finite(i, last.step, last.t);
                self.ending = Some(Termination::Failed(error));
            }
        }
    }
}

impl<L: Lagrangian, G: EventFunction> EventDetector<'_, L, G> {
    /// The watch at a step when an event reads the velocities: the inverse Legendre transform
    /// first, out of the common path (it costs more than the call).
    #[inline(never)]
    fn watch_with_velocities(&mut self, step: usize, state: &State) -> bool {
        let at = At {
            step,
            t: state.t,
            q: &state.q,
            p: &state.p,
        };
        match self.evaluate(&at) {
            Ok(false) => {
                self.advance(&at);
                false
            }
            Ok(true) => {
                self.pending = true;
                true
            }
            Err(error) => {
                self.ending = Some(Termination::Failed(error));
                true
            }
        }
    }

    /// The watch's loop when no event reads the velocities, over what it needs held in local
    /// borrows (so that they are not looked up again after each step): `g` at each new state,
    /// the state kept as the next step's start while `g` has not changed sign, the two slices
    /// of `g` trading their roles instead of being copied.
    #[inline(always)]
    fn watch_positions(&mut self, steps: &mut dyn WatchedSteps) -> LastScan {
        let Self {
            events,
            no_velocity,
            before,
            g_before,
            g_after,
            ..
        } = self;
        let (events, v) = (&events[..], &no_velocity[..]);
        let (mut g0, mut g1) = (&mut g_before[..], &mut g_after[..]);
        let mut traded = false;
        while let Some((step, state)) = steps.next_step() {
            let values = Values {
                g_before: g0,
                g_after: g1,
            };
            let found = scan(events, values, state.t, &state.q, v, &state.p);
            if found != Scan::Quiet {
                let t = state.t;
                return LastScan {
                    found,
                    step,
                    t,
                    traded,
                };
            }
            (before.step, before.t) = (step, state.t);
            short::copy(&mut before.q, &state.q);
            short::copy(&mut before.p, &state.p);
            std::mem::swap(&mut g0, &mut g1);
            traded = !traded;
        }
        LastScan {
            found: Scan::Quiet,
            step: before.step,
            t: before.t,
            traded,
        }
    }
}
