//! The optimal control problem: a mechanical system, controlled forces, costs, horizon,
//! boundary conditions, bounds and an initial guess.
//!
//! ```text
//!     minimise  J_d = Σ_k C_d(q_k, q_{k+1}, u_k) + Φ(q_N, p_N)
//!     subject to the forced DEL equations at k = 1 … N−1, the boundary conditions on
//!     (q_0, p_0) and (q_N, p_N), lo ≤ u_k ≤ hi, lo ≤ q_k ≤ hi, and g(t, q, q̇, u) ≤ 0 at
//!     each step's path points,
//! ```
//!
//! with `C_d` the rule's quadrature of `∫ C dt` over a step ([OJM11] §3.2; see
//! [`crate::transcription`]).
//!
//! [OJM11]: crate#references

use marsden::{Lagrangian, TimeGrid};

use crate::error::ControlError;
use crate::model::{ControlForce, FinalCost, NoFinalCost, NoPath, PathConstraint, RunningCost};

/// How the rate at a boundary is given, component by component (`None`: free).
#[derive(Debug, Clone, PartialEq)]
pub enum Rate {
    /// Velocities `v`; the condition is on `p = ∂L/∂v(t, q, v)`, so either every component is
    /// given or none.
    Velocity(Vec<Option<f64>>),
    /// Momenta `p`, each component fixed or free.
    Momentum(Vec<Option<f64>>),
}

/// The conditions at one end of the horizon: positions and a rate, each component fixed
/// (`Some`) or free (`None`).
#[derive(Debug, Clone, PartialEq)]
pub struct Boundary {
    /// Positions.
    pub q: Vec<Option<f64>>,
    /// Velocities or momenta.
    pub rate: Rate,
}

impl Boundary {
    /// At rest at `q` (`v = 0`).
    pub fn rest(q: &[f64]) -> Self {
        Self {
            q: q.iter().copied().map(Some).collect(),
            rate: Rate::Velocity(vec![Some(0.0); q.len()]),
        }
    }

    /// Positions and velocities given.
    pub fn velocity(q: &[f64], v: &[f64]) -> Self {
        Self {
            q: q.iter().copied().map(Some).collect(),
            rate: Rate::Velocity(v.iter().copied().map(Some).collect()),
        }
    }

    /// Positions and momenta given.
    pub fn momentum(q: &[f64], p: &[f64]) -> Self {
        Self {
            q: q.iter().copied().map(Some).collect(),
            rate: Rate::Momentum(p.iter().copied().map(Some).collect()),
        }
    }

    /// Nothing fixed (`n` coordinates).
    pub fn free(n: usize) -> Self {
        Self {
            q: vec![None; n],
            rate: Rate::Momentum(vec![None; n]),
        }
    }

    /// The components of the rate, fixed or free.
    pub fn rate_values(&self) -> &[Option<f64>] {
        match &self.rate {
            Rate::Velocity(v) | Rate::Momentum(v) => v,
        }
    }

    /// Whether every position and rate component is given.
    pub fn is_complete(&self) -> bool {
        self.q.iter().chain(self.rate_values()).all(Option::is_some)
    }

    fn check(&self, which: &'static str, n: usize) -> Result<(), ControlError> {
        let (what_q, what_rate) = match which {
            "start" => ("start q", "start rate"),
            _ => ("end q", "end rate"),
        };
        check_len(what_q, self.q.len(), n)?;
        check_len(what_rate, self.rate_values().len(), n)?;
        for (what, values) in [(what_q, &self.q[..]), (what_rate, self.rate_values())] {
            for (index, value) in values.iter().enumerate() {
                if let Some(value) = *value
                    && !value.is_finite()
                {
                    return Err(ControlError::NotFinite { what, index, value });
                }
            }
        }
        if let Rate::Velocity(v) = &self.rate {
            let free: Vec<usize> = (0..n).filter(|&i| v[i].is_none()).collect();
            if !free.is_empty() && free.len() < n {
                return Err(ControlError::PartialVelocity { which, free });
            }
        }
        Ok(())
    }
}

