//! The detector as the watch of the steps inside a stretch ([`Observer::watch_steps`]): the
//! loop that takes the stretch's steps and scans `g` at each new state.
//!
//! [`Observer::watch_steps`]: crate::run::Observer::watch_steps

use super::{At, Event, EventDetector, Point, Scan, Values, same_side, scan};
use crate::mechanics::{Lagrangian, State};
use crate::numerics::short;
use crate::run::events::EventFunction;
use crate::run::observer::WatchedSteps;
use crate::run::trajectory::Termination;

/// What the watch's loop saw last ([`watch_loop`]).
#[derive(Debug, Clone, Copy)]
struct LastScan {
    /// What the last scan found: a sign change or a `g` that is not finite ends the loop at
    /// that step; `Quiet` when the stretch is done (or a step failed).
    found: Scan,
    /// The step of that state and its time.
    step: usize,
    t: f64,
}

/// `g` of the events at each new state, compared with `g` at the state before: what the
/// watch's loop asks at each step ([`watch_loop`]).
trait Scanner {
    /// `g` at the new state `(t, q, p)` and what it found; when `Quiet`, the new values become
    /// the ones the next state is compared with.
    fn look(&mut self, t: f64, q: &[f64], p: &[f64]) -> Scan;
}

/// One event, the common case: `g` at the last state and at the new one held in the loop's
/// registers, written back to the detector's vectors where the loop ends ([`One::settle`]).
struct One<'a, G> {
    event: &'a Event<G>,
    v: &'a [f64],
    g_before: f64,
    g_after: f64,
}

impl<G: EventFunction> Scanner for One<'_, G> {
    #[inline(always)]
    fn look(&mut self, t: f64, q: &[f64], p: &[f64]) -> Scan {
        let g = self.event.function.value(t, q, self.v, p);
        self.g_after = g;
        match g.is_finite() {
            false => Scan::NotFinite(0),
            // The product test first: most steps keep `g`'s sign and skip the direction's.
            true if !same_side(self.g_before, g)
                && self.event.direction.crosses(self.g_before, g) =>
            {
                Scan::Crossed
            }
            true => {
                self.g_before = g;
                Scan::Quiet
            }
        }
    }
}

impl<G> One<'_, G> {
    /// `g_before[0]`, `g_after[0]` ← the loop's values.
    fn settle(&self, g_before: &mut [f64], g_after: &mut [f64]) {
        (g_before[0], g_after[0]) = (self.g_before, self.g_after);
    }
}

/// Any number of events: the two slices of `g` trade their roles at each quiet step instead
/// of being copied (the vectors swapped once where the loop ends when the count is odd).
struct Many<'a, G> {
    events: &'a [Event<G>],
    v: &'a [f64],
    g_before: &'a mut [f64],
    g_after: &'a mut [f64],
    traded: bool,
}

impl<G: EventFunction> Scanner for Many<'_, G> {
    #[inline(always)]
    fn look(&mut self, t: f64, q: &[f64], p: &[f64]) -> Scan {
        let values = Values {
            g_before: self.g_before,
            g_after: self.g_after,
        };
        let found = scan(self.events, values, t, q, self.v, p);
        if found == Scan::Quiet {
            std::mem::swap(&mut self.g_before, &mut self.g_after);
            self.traded = !self.traded;
        }
        found
    }
}

/// The detector as the stepper's watch inside a stretch of steps: `g` evaluated at each new
/// state, as [`Observer::observe`](crate::run::Observer::observe) does; at a sign change (or a
/// `g` that is not finite) the stretch ends there, with the start of that step kept as
/// `before`, and the crossing is located when the run loop shows the step. The run is then not
/// taken step by step through the run loop: watching costs one evaluation of `g` per step (and
/// a copy of each state where the stepper does not keep the starts of its steps).
impl<L: Lagrangian, G: EventFunction> EventDetector<'_, L, G> {
    /// What [`Observer::watch_steps`](crate::run::Observer::watch_steps) does for the detector.
    #[inline(always)]
    pub(super) fn watch<W: WatchedSteps>(&mut self, steps: &mut W) {
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

    /// The watch's loop when no event reads the velocities ([`watch_loop`]), for one event
    /// (its `g` in registers) or several.
    #[inline(always)]
    fn watch_positions<W: WatchedSteps>(&mut self, steps: &mut W) -> LastScan {
        let kept = steps.keep_starts();
        let v = &self.no_velocity[..];
        if let [event] = &self.events[..] {
            let mut one = One {
                event,
                v,
                g_before: self.g_before[0],
                g_after: self.g_after[0],
            };
            let last = watch_loop(&mut self.before, steps, kept, &mut one);
            one.settle(&mut self.g_before, &mut self.g_after);
            return last;
        }
        let mut many = Many {
            events: &self.events,
            v,
            g_before: &mut self.g_before,
            g_after: &mut self.g_after,
            traded: false,
        };
        let last = watch_loop(&mut self.before, steps, kept, &mut many);
        if many.traded {
            std::mem::swap(&mut self.g_before, &mut self.g_after);
        }
        last
    }
}

/// The watch's loop over the steps of a stretch, with what it needs held in local borrows (so
/// that they are not looked up again after each step): `scanner` looks at each new state. The
/// state is kept in `before` as the next step's start only where the loop ends (the stretch's
/// last state, or the start of the step where `g` changed sign, which the stepper kept:
/// [`WatchedSteps::step_start`]) when the stepper keeps the starts of its steps (`kept`); else
/// each new state is copied there.
#[inline(always)]
fn watch_loop<W: WatchedSteps>(
    before: &mut Point,
    steps: &mut W,
    kept: bool,
    scanner: &mut impl Scanner,
) -> LastScan {
    // The step and time of the last state the scanner's `g_before` belongs to.
    let (mut last_step, mut last_t) = (before.step, before.t);
    while let Some((step, state)) = steps.next_step() {
        let found = scanner.look(state.t, &state.q, &state.p);
        if found != Scan::Quiet {
            let t = state.t;
            if let Some((q, p)) = steps.step_start().filter(|_| kept) {
                keep(before, last_step, last_t, q, p);
            }
            return LastScan { found, step, t };
        }
        (last_step, last_t) = (step, state.t);
        if !kept {
            keep(before, step, state.t, &state.q, &state.p);
        }
    }
    if kept && last_step != before.step {
        let (_, state) = steps.current();
        keep(before, last_step, last_t, &state.q, &state.p);
    }
    LastScan {
        found: Scan::Quiet,
        step: before.step,
        t: before.t,
    }
}

/// `point` ← the state `(q, p)` of step `step` at time `t` (its velocities are not read).
#[inline(always)]
fn keep(point: &mut Point, step: usize, t: f64, q: &[f64], p: &[f64]) {
    (point.step, point.t) = (step, t);
    short::copy(&mut point.q, q);
    short::copy(&mut point.p, p);
}
