//! The problem: a mechanical system (Lagrangian, forces, constraints), its initial state and
//! the time grid — validated once, before any step is taken.
//!
//! With constraints, [`Problem::with_constraint`] checks that the initial data lie on the
//! constraint manifold (and are tangent to it) and that the constraints are independent there,
//! and [`Problem::integrator`] adds the RATTLE momentum projection ([`crate::holonomic`]).

use super::grid::{RunOptions, TimeGrid};
use super::observer::Observer;
use super::simulate::{Resumed, simulate, simulate_from};
use super::trajectory::{RunFailure, Trajectory};
use crate::discrete::rules::Rule;
use crate::error::Error;
use crate::error::InputError;
use crate::holonomic::{self, Rattle};
use crate::integrator::{Integrator, IntegratorCheckpoint};
use crate::mechanics;
use crate::mechanics::{Constraint, Force, Initial, Lagrangian, NoForce, State, Unconstrained};
use crate::numerics::newton::NewtonOptions;

/// Options of [`Problem::solve`]: one struct per layer, gathered.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SolveOptions {
    /// Newton's method inside each step.
    pub newton: NewtonOptions,
    /// Storage of the run.
    pub run: RunOptions,
    /// Take the general Newton path even where a structure-aware fast path applies (explicit
    /// Störmer–Verlet, the separable midpoint solve, the statically sized step): the reference
    /// the fast paths are tested against ([`Integrator::with_fast_paths`]).
    pub general_path: bool,
    /// Add each step's increments with compensated summation
    /// ([`Integrator::with_compensated_summation`]; unconstrained problems only).
    #[cfg_attr(feature = "serde", serde(default))]
    pub compensated: bool,
}

/// A mechanical system with initial data and a time grid.
///
/// ```
/// use marsden::{Initial, Midpoint, Problem, SolveOptions, TimeGrid, systems::Pendulum};
///
/// let problem = Problem::new(
///     Pendulum::default(),
///     Initial::velocity(&[1.5], &[0.0]),
///     TimeGrid::new(0.0, 0.05, 200).unwrap(),
/// )
/// .unwrap();
/// let trajectory = problem.solve(&Midpoint, &SolveOptions::default()).unwrap();
/// assert_eq!(trajectory.steps, 200);
/// ```
#[derive(Debug, Clone)]
pub struct Problem<L, F = NoForce, C = Unconstrained> {
    lagrangian: L,
    force: F,
    constraint: C,
    start: State,
    v0: Vec<f64>,
    grid: TimeGrid,
    /// How the initial data were given (`"velocity v0"` or `"momentum p0"`), for messages.
    given: &'static str,
}

impl<L: Lagrangian> Problem<L> {
    /// Validates the initial data (lengths, finiteness, regularity of `L` there) and completes
    /// it: velocities give momenta by `FL`, momenta give velocities by `FH`.
    pub fn new(lagrangian: L, initial: Initial, grid: TimeGrid) -> Result<Self, Error> {
        grid.validate()?;
        let n = lagrangian.dof();
        let t = grid.t0;
        let given = match initial {
            Initial::Velocity { .. } => "velocity v0",
            Initial::Momentum { .. } => "momentum p0",
        };
        let (q, v, p) = match initial {
            Initial::Velocity { q, v } => {
                check_vector("q0", &q, n)?;
                check_vector("v0", &v, n)?;
                mechanics::check_regular(&lagrangian, t, &q, &v)?;
                let mut p = vec![0.0; n];
                mechanics::momentum(&lagrangian, t, &q, &v, &mut p);
                (q, v, p)
            }
            Initial::Momentum { q, p } => {
                check_vector("q0", &q, n)?;
                check_vector("p0", &p, n)?;
                let mut v = vec![0.0; n];
                mechanics::velocity(&lagrangian, t, &q, &p, &mut v)?;
                mechanics::check_regular(&lagrangian, t, &q, &v)?;
                (q, v, p)
            }
        };
        mechanics::check_structure(&lagrangian, t, &q, &v)?;
        Ok(Self {
            lagrangian,
            force: NoForce,
            constraint: Unconstrained,
            start: State { t, q, p },
            v0: v,
            grid,
            given,
        })
    }
}

fn check_vector(what: &'static str, x: &[f64], n: usize) -> Result<(), Error> {
    Error::check_len(what, x, n)?;
    Error::check_finite(what, x)
}

impl<L: Lagrangian, F: Force, C: Constraint> Problem<L, F, C> {
    /// Adds an external force (replacing any previous one).
    pub fn with_force<F2: Force>(self, force: F2) -> Problem<L, F2, C> {
        Problem {
            lagrangian: self.lagrangian,
            force,
            constraint: self.constraint,
            start: self.start,
            v0: self.v0,
            grid: self.grid,
            given: self.given,
        }
    }

    /// Adds holonomic constraints `φ(q) = 0` (replacing any previous ones), after checking the
    /// initial data with [`holonomic::check_initial`] at the default tolerance
    /// [`holonomic::DEFAULT_TOLERANCE`]: `q₀` on the manifold, `Dφ(q₀)` of full rank, `v₀` tangent.
    /// Data that fail are refused with a typed error naming the residual, never moved; project
    /// them explicitly with [`Initial::project_onto`].
    pub fn with_constraint<C2: Constraint>(
        self,
        constraint: C2,
    ) -> Result<Problem<L, F, C2>, Error> {
        self.with_constraint_tolerance(constraint, holonomic::DEFAULT_TOLERANCE)
    }

