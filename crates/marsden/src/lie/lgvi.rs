//! The Lie group variational integrator (LGVI) of rigid bodies, and its compositions.
//!
//! One step of `m` bodies from the trapezoidal discrete Lagrangian ([LLM05], [LLM07] §3)
//!
//! ```text
//! L_d = Σᵢ [(1/h) tr((I − F_i) J_{d,i}) + (m_i/2h)|x_i⁺ − x_i|²] − (h/2)[U(R, x) + U(R⁺, x⁺)],
//! F_i = R_iᵀR_i⁺,
//! ```
//!
//! with external loads by the discrete Lagrange–d'Alembert principle (`(h/2)τ` at each end):
//!
//! ```text
//! q_i = Π_i + (h/2)(M_i + τ_i),    (h q_i)^ = F_i J_d − J_d F_iᵀ   (solved for F_i, body by body),
//! R_i⁺ = R_i F_i,                  p_i^½ = p_i + (h/2)(f_i − ∂U/∂x_i),   x_i⁺ = x_i + (h/m_i) p_i^½,
//! Π_i⁺ = F_iᵀ q_i + (h/2)(M_i⁺ + τ_i⁺),   p_i⁺ = p_i^½ + (h/2)(f_i⁺ − ∂U/∂x_i⁺).
//! ```
//!
//! The trapezoidal potential decouples the implicit part: each `F_i` is solved on its own (three
//! Cayley parameters, [`super::cayley`]), the translation is Störmer–Verlet, and the loads at the
//! new configuration need every `R⁺, x⁺`; they are kept for the next step (one evaluation of the
//! loads per step). The step is symmetric, so the compositions of
//! [`crate::discrete::rules::composition`] raise its order: a composed step is the sequence of
//! sub-steps of `γ_j h` ([HLW06] §V.3).
//!
//! [LLM05]: crate#references
//! [LLM07]: crate#references
//! [HLW06]: crate#references

use super::cayley::solve_cayley;
use super::potential::{Configuration, ExternalLoads, Loads, RigidPotential};
use super::so3::{Mat3, Vec3, cay_offset};
use super::state::{RigidState, RigidSystem};
use crate::discrete::rules::composition::CompositionScheme;
use crate::error::{Error, InputError, StepError};
use crate::numerics::newton::{NewtonFailure, NewtonOptions};

/// Options of an LGVI run.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LgviOptions {
    /// The Newton solve of each body's Cayley parameters.
    pub newton: NewtonOptions,
    /// A composition of LGVI sub-steps for a higher order (`None`: the plain, second-order step).
    pub composition: Option<CompositionScheme>,
}

/// Work counted over a run.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LgviStatistics {
    /// Steps taken.
    pub steps: usize,
    /// Newton iterations over all bodies and sub-steps.
    pub newton_iterations: usize,
    /// Evaluations of the loads (one per sub-step, plus the initial one).
    pub load_evaluations: usize,
}

/// The LGVI stepper: owns the system, the state and the loads at the state.
#[derive(Debug, Clone)]
pub struct Lgvi<U, E> {
    system: RigidSystem<U, E>,
    h: f64,
    options: LgviOptions,
    gammas: Vec<f64>,
    free: Vec<usize>,
    state: RigidState,
    loads: Loads,
    saved_state: RigidState,
    saved_loads: Loads,
    half: Vec<Vec3>,
    /// `F_i − I` of the sub-step.
    turns: Vec<Mat3>,
    step: usize,
    statistics: LgviStatistics,
}

impl<U: RigidPotential, E: ExternalLoads> Lgvi<U, E> {
    /// A stepper of step `h` from `initial`.
    ///
    /// # Errors
    /// [`InputError::InvalidStep`] for a bad `h`, an invalid Newton option,
    /// [`InputError::DimensionMismatch`] when the state does not have one entry per body.
    pub fn new(
        system: RigidSystem<U, E>,
        initial: RigidState,
        h: f64,
        options: LgviOptions,
    ) -> Result<Self, Error> {
        if !(h.is_finite() && h > 0.0) {
            return Err(Error::Input(InputError::InvalidStep { h }));
        }
        options.newton.validate()?;
        let m = system.bodies.len();
        Error::check_len("rotations", &initial.rotations, 9 * m)?;
        Error::check_len("momenta", &initial.momenta, 3 * m)?;
        Error::check_len("positions", &initial.positions, 3 * m)?;
        Error::check_len("linear momenta", &initial.linear_momenta, 3 * m)?;
        let gammas = options
            .composition
            .map_or_else(|| vec![1.0], CompositionScheme::coefficients);
        let free = system.free_bodies();
        let mut stepper = Self {
            system,
            h,
            options,
            gammas,
            free,
            saved_state: initial.clone(),
            state: initial,
            loads: Loads::new(m),
            saved_loads: Loads::new(m),
            half: vec![Vec3::zeros(); 2 * m],
            turns: vec![Mat3::zeros(); m],
            step: 0,
            statistics: LgviStatistics::default(),
        };
        stepper.evaluate_loads();
        Ok(stepper)
    }

