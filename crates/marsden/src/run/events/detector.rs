//! The event detector: an observer that watches every step for sign changes of its events and
//! locates them inside the step.

use std::ops::ControlFlow;

mod checkpoint;
mod watch;

use super::interpolant::HermiteStep;
use super::legendre::LegendreMaps;
use super::{Action, Direction, Event, EventFunction, EventRecord};
use crate::error::{Error, InputError, StepError};
use crate::mechanics::Lagrangian;
use crate::numerics::brent::{self, Bracket, BrentOptions, RootError};
use crate::numerics::short;
use crate::run::observer::{Observer, StepView, WatchedSteps};
use crate::run::trajectory::Termination;

pub use checkpoint::DetectorCheckpoint;

/// Evaluations of `g` allowed to locate one crossing (Brent's method needs about ten on smooth
/// functions; bisection of a step to round-off needs 53).
const MAX_EVALUATIONS: usize = 200;

/// A state of the run with its velocities.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct Point {
    step: usize,
    t: f64,
    q: Vec<f64>,
    v: Vec<f64>,
    p: Vec<f64>,
}

impl Point {
    fn empty(n: usize) -> Self {
        Self {
            step: 0,
            t: f64::NAN,
            q: vec![0.0; n],
            v: vec![0.0; n],
            p: vec![0.0; n],
        }
    }
}

/// The state after a step, as the detector reads it: from the run's view, or from the stepper
/// inside a stretch of steps ([`Observer::watch_steps`]).
#[derive(Debug, Clone, Copy)]
struct At<'a> {
    step: usize,
    t: f64,
    q: &'a [f64],
    p: &'a [f64],
}

impl<'a> At<'a> {
    fn view(view: &StepView<'a>) -> Self {
        Self {
            step: view.step,
            t: view.t,
            q: view.q,
            p: view.p,
        }
    }
}

/// What one pass of `g` over the events found at a state ([`EventDetector::scan`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Scan {
    /// No sign change.
    Quiet,
    /// Some event's `g` changed sign in its direction.
    Crossed,
    /// Event `i`'s `g` is not finite (its value is in `g_after[i]`).
    NotFinite(usize),
}

/// A sign change found at the end of a step, located.
#[derive(Debug, Clone, Copy)]
struct Crossing {
    event: usize,
    direction: Direction,
    t: f64,
}

/// `g` of every event at the two ends of a step: at its start (known) and at its end (being
/// filled).
struct Values<'a> {
    g_before: &'a [f64],
    g_after: &'a mut [f64],
}

/// `g_after` ← `g` of every event at the state `(t, q, v, p)`, and whether some event's `g`
/// changed sign in its direction from `g_before`: one pass over the events. Returns a small
/// value, not a `Result`: the watch calls it at every step, and the error of a `g` that is not
/// finite is built out of line ([`EventDetector::not_finite`]).
#[inline(always)]
fn scan<G: EventFunction>(
    events: &[Event<G>],
    values: Values<'_>,
    t: f64,
    q: &[f64],
    v: &[f64],
    p: &[f64],
) -> Scan {
    let mut crossed = false;
    let pairs = values.g_after.iter_mut().zip(values.g_before);
    for (i, (event, (g_after, &g_before))) in events.iter().zip(pairs).enumerate() {
        let g = event.function.value(t, q, v, p);
        *g_after = g;
        if !g.is_finite() {
            return Scan::NotFinite(i);
        }
        crossed |= !same_side(g_before, g) && event.direction.crosses(g_before, g);
    }
    match crossed {
        true => Scan::Crossed,
        false => Scan::Quiet,
    }
}

/// Whether `g` stayed strictly on one side of zero from `before` to `after` (a product that
/// underflows to 0 says no: the full test of [`Direction::crosses`] decides then), so that no
/// direction crosses: the quiet step's test, one multiplication and one comparison.
#[inline(always)]
fn same_side(before: f64, after: f64) -> bool {
    before * after > 0.0
}

/// Watches a run for the zero crossings of its [`Event`]s (see the [module](super) docs):
/// pass it to [`crate::Problem::solve_with`] or [`crate::run::simulate()`], then read
/// [`EventDetector::records`].
#[derive(Debug)]
pub struct EventDetector<'l, L, G> {
    legendre: LegendreMaps<'l, L>,
    events: Vec<Event<G>>,
    /// Whether some event reads `v`: then `v` is computed at every step; otherwise only at the
    /// two ends of a step where a sign change was found.
    velocities_every_step: bool,
    /// NaN: the velocities an event that does not read them is shown.
    no_velocity: Vec<f64>,
    /// The state before the step being looked at, and the new one: the new state is read from
    /// the run's view, and copied here only at a step with a sign change (its velocities at
    /// every step if an event reads them).
    before: Point,
    after: Point,
    /// `g` of every event at `before` and at `after`.
    g_before: Vec<f64>,
    g_after: Vec<f64>,
    /// Crossings of each event so far.
    crossings: Vec<usize>,
    records: Vec<EventRecord>,
    /// Why the run ends, once it must.
    ending: Option<Termination>,
    /// A point of the interpolant.
    probe: Point,
    /// A sign change the step watch found at the end of the step after `before` (its `g` in
    /// `g_after`), located when the run loop shows that step.
    pending: bool,
}