    /// [`Problem::with_constraint`] with a chosen relative tolerance for the initial-data check.
    pub fn with_constraint_tolerance<C2: Constraint>(
        self,
        constraint: C2,
        tolerance: f64,
    ) -> Result<Problem<L, F, C2>, Error> {
        constraint.validate(self.lagrangian.dof())?;
        holonomic::check_initial(&constraint, &self.start.q, &self.v0, self.given, tolerance)?;
        Ok(Problem {
            lagrangian: self.lagrangian,
            force: self.force,
            constraint,
            start: self.start,
            v0: self.v0,
            grid: self.grid,
            given: self.given,
        })
    }

    /// Replaces the time grid.
    pub fn with_grid(mut self, grid: TimeGrid) -> Result<Self, Error> {
        grid.validate()?;
        self.grid = grid;
        self.start.t = grid.t0;
        Ok(self)
    }

    /// The Lagrangian.
    pub fn lagrangian(&self) -> &L {
        &self.lagrangian
    }

    /// The external force.
    pub fn force(&self) -> &F {
        &self.force
    }

    /// The constraints.
    pub fn constraint(&self) -> &C {
        &self.constraint
    }

    /// The initial phase-space state `(t₀, q₀, p₀)`.
    pub fn start(&self) -> &State {
        &self.start
    }

    /// The initial velocities `v₀`.
    pub fn initial_velocity(&self) -> &[f64] {
        &self.v0
    }

    /// The time grid.
    pub fn grid(&self) -> &TimeGrid {
        &self.grid
    }

    /// An integrator for this problem under `rule`, ready to start from [`Problem::start`]: the
    /// rule's `L_d` and `f_d^±`, the constraints, and the RATTLE momentum projection (inactive
    /// without constraints) with the same Newton options.
    ///
    /// # Errors
    /// [`InputError::UnconstrainableMethod`] for a constrained problem and a rule without
    /// stage constraints (Gauss), besides invalid forces and options.
    #[allow(clippy::type_complexity)]
    pub fn integrator<R: Rule>(
        &self,
        rule: &R,
        newton: NewtonOptions,
    ) -> Result<Integrator<R::Discrete<&L>, R::DiscreteForce<&F>, &C, Rattle<&L, &C>>, Error> {
        let n = self.lagrangian.dof();
        self.force.validate(n)?;
        let rattle = Rattle::new(&self.lagrangian, &self.constraint).with_options(newton);
        let mut integrator = Integrator::new(rule.discretize(&self.lagrangian))
            .with_force(rule.discretize_force(&self.force, n))
            .with_constraint(&self.constraint)
            .with_projection(rattle)
            .with_options(newton)?;
        if let Some(reason) = integrator.stage_constraint_refusal() {
            return Err(Error::Input(InputError::UnconstrainableMethod {
                method: rule.name(),
                reason,
            }));
        }
        integrator.set_velocity_hint(&self.v0);
        Ok(integrator)
    }

    /// Runs the problem with `rule`; a failed run returns its error with the trajectory computed
    /// up to the failure.
    pub fn solve<R: Rule>(
        &self,
        rule: &R,
        options: &SolveOptions,
    ) -> Result<Trajectory, Box<RunFailure>> {
        self.solve_with(rule, options, &mut ())
    }

    /// Like [`Problem::solve`], showing every step to `observer`.
    pub fn solve_with<R: Rule, O: Observer>(
        &self,
        rule: &R,
        options: &SolveOptions,
        observer: &mut O,
    ) -> Result<Trajectory, Box<RunFailure>> {
        self.solve_from(rule, options, observer, None)
    }

    /// [`Problem::solve_with`] from a checkpoint of the same problem, rule and options: the
    /// integrator is built as for a fresh run, `carried` restored into it, and the run goes on
    /// from `from` ([`simulate_from`]) — bit for bit the run that was checkpointed, if
    /// `observer` holds what it had accumulated then.
    ///
    /// # Errors
    /// As [`Problem::solve_with`]; a checkpoint of another kind of step
    /// ([`Integrator::restore`]) fails the run before any step, with an empty trajectory.
    pub fn solve_resumed<R: Rule, O: Observer>(
        &self,
        rule: &R,
        options: &SolveOptions,
        observer: &mut O,
        from: Resumed,
        carried: &IntegratorCheckpoint,
    ) -> Result<Trajectory, Box<RunFailure>> {
        self.solve_from(rule, options, observer, Some((from, carried)))
    }

    fn solve_from<R: Rule, O: Observer>(
        &self,
        rule: &R,
        options: &SolveOptions,
        observer: &mut O,
        resume: Option<(Resumed, &IntegratorCheckpoint)>,
    ) -> Result<Trajectory, Box<RunFailure>> {
        // Set-up errors come back with an empty trajectory (nothing was computed).
        let failure = |error| {
            let trajectory =
                Trajectory::new(self.lagrangian.dof(), self.constraint.count(), self.grid.h);
            Box::new(RunFailure { error, trajectory })
        };
        if options.compensated && self.constraint.count() > 0 {
            return Err(failure(Error::Input(InputError::InvalidOption {
                name: "compensated",
                value: 1.0,
                reason: "compensated summation applies to unconstrained problems only (the \
                         momenta of a constrained step come from its projection)",
            })));
        }
        let mut integrator = self
            .integrator(rule, options.newton)
            .map_err(failure)?
            .with_fast_paths(!options.general_path)
            .with_compensated_summation(options.compensated);
        let trajectory = match resume {
            None => simulate(
                &mut integrator,
                self.start.clone(),
                &self.grid,
                &options.run,
                observer,
            ),
            Some((from, carried)) => {
                integrator.restore(carried).map_err(failure)?;
                simulate_from(&mut integrator, from, &self.grid, &options.run, observer)
            }
        };
        trajectory.into_result()
    }
}