/// Simple bounds `lower ≤ x ≤ upper`, component by component (infinite: no bound).
#[derive(Debug, Clone, PartialEq)]
pub struct Bounds {
    /// Lower bounds.
    pub lower: Vec<f64>,
    /// Upper bounds.
    pub upper: Vec<f64>,
}

impl Bounds {
    /// No bounds on `len` components.
    pub fn none(len: usize) -> Self {
        Self {
            lower: vec![f64::NEG_INFINITY; len],
            upper: vec![f64::INFINITY; len],
        }
    }

    /// `lower ≤ x ≤ upper`, checked for `len` components.
    pub fn new(
        what: &'static str,
        len: usize,
        lower: &[f64],
        upper: &[f64],
    ) -> Result<Self, ControlError> {
        check_len(what, lower.len(), len)?;
        check_len(what, upper.len(), len)?;
        for (index, (&lo, &hi)) in lower.iter().zip(upper).enumerate() {
            for value in [lo, hi] {
                if value.is_nan() {
                    return Err(ControlError::NotFinite { what, index, value });
                }
            }
            if lo > hi {
                return Err(ControlError::Bounds {
                    what,
                    index,
                    lower: lo,
                    upper: hi,
                });
            }
        }
        Ok(Self {
            lower: lower.to_vec(),
            upper: upper.to_vec(),
        })
    }
}

/// An initial guess: positions at the `N + 1` nodes, controls on the `N` steps.
#[derive(Debug, Clone, PartialEq)]
pub struct Guess {
    /// `q_0 … q_N`.
    pub q: Vec<Vec<f64>>,
    /// `u_0 … u_{N−1}`.
    pub u: Vec<Vec<f64>>,
}

/// A DMOC problem ([OJM11]): minimise a discrete cost over positions and piecewise-constant
/// controls subject to the forced discrete Euler–Lagrange equations.
///
/// [OJM11]: crate#references
#[derive(Debug, Clone)]
pub struct OptimalControl<L, F, C, P = NoFinalCost, G = NoPath> {
    pub(crate) lagrangian: L,
    pub(crate) force: F,
    pub(crate) cost: C,
    pub(crate) final_cost: P,
    pub(crate) path: G,
    pub(crate) grid: TimeGrid,
    pub(crate) start: Boundary,
    pub(crate) end: Boundary,
    pub(crate) control_bounds: Bounds,
    pub(crate) state_bounds: Bounds,
    pub(crate) guess: Option<Guess>,
}

/// The time horizon of an [`OptimalControl`] problem: `[t0, t0 + duration]` in `steps` steps of
/// equal length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Horizon {
    /// The start time `t0`.
    pub t0: f64,
    /// The length of the horizon.
    pub duration: f64,
    /// The number of steps.
    pub steps: usize,
}