impl<'l, L: Lagrangian, G: EventFunction> EventDetector<'l, L, G> {
    /// A detector of `events` on the runs of `lagrangian` (whose Legendre transform gives the
    /// velocities the events read).
    ///
    /// # Errors
    /// [`InputError::InvalidOption`] for a count of 0; the error of a singular declared mass
    /// matrix.
    pub fn new(lagrangian: &'l L, events: Vec<Event<G>>) -> Result<Self, Error> {
        if events.iter().any(|e| e.count == Some(0)) {
            return Err(Error::Input(InputError::InvalidOption {
                name: "count",
                value: 0.0,
                reason: "an event's count is the number of the crossing that stops the run (or \
                         of the last one recorded): at least 1",
            }));
        }
        let n = lagrangian.dof();
        let m = events.len();
        Ok(Self {
            legendre: LegendreMaps::new(lagrangian)?,
            velocities_every_step: events.iter().any(|e| e.reads_velocity),
            no_velocity: vec![f64::NAN; n],
            events,
            before: Point::empty(n),
            after: Point::empty(n),
            g_before: vec![0.0; m],
            g_after: vec![0.0; m],
            crossings: vec![0; m],
            records: Vec::new(),
            ending: None,
            probe: Point::empty(n),
            pending: false,
        })
    }

    /// The crossings located so far, in the order of their times.
    pub fn records(&self) -> &[EventRecord] {
        &self.records
    }

    /// The records, the detector consumed.
    pub fn into_records(self) -> Vec<EventRecord> {
        self.records
    }

    /// The events watched.
    pub fn events(&self) -> &[Event<G>] {
        &self.events
    }

    /// `g_after` ← `g` at the view's state (and `after.v` ← its velocities first, if an event
    /// reads them), and whether some event's `g` changed sign in its direction from
    /// `g_before`: one pass over the events. Nothing is copied: the state is read from the
    /// view.
    fn evaluate(&mut self, view: &At<'_>) -> Result<bool, Error> {
        if self.velocities_every_step {
            // The previous velocities are the general inverse's first guess.
            let v = &mut self.after.v;
            v.copy_from_slice(&self.before.v);
            self.legendre.velocity(view.t, view.q, view.p, v)?;
        }
        match self.scan(view.t, view.q, view.p) {
            Scan::Quiet => Ok(false),
            Scan::Crossed => Ok(true),
            Scan::NotFinite(i) => Err(self.not_finite(i, view.step, view.t)),
        }
    }

    /// `g_after` ← `g` of every event at `(t, q, p)` with the velocities in `after.v` (when an
    /// event reads them; NaN otherwise), and what it found against `g_before` ([`scan`]).
    #[inline(always)]
    fn scan(&mut self, t: f64, q: &[f64], p: &[f64]) -> Scan {
        let v = match self.velocities_every_step {
            true => &self.after.v,
            false => &self.no_velocity,
        };
        let values = Values {
            g_before: &self.g_before,
            g_after: &mut self.g_after,
        };
        scan(&self.events, values, t, q, v, p)
    }

    /// The error of event `i`'s `g` (in `g_after`), not finite at the state after `step`
    /// (at `t`), which ends the step from `before`.
    #[cold]
    #[inline(never)]
    fn not_finite(&self, i: usize, step: usize, t: f64) -> Error {
        let cause = StepError::EventNotFinite {
            event: i,
            at: t,
            value: self.g_after[i],
        };
        Error::step(step.saturating_sub(1), self.before.t, cause)
    }

    /// `after` ← the view's state, to locate a crossing in the step (its velocities are
    /// already there if computed at every step).
    fn keep_after(&mut self, view: &At<'_>) {
        let after = &mut self.after;
        after.step = view.step;
        after.t = view.t;
        short::copy(&mut after.q, view.q);
        short::copy(&mut after.p, view.p);
    }

    /// `before` ← the view's state with its velocities (when computed at every step; else
    /// they are computed at a crossing) and `g`: the next step starts there.
    #[inline(always)]
    fn advance(&mut self, view: &At<'_>) {
        let before = &mut self.before;
        before.step = view.step;
        before.t = view.t;
        short::copy(&mut before.q, view.q);
        short::copy(&mut before.p, view.p);
        if self.velocities_every_step {
            std::mem::swap(&mut before.v, &mut self.after.v);
        }
        short::copy(&mut self.g_before, &self.g_after);
    }

