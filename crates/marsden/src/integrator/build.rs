//! Building an integrator: its parts (action, forces, constraints, projection), its Newton
//! options and switches. Every change of parts or switches chooses the path of the steps
//! anew ([`super::path`]), so that [`Integrator::step`] only follows it.

use super::compensated::Compensation;
use super::path::{Path, separable_applies};
use super::predictor::Predictor;
use super::report::Statistics;
use super::small::dispatch::Dispatch;
use super::{Buffers, Integrator, StepShape};
use crate::discrete::{DiscreteAction, DiscreteForce};
use crate::error::Error;
use crate::holonomic::{MomentumProjection, NoProjection};
use crate::mechanics::{Constraint, NoForce, Unconstrained};
use crate::numerics::newton::NewtonOptions;

/// The parts an integrator is assembled from.
struct Parts<A, F, C, P> {
    /// The discrete action.
    action: A,
    /// The discrete forces.
    force: F,
    /// The holonomic constraints.
    constraint: C,
    /// The momentum projection after every solved step.
    projection: P,
}

/// The switches an integrator rebuilt from new parts keeps from the one it replaces.
struct Switches {
    /// Use the fast paths when the step allows them.
    fast_paths: bool,
    /// Compensated summation of the state update, with the errors it carries.
    compensation: Compensation,
    /// The instruction set of the small kernels.
    dispatch: Dispatch,
}

impl<A: DiscreteAction> Integrator<A> {
    /// An unforced, unconstrained integrator with default Newton options.
    pub fn new(action: A) -> Self {
        let shape = StepShape {
            n: action.dof(),
            s: action.internal_stages() + 1,
            d: 0,
            forced: false,
            stages: 0,
        };
        Integrator {
            action,
            force: NoForce,
            constraint: Unconstrained,
            projection: NoProjection,
            options: NewtonOptions::default(),
            shape,
            buffers: Buffers::default(),
            predictor: Predictor::default(),
            statistics: Statistics::default(),
            path: Path::General,
            fast_paths: true,
            compensation: Compensation::default(),
            dispatch: Dispatch::detect(),
        }
        .with_path()
    }
}