impl<L: Lagrangian, F: ControlForce, C: RunningCost> OptimalControl<L, F, C> {
    /// The problem on the `horizon` `[t0, t0 + duration]` with `steps` steps of equal length, no
    /// bounds, no final cost, and the default initial guess ([`crate::guess`]).
    ///
    /// # Errors
    /// [`ControlError::Horizon`], and [`ControlError::Length`], [`ControlError::NotFinite`] or
    /// [`ControlError::PartialVelocity`] for boundary data that do not fit the system.
    pub fn new(
        lagrangian: L,
        force: F,
        cost: C,
        horizon: Horizon,
        start: Boundary,
        end: Boundary,
    ) -> Result<Self, ControlError> {
        let Horizon {
            t0,
            duration,
            steps,
        } = horizon;
        let horizon = ControlError::Horizon { duration, steps };
        if !(duration > 0.0 && duration.is_finite() && t0.is_finite()) || steps == 0 {
            return Err(horizon);
        }
        let grid = TimeGrid::new(t0, duration / steps as f64, steps).map_err(|_| horizon)?;
        let n = lagrangian.dof();
        let m = force.controls();
        start.check("start", n)?;
        end.check("end", n)?;
        Ok(Self {
            lagrangian,
            force,
            cost,
            final_cost: NoFinalCost,
            path: NoPath,
            grid,
            start,
            end,
            control_bounds: Bounds::none(m),
            state_bounds: Bounds::none(n),
            guess: None,
        })
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
    /// The same problem with the final cost `Φ(q_N, p_N)`.
    pub fn with_final_cost<P2: FinalCost>(self, final_cost: P2) -> OptimalControl<L, F, C, P2, G> {
        OptimalControl {
            lagrangian: self.lagrangian,
            force: self.force,
            cost: self.cost,
            final_cost,
            path: self.path,
            grid: self.grid,
            start: self.start,
            end: self.end,
            control_bounds: self.control_bounds,
            state_bounds: self.state_bounds,
            guess: self.guess,
        }
    }

    /// The same problem with the path inequalities `g(t, q, q̇, u) ≤ 0`, imposed at each
    /// control value's point of every step ([`crate::stages::PathPoints`]).
    pub fn with_path<G2: PathConstraint>(self, path: G2) -> OptimalControl<L, F, C, P, G2> {
        OptimalControl {
            lagrangian: self.lagrangian,
            force: self.force,
            cost: self.cost,
            final_cost: self.final_cost,
            path,
            grid: self.grid,
            start: self.start,
            end: self.end,
            control_bounds: self.control_bounds,
            state_bounds: self.state_bounds,
            guess: self.guess,
        }
    }

    /// Bounds `lower ≤ u_k ≤ upper` on every control.
    ///
    /// # Errors
    /// [`ControlError::Length`], [`ControlError::Bounds`] (lower > upper) or NaN bounds.
    pub fn with_control_bounds(
        mut self,
        lower: &[f64],
        upper: &[f64],
    ) -> Result<Self, ControlError> {
        self.control_bounds = Bounds::new("control", self.controls(), lower, upper)?;
        Ok(self)
    }

    /// Bounds `lower ≤ q_k ≤ upper` on every node's positions.
    ///
    /// # Errors
    /// As [`OptimalControl::with_control_bounds`].
    pub fn with_state_bounds(mut self, lower: &[f64], upper: &[f64]) -> Result<Self, ControlError> {
        self.state_bounds = Bounds::new("state", self.dof(), lower, upper)?;
        Ok(self)
    }

    /// The initial guess of the solver, instead of the default ([`crate::guess`]).
    ///
    /// # Errors
    /// [`ControlError::Guess`] for a wrong number of nodes, [`ControlError::Length`] for a node
    /// of the wrong size.
    pub fn with_guess(mut self, guess: Guess) -> Result<Self, ControlError> {
        let (n, m, steps) = (self.dof(), self.controls(), self.grid.steps);
        for (what, nodes, expected, len) in
            [("q", &guess.q, steps + 1, n), ("u", &guess.u, steps, m)]
        {
            if nodes.len() != expected {
                return Err(ControlError::Guess {
                    what,
                    got: nodes.len(),
                    expected,
                });
            }
            for node in nodes.iter() {
                check_len(what, node.len(), len)?;
            }
        }
        self.guess = Some(guess);
        Ok(self)
    }

    /// Degrees of freedom `n`.
    pub fn dof(&self) -> usize {
        self.lagrangian.dof()
    }

    /// Number of controls `m`.
    pub fn controls(&self) -> usize {
        self.force.controls()
    }

    /// The time grid (`t0`, `h = T/N`, `N`).
    pub fn grid(&self) -> &TimeGrid {
        &self.grid
    }

    /// The mechanical system.
    pub fn lagrangian(&self) -> &L {
        &self.lagrangian
    }

    /// The controlled force.
    pub fn force(&self) -> &F {
        &self.force
    }

    /// The boundary conditions at the start.
    pub fn start(&self) -> &Boundary {
        &self.start
    }

    /// The boundary conditions at the end.
    pub fn end(&self) -> &Boundary {
        &self.end
    }
}

/// `Ok` if `got == expected`.
pub(crate) fn check_len(
    what: &'static str,
    got: usize,
    expected: usize,
) -> Result<(), ControlError> {
    if got == expected {
        Ok(())
    } else {
        Err(ControlError::Length {
            what,
            got,
            expected,
        })
    }
}