    /// The velocities at both ends of the step, when they are not computed at every step: the
    /// general inverse starts both from the secant `(q_{k+1} − q_k)/h`, a guess that depends on
    /// the two states alone, so a run resumed from a checkpoint locates the same events to the
    /// bit.
    fn end_velocities(&mut self) -> Result<(), Error> {
        let (before, after) = (&mut self.before, &mut self.after);
        let h = after.t - before.t;
        for ((v0, v1), (q0, q1)) in
            (before.v.iter_mut().zip(after.v.iter_mut())).zip(before.q.iter().zip(&after.q))
        {
            *v0 = (q1 - q0) / h;
            *v1 = *v0;
        }
        self.legendre
            .velocity(before.t, &before.q, &before.p, &mut before.v)?;
        self.legendre
            .velocity(after.t, &after.q, &after.p, &mut after.v)
    }

    /// The crossings of the step from `before` to `after`, located, earliest first.
    fn crossings_in_step(&mut self) -> Result<Vec<Crossing>, Error> {
        let mut found = Vec::new();
        for i in 0..self.events.len() {
            let (g0, g1) = (self.g_before[i], self.g_after[i]);
            if !self.events[i].direction.crosses(g0, g1) {
                continue;
            }
            let direction = if g0 < 0.0 {
                Direction::Up
            } else {
                Direction::Down
            };
            let t = self.locate(i)?;
            found.push(Crossing {
                event: i,
                direction,
                t,
            });
        }
        found.sort_by(|a, b| a.t.total_cmp(&b.t));
        Ok(found)
    }

    /// The root of event `i`'s `g` along the interpolant of the step, by Brent's method.
    fn locate(&mut self, i: usize) -> Result<f64, Error> {
        let (before, after) = (&self.before, &self.after);
        let h = after.t - before.t;
        let step = HermiteStep {
            t0: before.t,
            h,
            q0: &before.q,
            v0: &before.v,
            q1: &after.q,
            v1: &after.v,
        };
        let (legendre, probe, function) =
            (&self.legendre, &mut self.probe, &self.events[i].function);
        let g = |t: f64| {
            step.at(t, &mut probe.q, &mut probe.v);
            legendre.momentum(t, &probe.q, &probe.v, &mut probe.p);
            function.value(t, &probe.q, &probe.v, &probe.p)
        };
        let options = BrentOptions {
            x_tolerance: 4.0 * f64::EPSILON * before.t.abs().max(after.t.abs()).max(h),
            max_evaluations: MAX_EVALUATIONS,
        };
        let bracket = Bracket {
            a: before.t,
            fa: self.g_before[i],
            b: after.t,
            fb: self.g_after[i],
        };
        let failure = |cause| Error::step(before.step, before.t, cause);
        match brent::find_root(g, bracket, &options) {
            Ok(root) => Ok(root.x),
            Err(RootError::NonFinite { x, value }) => Err(failure(StepError::EventNotFinite {
                event: i,
                at: x,
                value,
            })),
            Err(RootError::Budget { low, high, .. }) => Err(failure(StepError::EventNotLocated {
                event: i,
                low,
                high,
            })),
            // Not reached: the ends were checked to be finite and of opposite signs.
            Err(RootError::NotBracketed { .. }) => Err(failure(StepError::EventNotLocated {
                event: i,
                low: before.t,
                high: after.t,
            })),
        }
    }

    /// The record of a crossing: the stored state at an end of the step, else the point of the
    /// interpolant.
    fn record(&mut self, crossing: Crossing) -> EventRecord {
        let point = if crossing.t == self.after.t {
            &self.after
        } else if crossing.t == self.before.t {
            &self.before
        } else {
            let step = HermiteStep {
                t0: self.before.t,
                h: self.after.t - self.before.t,
                q0: &self.before.q,
                v0: &self.before.v,
                q1: &self.after.q,
                v1: &self.after.v,
            };
            let probe = &mut self.probe;
            step.at(crossing.t, &mut probe.q, &mut probe.v);
            self.legendre
                .momentum(crossing.t, &probe.q, &probe.v, &mut probe.p);
            probe
        };
        EventRecord {
            event: crossing.event,
            direction: crossing.direction,
            step: self.after.step,
            t: crossing.t,
            q: point.q.clone(),
            v: point.v.clone(),
            p: point.p.clone(),
        }
    }