impl<A: DiscreteAction, F: DiscreteForce, C: Constraint, P: MomentumProjection>
    Integrator<A, F, C, P>
{
    /// Adds discrete forces (replacing any previous ones).
    pub fn with_force<F2: DiscreteForce>(self, force: F2) -> Integrator<A, F2, C, P> {
        let shape = StepShape {
            forced: force.is_active(),
            ..self.shape
        };
        let switches = self.switches();
        let parts = Parts {
            action: self.action,
            force,
            constraint: self.constraint,
            projection: self.projection,
        };
        Integrator::assemble(parts, shape, self.options, self.statistics, switches)
    }

    /// Adds holonomic constraints (replacing any previous ones), imposed at the step's end and
    /// at the action's stage points ([`DiscreteAction::constrained_stages`]). A rule without
    /// stage constraints (Gauss) imposes them at the end only, which limits the order to 2:
    /// [`crate::run::Problem`] refuses it ([`Integrator::stage_constraint_refusal`]).
    pub fn with_constraint<C2: Constraint>(self, constraint: C2) -> Integrator<A, F, C2, P> {
        let d = constraint.count();
        let stages = if d > 0 {
            self.action.constrained_stages().unwrap_or(0)
        } else {
            0
        };
        let shape = StepShape {
            d,
            stages,
            ..self.shape
        };
        let switches = self.switches();
        let parts = Parts {
            action: self.action,
            force: self.force,
            constraint,
            projection: self.projection,
        };
        Integrator::assemble(parts, shape, self.options, self.statistics, switches)
    }

    /// Adds a momentum projection applied after every solved step (replacing any previous one),
    /// e.g. [`crate::holonomic::Rattle`] for constrained systems.
    pub fn with_projection<P2: MomentumProjection>(
        self,
        projection: P2,
    ) -> Integrator<A, F, C, P2> {
        Integrator {
            action: self.action,
            force: self.force,
            constraint: self.constraint,
            projection,
            options: self.options,
            shape: self.shape,
            buffers: self.buffers,
            predictor: self.predictor,
            statistics: self.statistics,
            path: self.path,
            fast_paths: self.fast_paths,
            compensation: self.compensation,
            dispatch: self.dispatch,
        }
    }

    /// An integrator of new parts with fresh buffers, keeping the options, counters and
    /// switches of the one it replaces; its path is chosen anew.
    fn assemble(
        parts: Parts<A, F, C, P>,
        shape: StepShape,
        options: NewtonOptions,
        statistics: Statistics,
        switches: Switches,
    ) -> Self {
        let Parts {
            action,
            force,
            constraint,
            projection,
        } = parts;
        let Switches {
            fast_paths,
            compensation,
            dispatch,
        } = switches;
        Integrator {
            action,
            force,
            constraint,
            projection,
            options,
            shape,
            buffers: Buffers::default(),
            predictor: Predictor::default(),
            statistics,
            path: Path::General,
            fast_paths,
            compensation,
            dispatch,
        }
        .with_path()
    }

    /// The switches a rebuilt integrator keeps.
    fn switches(&self) -> Switches {
        Switches {
            fast_paths: self.fast_paths,
            compensation: self.compensation.clone(),
            dispatch: self.dispatch,
        }
    }

    /// Chooses the path of the steps ([`Path::choose`]).
    fn with_path(mut self) -> Self {
        let (shape, fast, compensated) = (self.shape, self.fast_paths, self.compensation.enabled);
        let explicit = self.action.explicit().is_some();
        let (action, workspace) = (&self.action, &mut self.buffers.separable);
        self.path = Path::choose(shape, fast, compensated, explicit, || {
            separable_applies(action, workspace)
        });
        self
    }

    /// Sets the Newton options (validated).
    pub fn with_options(mut self, options: NewtonOptions) -> Result<Self, Error> {
        options.validate()?;
        self.options = options;
        Ok(self)
    }

    /// Whether to use the fast paths (default: true): the explicit Störmer–Verlet step of the
    /// trapezoid rule on separable Lagrangians ([`crate::separable::explicit`]), the Newton step with
    /// Jacobian `M/h + hα(1−α)∇²V` of the α rules on separable Lagrangians
    /// ([`crate::separable::alpha`]) — both only without forces and constraints — and the statically
    /// sized Newton steps for small systems (`crate::integrator::small::unconstrained`, `crate::integrator::small::constrained`).
    /// The general path solves the same equations (tests: equal to round-off); switching is
    /// for testing and measurement.
    pub fn with_fast_paths(mut self, enabled: bool) -> Self {
        self.fast_paths = enabled;
        self.with_path()
    }

    /// Whether the small kernels (`crate::integrator::small::unconstrained`, `crate::integrator::small::constrained`) may run in code
    /// compiled for x86-64-v3 (AVX2, FMA) when the CPU has it (default: true; chosen at run
    /// time, `crate::integrator::small::dispatch`). Both give the same bits; switch it off for tools that do not
    /// decode every AVX instruction (valgrind 3.19) or to measure the difference.
    ///
    /// ```
    /// use marsden::{Integrator, Midpoint, Rule, State, systems::DoublePendulum};
    ///
    /// let mut wide = Integrator::new(Midpoint.discretize(DoublePendulum::default()));
    /// let mut baseline = Integrator::new(Midpoint.discretize(DoublePendulum::default()))
    ///     .with_wide_instructions(false);
    /// let start = State { t: 0.0, q: vec![1.0, 0.5], p: vec![0.0, 0.0] };
    /// let (mut a, mut b) = (start.clone(), start);
    /// wide.advance(&mut a, 0.01, 100)?;
    /// baseline.advance(&mut b, 0.01, 100)?;
    /// assert_eq!(a.q, b.q);
    /// # Ok::<(), marsden::Error>(())
    /// ```
    pub fn with_wide_instructions(mut self, enabled: bool) -> Self {
        self.dispatch = if enabled {
            Dispatch::detect()
        } else {
            Dispatch::baseline()
        };
        self
    }

    /// Whether to add each step's increments to the state with compensated summation
    /// (default: false; `crate::integrator::compensated`). For long runs of high-order rules, whose
    /// truncation error is below the rounding error of `q + Δ`: over 10⁵ steps of Kepler's
    /// problem gauss-4 keeps the angular momentum to 1.4e-15 instead of 1.6e-11. Costs one
    /// gradient of the discrete action per step (`⌈n/8⌉` dual evaluations of the action, so
    /// think twice for large `n`; measured costs in BENCHMARKS.md), and the explicit
    /// run loop is not used (the explicit step of the trapezoid rule goes through Newton's
    /// method). Constrained steps are not compensated.
    ///
    /// ```
    /// use marsden::discrete::rules::Galerkin;
    /// use marsden::{Integrator, Rule, State, systems::Kepler};
    ///
    /// let rule = Galerkin::gauss(4)?;
    /// let mut integrator =
    ///     Integrator::new(rule.discretize(Kepler::default())).with_compensated_summation(true);
    /// let mut state = State { t: 0.0, q: vec![0.4, 0.0], p: vec![0.0, 2.0] };
    /// integrator.advance(&mut state, 0.05, 100)?;
    /// assert!(integrator.is_compensated());
    /// # Ok::<(), marsden::Error>(())
    /// ```
    pub fn with_compensated_summation(mut self, enabled: bool) -> Self {
        self.compensation.enabled = enabled;
        self.with_path()
    }
}
