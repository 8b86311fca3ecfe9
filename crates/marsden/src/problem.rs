//! The problem: a mechanical system (Lagrangian, forces, constraints), its initial state and
//! the time grid — validated once, before any step is taken.

use crate::mechanics;
use crate::newton::NewtonOptions;
use crate::simulate::{Observer, RunOptions, TimeGrid, simulate};
use crate::{
    Constraint, Error, Force, Integrator, Lagrangian, NoForce, RunFailure, State, Trajectory,
    Unconstrained, rules::Rule,
};

/// Initial data, given as velocities or as momenta.
#[derive(Debug, Clone, PartialEq)]
pub enum Initial {
    /// `(q₀, v₀)`; the momenta are `p₀ = ∂L/∂v(t₀, q₀, v₀)`.
    Velocity {
        /// Positions.
        q: Vec<f64>,
        /// Velocities.
        v: Vec<f64>,
    },
    /// `(q₀, p₀)`; the velocities are found by inverting the Legendre transform.
    Momentum {
        /// Positions.
        q: Vec<f64>,
        /// Momenta.
        p: Vec<f64>,
    },
}

impl Initial {
    /// Initial positions and velocities.
    pub fn velocity(q: &[f64], v: &[f64]) -> Self {
        Self::Velocity {
            q: q.to_vec(),
            v: v.to_vec(),
        }
    }

    /// Initial positions and momenta.
    pub fn momentum(q: &[f64], p: &[f64]) -> Self {
        Self::Momentum {
            q: q.to_vec(),
            p: p.to_vec(),
        }
    }
}

/// Options of [`Problem::solve`]: one struct per layer, gathered.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SolveOptions {
    /// Newton's method inside each step.
    pub newton: NewtonOptions,
    /// Storage of the run.
    pub run: RunOptions,
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
}

impl<L: Lagrangian> Problem<L> {
    /// Validates the initial data (lengths, finiteness, regularity of `L` there) and completes
    /// it: velocities give momenta by `FL`, momenta give velocities by `FH`.
    pub fn new(lagrangian: L, initial: Initial, grid: TimeGrid) -> Result<Self, Error> {
        TimeGrid::new(grid.t0, grid.h, grid.steps)?;
        let n = lagrangian.dof();
        let t = grid.t0;
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
        }
    }

    /// Adds holonomic constraints (replacing any previous ones).
    pub fn with_constraint<C2: Constraint>(self, constraint: C2) -> Problem<L, F, C2> {
        Problem {
            lagrangian: self.lagrangian,
            force: self.force,
            constraint,
            start: self.start,
            v0: self.v0,
            grid: self.grid,
        }
    }

    /// Replaces the time grid.
    pub fn with_grid(mut self, grid: TimeGrid) -> Result<Self, Error> {
        self.grid = TimeGrid::new(grid.t0, grid.h, grid.steps)?;
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

    /// An integrator for this problem under `rule`, ready to start from [`Problem::start`].
    #[allow(clippy::type_complexity)]
    pub fn integrator<R: Rule>(
        &self,
        rule: &R,
        newton: NewtonOptions,
    ) -> Result<Integrator<R::Discrete<&L>, R::DiscreteForce<&F>, &C>, Error> {
        let n = self.lagrangian.dof();
        let mut integrator = Integrator::new(rule.discretize(&self.lagrangian))
            .with_force(rule.discretize_force(&self.force, n))
            .with_constraint(&self.constraint)
            .with_options(newton)?;
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
    pub fn solve_with<R: Rule, O: Observer + ?Sized>(
        &self,
        rule: &R,
        options: &SolveOptions,
        observer: &mut O,
    ) -> Result<Trajectory, Box<RunFailure>> {
        let mut integrator = self.integrator(rule, options.newton).map_err(|error| {
            let trajectory =
                Trajectory::new(self.lagrangian.dof(), self.constraint.count(), self.grid.h);
            Box::new(RunFailure { error, trajectory })
        })?;
        simulate(
            &mut integrator,
            self.start.clone(),
            &self.grid,
            &options.run,
            observer,
        )
        .into_result()
    }
}