    /// Records the step's crossings in time order, until (and including) the one that stops.
    fn act(&mut self, crossings: Vec<Crossing>) {
        for crossing in crossings {
            let i = crossing.event;
            self.crossings[i] += 1;
            let (action, count) = (self.events[i].action, self.events[i].count);
            let nth = self.crossings[i];
            match action {
                Action::Record if count.is_none_or(|n| nth <= n) => {
                    let record = self.record(crossing);
                    self.records.push(record);
                }
                Action::Record => {}
                Action::Stop => {
                    let record = self.record(crossing);
                    self.records.push(record);
                    if nth == count.unwrap_or(1) {
                        self.ending = Some(Termination::Event {
                            event: i,
                            steps: self.after.step,
                            t: crossing.t,
                        });
                        return;
                    }
                }
            }
        }
    }
}

impl<L: Lagrangian, G: EventFunction> EventDetector<'_, L, G> {
    /// Takes the step `view` ends, and locates and acts on its crossings, if any. Where no
    /// event reads the velocities, the scan alone: the run loop shows every step here when
    /// each step is a stretch of its own.
    fn look_at(&mut self, view: &At<'_>) -> Result<(), Error> {
        if self.velocities_every_step {
            return match self.evaluate(view)? {
                true => self.locate_in_step(view),
                false => Ok(()),
            };
        }
        match self.scan(view.t, view.q, view.p) {
            Scan::Quiet => Ok(()),
            Scan::Crossed => self.locate_in_step(view),
            Scan::NotFinite(i) => Err(self.not_finite(i, view.step, view.t)),
        }
    }

    /// Locates and acts on the crossings of the step `view` ends, whose `g` is in `g_after`
    /// (out of line: the common step has none).
    #[inline(never)]
    fn locate_in_step(&mut self, view: &At<'_>) -> Result<(), Error> {
        self.keep_after(view);
        if !self.velocities_every_step {
            self.end_velocities()?;
        }
        let crossings = self.crossings_in_step()?;
        self.act(crossings);
        Ok(())
    }
}

impl<L: Lagrangian, G: EventFunction> Observer for EventDetector<'_, L, G> {
    fn start(&mut self, initial: &StepView<'_>) {
        self.records.clear();
        self.crossings.iter_mut().for_each(|c| *c = 0);
        (self.ending, self.pending) = (None, false);
        self.before.v.iter_mut().for_each(|v| *v = 0.0);
        let initial = At::view(initial);
        if let Err(error) = self.evaluate(&initial) {
            self.ending = Some(Termination::Failed(error));
        }
        self.advance(&initial);
    }

    /// A step the watch has looked at ([`Observer::watch_steps`]) is passed over, unless the
    /// watch found a sign change at it: that is located now.
    fn observe(&mut self, view: &StepView<'_>) -> ControlFlow<()> {
        if self.ending.is_some() {
            return ControlFlow::Break(());
        }
        let view = At::view(view);
        if self.before.step == view.step && !self.pending {
            return ControlFlow::Continue(());
        }
        let found = match std::mem::take(&mut self.pending) {
            true => self.locate_in_step(&view),
            false => self.look_at(&view),
        };
        if let Err(error) = found {
            self.ending = Some(Termination::Failed(error));
        }
        self.advance(&view);
        match self.ending {
            Some(_) => ControlFlow::Break(()),
            None => ControlFlow::Continue(()),
        }
    }

    /// The run loop may hand the stepper stretches of steps: the detector watches each step
    /// inside them ([`Observer::watches_steps`]).
    fn every_step(&self) -> bool {
        false
    }

    fn watches_steps(&self) -> bool {
        true
    }

    fn watch_steps<W: WatchedSteps>(&mut self, steps: &mut W) {
        self.watch(steps);
    }

    fn termination(&self) -> Option<Termination> {
        self.ending.clone()
    }
}

#[cfg(test)]
mod tests {
    use super::{Direction, same_side};

    /// The quiet step's test never hides a crossing: where it says "one side", no direction
    /// crosses, over signed zeros, values whose product underflows or overflows, and infinities.
    #[test]
    fn same_side_never_hides_a_crossing() {
        let values = [
            0.0,
            -0.0,
            1e-200,
            -1e-200,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
            1.0,
            -1.0,
            1e200,
            -1e200,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        let directions = [Direction::Up, Direction::Down, Direction::Both];
        for (a, b) in values
            .iter()
            .flat_map(|&a| values.iter().map(move |&b| (a, b)))
        {
            let crossed = directions.iter().any(|d| d.crosses(a, b));
            assert!(!(same_side(a, b) && crossed), "{a} → {b}");
        }
        assert!(same_side(2.0, 3.0) && same_side(-2.0, -3.0));
        assert!(
            !same_side(1e-200, 1e-200),
            "an underflowing product leaves it to the full test"
        );
    }
}