    /// The current state.
    pub fn state(&self) -> &RigidState {
        &self.state
    }

    /// The system stepped.
    pub fn system(&self) -> &RigidSystem<U, E> {
        &self.system
    }

    /// The step `h`.
    pub fn h(&self) -> f64 {
        self.h
    }

    /// The loads `M + τ`, `f − ∂U/∂x` at the current state.
    pub fn loads(&self) -> &Loads {
        &self.loads
    }

    /// Work counted so far.
    pub fn statistics(&self) -> LgviStatistics {
        self.statistics
    }

    /// One (composed) step of `h`. On failure the state is left as it was before the step.
    ///
    /// # Errors
    /// [`Error::Step`] naming the step and its start time: [`StepError::NewtonDidNotConverge`]
    /// with the residual, [`StepError::SingularJacobian`], or [`StepError::NonFinite`].
    pub fn step(&mut self) -> Result<(), Error> {
        self.saved_state.clone_from(&self.state);
        self.saved_loads.clone_from(&self.loads);
        for j in 0..self.gammas.len() {
            let h = self.gammas[j] * self.h;
            if let Err(cause) = self.substep(h) {
                let failure = Error::step(self.step, self.saved_state.t, cause);
                std::mem::swap(&mut self.state, &mut self.saved_state);
                std::mem::swap(&mut self.loads, &mut self.saved_loads);
                return Err(failure);
            }
        }
        self.step += 1;
        self.statistics.steps += 1;
        Ok(())
    }

    fn evaluate_loads(&mut self) {
        let config = Configuration {
            t: self.state.t,
            rotations: &self.state.rotations,
            positions: &self.state.positions,
            free: &self.free,
        };
        self.loads
            .evaluate(&self.system.potential, &self.system.loads, config);
        self.statistics.load_evaluations += 1;
    }

    /// One LGVI step of `h` (a sub-step of a composition), from the loads at the state.
    fn substep(&mut self, h: f64) -> Result<(), StepError> {
        let m = self.system.bodies.len();
        for i in 0..m {
            let q = self.state.momentum(i) + 0.5 * h * self.loads.moments[i];
            let inertia = &self.system.bodies[i].inertia;
            let (f, report) = solve_cayley(inertia.tensor(), &(h * q), &self.options.newton)
                .map_err(|failure| step_error(failure, &self.options.newton))?;
            self.statistics.newton_iterations += report.iterations;
            // F − I, not F: the offsets round once on each sum (see `cay_offset`).
            let offset = cay_offset(&f);
            let r = self.state.rotation(i);
            self.state.set_rotation(i, &(r + r * offset));
            self.turns[i] = offset;
            self.half[i] = q;
        }
        for &i in &self.free {
            let mass = self.system.bodies[i].mass.unwrap_or(1.0);
            let p = self.state.linear_momentum(i) + 0.5 * h * self.loads.forces[i];
            let x = self.state.position(i) + (h / mass) * p;
            self.state.set_position(i, &x);
            self.half[m + i] = p;
        }
        self.state.t += h;
        self.evaluate_loads();
        for i in 0..m {
            let q = self.half[i];
            let pi = q + self.turns[i].transpose() * q + 0.5 * h * self.loads.moments[i];
            if !pi.iter().all(|v| v.is_finite()) {
                return Err(StepError::NonFinite {
                    what: "the body angular momentum Π",
                });
            }
            self.state.set_momentum(i, &pi);
        }
        for &i in &self.free {
            let p = self.half[m + i] + 0.5 * h * self.loads.forces[i];
            if !p.iter().all(|v| v.is_finite()) {
                return Err(StepError::NonFinite {
                    what: "the linear momentum p",
                });
            }
            self.state.set_linear_momentum(i, &p);
        }
        Ok(())
    }
}

/// The step error of a failed Cayley solve.
pub(crate) fn step_error(failure: NewtonFailure, options: &NewtonOptions) -> StepError {
    match failure {
        NewtonFailure::NotConverged(report) => StepError::NewtonDidNotConverge {
            iterations: report.iterations,
            residual: report.residual,
            tolerance: options.residual_tolerance,
        },
        NewtonFailure::Singular { iteration, pivot } => {
            StepError::SingularJacobian { iteration, pivot }
        }
        NewtonFailure::NonFinite(_) => StepError::NonFinite {
            what: "the Cayley parameters of F_k (LGVI step)",
        },
    }
}
