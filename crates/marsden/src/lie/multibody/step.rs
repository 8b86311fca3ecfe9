//! The constrained LGVI step of jointed bodies: SHAKE for the joints, RATTLE for the momenta.
//!
//! The step of [`crate::lie::lgvi`] with the joints' reactions added as forces with multipliers
//! ([LMO08] §3; [HLW06] §VII.1 for RATTLE on ℝⁿ; the moment of a row `g_k` is its
//! left-trivialised gradient, as the potential's, [`crate::lie::potential`]):
//!
//! ```text
//! q_i = Π_i + (h/2)(M_i − Σ_k λ_k ∂g_k/∂ξ_i),      (h q_i)^ = F_i J_d − J_d F_iᵀ,   R_i⁺ = R_i F_i,
//! p_i^½ = p_i + (h/2)(f_i − Σ_k λ_k ∂g_k/∂x_i),     x_i⁺ = x_i + (h/m_i) p_i^½,
//! g(R⁺, x⁺) = 0                                      (SHAKE: λ by Newton),
//! Π̃_i = F_iᵀ q_i + (h/2)M_i⁺,   p̃_i = p_i^½ + (h/2) f_i⁺,
//! Π_i⁺ = Π̃_i − Σ_k ν_k ∂g_k⁺/∂ξ_i,   p_i⁺ = p̃_i − Σ_k ν_k ∂g_k⁺/∂x_i,
//! Σ_i ∂g_k⁺/∂ξ_i · J_i⁻¹Π_i⁺ + ∂g_k⁺/∂x_i · p_i⁺/m_i = 0     (RATTLE: ν, linear).
//! ```
//!
//! Newton on `λ`: a change `δλ` changes `q_i` by `−(h/2)Σ δλ_k ∂g_k/∂ξ_i`, and the attitude
//! `R_i⁺` by `R_i⁺ ζ^` with `ζ = h K_i⁻¹ δq_i`, where `K_i ζ = vee(F_i ζ^ J_d + J_d ζ^ F_iᵀ)` is the
//! derivative of the Cayley equation at its solution (`K = J` at `F = I`). So the Jacobian is
//! `A = −(h²/2) G⁺ diag(K_i⁻¹, I/m_i) Gᵀ` — exact, and banded for a chain ([`JointSet`]).
//! The projection solves `G⁺ diag(J_i⁻¹, I/m_i) G⁺ᵀ ν = G⁺ · (J⁻¹Π̃, p̃/m)`. The multipliers
//! reported are `λ` (the joints' reaction forces, in force units: the reaction on body `i` is
//! `−Σ_k λ_k ∂g_k/∂x_i`, its moment `−Σ_k λ_k ∂g_k/∂ξ_i`).
//!
//! The step is symmetric, so the compositions of [`crate::lie::lgvi`] raise its order, and the
//! joints hold at every sub-step.
//!
//! [LMO08]: crate#references
//! [HLW06]: crate#references

use super::damper::{Dampers, Damping};
use super::joints::{BodyWeight, JointRows, JointSet};
use crate::error::{Error, StepError};
use crate::lie::cayley::solve_cayley;
use crate::lie::lgvi::LgviOptions;
use crate::lie::lgvi::step_error;
use crate::lie::potential::{Configuration, ExternalLoads, Loads, RigidPotential};
use crate::lie::so3::{Mat3, Vec3, cay_offset, hat, vee};
use crate::lie::state::{RigidState, RigidSystem};
use crate::numerics::banded::{BandLu, Banded};
use crate::numerics::dense::{max_norm, max_or_nan};
use crate::numerics::newton::{Convergence, NewtonFailure, NewtonReport};

/// The joints' residual at the end of a step, relative to their length scale: round-off for
/// lengths of order one (one Newton iteration past `1e-12` reaches it: the iteration on the
/// multipliers converges quadratically).
pub const JOINT_TOLERANCE: f64 = 1e-14;

/// Work counted over a run.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MultibodyStatistics {
    /// Steps taken.
    pub steps: usize,
    /// Newton iterations on the multipliers over all sub-steps.
    pub joint_iterations: usize,
    /// Newton iterations of the bodies' Cayley solves.
    pub cayley_iterations: usize,
    /// Extra projections of the end momenta for the dampers' implicit end loads.
    pub damper_iterations: usize,
}

/// The buffers of one sub-step (reused, never reallocated after the first step).
#[derive(Debug, Clone)]
struct Work {
    start_rotations: Vec<f64>,
    start_positions: Vec<f64>,
    /// `q_i` (body frame), per body.
    q: Vec<Vec3>,
    /// `p_i^½`, per body.
    half: Vec<Vec3>,
    /// `F_i − I`, per body.
    turns: Vec<Mat3>,
    /// The constraint moments and forces `Σ λ ∂g/∂(ξ, x)`.
    moments: Vec<Vec3>,
    forces: Vec<Vec3>,
    /// `(K_i⁻¹, 1/m_i)` for the Newton matrix, `(J_i⁻¹, 1/m_i)` for the projection.
    weights: Vec<BodyWeight>,
    omega: Vec<Vec3>,
    velocity: Vec<Vec3>,
    rhs: Vec<f64>,
    a: Banded,
    lu: BandLu,
}

/// The constrained LGVI stepper of bodies joined by joints.
#[derive(Debug, Clone)]
pub struct MultibodyLgvi<U, E> {
    system: RigidSystem<U, E>,
    joints: JointSet,
    h: f64,
    options: LgviOptions,
    gammas: Vec<f64>,
    free: Vec<usize>,
    /// The joints' length scale: residuals are judged relative to it.
    length: f64,
    state: RigidState,
    loads: Loads,
    /// Dampers between body points (loads that depend on the velocities), and their part of
    /// `loads`.
    dampers: Dampers,
    damping: Damping,
    /// The joint rows at the state, and at the sub-step's new configuration.
    rows: JointRows,
    next_rows: JointRows,
    lambda: Vec<f64>,
    nu: Vec<f64>,
    saved_state: RigidState,
    saved_loads: Loads,
    saved_rows: JointRows,
    saved_lambda: Vec<f64>,
    work: Work,
    step: usize,
    statistics: MultibodyStatistics,
}

impl<U: RigidPotential, E: ExternalLoads> MultibodyLgvi<U, E> {
    /// A stepper of step `h` from `initial`, which must satisfy the joints
    /// ([`super::initial::check`]; [`super::initial::project`] moves a state onto them).
    ///
    /// # Errors
    /// Those of [`super::initial::check`], and [`crate::error::InputError::InvalidStep`] for a
    /// bad `h` or an invalid Newton option.
    pub fn new(
        system: RigidSystem<U, E>,
        joints: JointSet,
        initial: RigidState,
        h: f64,
        options: LgviOptions,
    ) -> Result<Self, Error> {
        if !(h.is_finite() && h > 0.0) {
            return Err(Error::Input(crate::error::InputError::InvalidStep { h }));
        }
        options.newton.validate()?;
        let rows = super::initial::check(&system, &joints, &initial)?;
        let m = system.bodies.len();
        let n = joints.rows();
        let gammas = options
            .composition
            .map_or_else(|| vec![1.0], |scheme| scheme.coefficients());
        let free = system.free_bodies();
        let length = super::initial::length_scale(&joints, &initial);
        let work = Work {
            start_rotations: initial.rotations.clone(),
            start_positions: initial.positions.clone(),
            q: vec![Vec3::zeros(); m],
            half: vec![Vec3::zeros(); m],
            turns: vec![Mat3::zeros(); m],
            moments: vec![Vec3::zeros(); m],
            forces: vec![Vec3::zeros(); m],
            weights: vec![
                BodyWeight {
                    rotation: Mat3::zeros(),
                    translation: 0.0
                };
                m
            ],
            omega: vec![Vec3::zeros(); m],
            velocity: vec![Vec3::zeros(); m],
            rhs: vec![0.0; n],
            a: Banded::new(n, joints.bandwidth()),
            lu: BandLu::new(),
        };
        let mut stepper = Self {
            system,
            h,
            options,
            gammas,
            free,
            length,
            saved_state: initial.clone(),
            state: initial,
            loads: Loads::new(m),
            dampers: Dampers::default(),
            damping: Damping::default(),
            saved_loads: Loads::new(m),
            next_rows: rows.clone(),
            saved_rows: rows.clone(),
            rows,
            lambda: vec![0.0; n],
            nu: vec![0.0; n],
            saved_lambda: vec![0.0; n],
            joints,
            work,
            step: 0,
            statistics: MultibodyStatistics::default(),
        };
        stepper.evaluate_loads();
        Ok(stepper)
    }

    /// The stepper with `dampers` between body points ([`super::damper`]): their loads enter
    /// each (sub-)step as `(h/2) f` at both ends, at the velocities of the momenta there; the
    /// end's load is implicit in the end momenta, found by a fixed-point iteration on the
    /// momentum projection (it contracts by about `(h/2) c/m` per iteration).
    #[must_use]
    pub fn with_dampers(mut self, dampers: Dampers) -> Self {
        self.dampers = dampers;
        self.evaluate_loads();
        self
    }

    /// The dampers.
    pub fn dampers(&self) -> &Dampers {
        &self.dampers
    }

    /// The current state.
    pub fn state(&self) -> &RigidState {
        &self.state
    }

    /// The system stepped.
    pub fn system(&self) -> &RigidSystem<U, E> {
        &self.system
    }

    /// The joints.
    pub fn joints(&self) -> &JointSet {
        &self.joints
    }

    /// The step `h`.
    pub fn h(&self) -> f64 {
        self.h
    }

    /// The joint rows `g` at the current state (their values: the joints' residuals).
    pub fn joint_rows(&self) -> &JointRows {
        &self.rows
    }

    /// The multipliers `λ` of the last sub-step (the joints' reactions, module docs).
    pub fn multipliers(&self) -> &[f64] {
        &self.lambda
    }

    /// The projection's multipliers `ν` of the last sub-step (`(h/2)` times the end reactions).
    pub fn projection_multipliers(&self) -> &[f64] {
        &self.nu
    }

    /// Work counted so far.
    pub fn statistics(&self) -> MultibodyStatistics {
        self.statistics
    }

    /// One (composed) step of `h`. On failure the state is left as it was before the step.
    ///
    /// # Errors
    /// [`Error::Step`] naming the step and its start time: [`StepError::ConstraintNotSatisfied`]
    /// with the most violated row, [`StepError::SingularJacobian`] (a Cayley solve, or a
    /// singular joint matrix: the joints are redundant there), [`StepError::NonFinite`].
    pub fn step(&mut self) -> Result<(), Error> {
        self.saved_state.clone_from(&self.state);
        self.saved_loads.clone_from(&self.loads);
        self.saved_rows.clone_from(&self.rows);
        self.saved_lambda.clone_from(&self.lambda);
        for j in 0..self.gammas.len() {
            let h = self.gammas[j] * self.h;
            if let Err(cause) = self.substep(h) {
                let failure = Error::step(self.step, self.saved_state.t, cause);
                std::mem::swap(&mut self.state, &mut self.saved_state);
                std::mem::swap(&mut self.loads, &mut self.saved_loads);
                std::mem::swap(&mut self.rows, &mut self.saved_rows);
                std::mem::swap(&mut self.lambda, &mut self.saved_lambda);
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
        if !self.dampers.is_empty() {
            let bodies = &self.system.bodies;
            (self.damping).add(&self.dampers, bodies, &self.state, &mut self.loads);
        }
    }

    /// One constrained step of `h` from the state, its loads and its joint rows.
    fn substep(&mut self, h: f64) -> Result<(), StepError> {
        self.work.start_rotations.clone_from(&self.state.rotations);
        self.work.start_positions.clone_from(&self.state.positions);
        self.solve_multipliers(h)?;
        self.state.t += h;
        self.evaluate_loads();
        self.project(h)?;
        self.settle_dampers(h)?;
        std::mem::swap(&mut self.rows, &mut self.next_rows);
        Ok(())
    }

    /// The end momenta and the dampers' loads at them, by fixed-point iteration: the dampers at
    /// the projected momenta, the projection again with them, until the change of the impulse
    /// `(h/2)·δf` is round-off of the momenta (or stops decreasing below the Newton tolerance
    /// relative to them).
    fn settle_dampers(&mut self, h: f64) -> Result<(), StepError> {
        if self.dampers.is_empty() {
            return Ok(());
        }
        let tolerance = self.options.newton.residual_tolerance;
        let mut last = f64::INFINITY;
        for _ in 0..self.options.newton.max_iterations.max(1) {
            let bodies = &self.system.bodies;
            let change = (self.damping).update(&self.dampers, bodies, &self.state, &mut self.loads);
            let impulse = 0.5 * h.abs() * change;
            let momenta = max_or_nan(
                max_norm(&self.state.momenta),
                max_norm(&self.state.linear_momenta),
            );
            let settled = impulse <= 4.0 * f64::EPSILON * momenta
                || (impulse >= last && impulse <= tolerance * momenta);
            if settled {
                return Ok(());
            }
            if !impulse.is_finite() {
                return Err(StepError::NonFinite {
                    what: "the dampers' loads",
                });
            }
            last = impulse;
            self.project(h)?;
            self.statistics.damper_iterations += 1;
        }
        Err(StepError::NewtonDidNotConverge {
            iterations: self.options.newton.max_iterations,
            residual: last,
            tolerance,
        })
    }

    /// SHAKE: Newton on `λ` until the joints hold at the new configuration.
    fn solve_multipliers(&mut self, h: f64) -> Result<(), StepError> {
        let mut convergence = Convergence::new(&self.options.newton);
        let mut report = NewtonReport::default();
        loop {
            self.advance(h)?;
            self.joints.evaluate(
                &self.system.bodies,
                &self.state.rotations,
                &self.state.positions,
                &mut self.next_rows,
            );
            report.residual = max_norm(&self.next_rows.values);
            report.evaluations += 1;
            // The joints are closed to JOINT_TOLERANCE of their length, whatever the Newton
            // tolerance asks of the bodies' own solves (the update rule still stops an
            // iteration that reached round-off first).
            let scale = self.length * JOINT_TOLERANCE / self.options.newton.residual_tolerance;
            match convergence.check(&report, scale.min(self.length)) {
                Ok(true) => return Ok(()),
                Ok(false) => {}
                Err(failure) => return Err(self.constraint_failure(failure)),
            }
            self.joints.assemble(
                &self.next_rows,
                &self.rows,
                &self.work.weights,
                -0.5 * h * h,
                &mut self.work.a,
            );
            self.factor(report.iterations)?;
            for (r, g) in self.work.rhs.iter_mut().zip(&self.next_rows.values) {
                *r = -g;
            }
            self.work.lu.solve(&mut self.work.rhs);
            for (l, d) in self.lambda.iter_mut().zip(&self.work.rhs) {
                *l += d;
            }
            report.iterations += 1;
            self.statistics.joint_iterations += 1;
            let size = max_norm(&self.work.rhs);
            convergence.record_update(size, max_norm(&self.lambda).max(1.0));
        }
    }

    /// The configuration `(R⁺, x⁺)` of the current `λ`, from the sub-step's start; also the
    /// Newton weights `K_i⁻¹`, `1/m_i`.
    fn advance(&mut self, h: f64) -> Result<(), StepError> {
        let work = &mut self.work;
        work.moments.iter_mut().for_each(|m| *m = Vec3::zeros());
        work.forces.iter_mut().for_each(|f| *f = Vec3::zeros());
        self.joints.add_transpose(
            &self.rows,
            &self.lambda,
            &mut work.moments,
            &mut work.forces,
        );
        for (i, body) in self.system.bodies.iter().enumerate() {
            if body.particle {
                // A point mass does not turn: F = I, and no rotational response to `λ`.
                work.turns[i] = Mat3::zeros();
                work.q[i] = Vec3::zeros();
                work.weights[i] = BodyWeight {
                    rotation: Mat3::zeros(),
                    translation: body.mass.map_or(0.0, |m| 1.0 / m),
                };
                continue;
            }
            let moment = self.loads.moments[i] - work.moments[i];
            let q = self.state.momentum(i) + 0.5 * h * moment;
            let inertia = &body.inertia;
            let (f, report) = solve_cayley(inertia.tensor(), &(h * q), &self.options.newton)
                .map_err(|failure| step_error(failure, &self.options.newton))?;
            self.statistics.cayley_iterations += report.iterations;
            let offset = cay_offset(&f);
            let r = Mat3::from_row_slice(&work.start_rotations[9 * i..9 * i + 9]);
            self.state.set_rotation(i, &(r + r * offset));
            work.turns[i] = offset;
            work.q[i] = q;
            let k = cayley_derivative(&(Mat3::identity() + offset), inertia.nonstandard());
            let rotation = k.try_inverse().ok_or(StepError::SingularJacobian {
                iteration: 0,
                pivot: k.determinant(),
            })?;
            work.weights[i] = BodyWeight {
                rotation,
                translation: body.mass.map_or(0.0, |m| 1.0 / m),
            };
        }
        for &i in &self.free {
            let mass = self.system.bodies[i].mass.unwrap_or(1.0);
            let p =
                self.state.linear_momentum(i) + 0.5 * h * (self.loads.forces[i] - work.forces[i]);
            let x0 = Vec3::from_column_slice(&work.start_positions[3 * i..3 * i + 3]);
            self.state.set_position(i, &(x0 + (h / mass) * p));
            work.half[i] = p;
        }
        Ok(())
    }

    /// RATTLE: the momenta at the new configuration, projected onto the joints' hidden
    /// constraint.
    fn project(&mut self, h: f64) -> Result<(), StepError> {
        let work = &mut self.work;
        for (i, body) in self.system.bodies.iter().enumerate() {
            let q = work.q[i];
            let pi = match body.particle {
                true => Vec3::zeros(),
                false => q + work.turns[i].transpose() * q + 0.5 * h * self.loads.moments[i],
            };
            self.state.set_momentum(i, &pi);
            work.omega[i] = body.inertia.inverse() * pi;
            work.weights[i] = BodyWeight {
                rotation: *body.inertia.inverse(),
                translation: body.mass.map_or(0.0, |m| 1.0 / m),
            };
        }
        for &i in &self.free {
            let p = work.half[i] + 0.5 * h * self.loads.forces[i];
            self.state.set_linear_momentum(i, &p);
            work.velocity[i] = p * work.weights[i].translation;
        }
        self.joints
            .rates(&self.next_rows, &work.omega, &work.velocity, &mut work.rhs);
        self.joints.assemble(
            &self.next_rows,
            &self.next_rows,
            &work.weights,
            1.0,
            &mut work.a,
        );
        work.lu
            .factor(&work.a)
            .map_err(|singular| StepError::SingularJacobian {
                iteration: 0,
                pivot: singular.pivot,
            })?;
        work.lu.solve(&mut work.rhs);
        self.nu.clone_from(&work.rhs);
        work.moments.iter_mut().for_each(|m| *m = Vec3::zeros());
        work.forces.iter_mut().for_each(|f| *f = Vec3::zeros());
        self.joints.add_transpose(
            &self.next_rows,
            &self.nu,
            &mut work.moments,
            &mut work.forces,
        );
        for i in 0..self.system.bodies.len() {
            let pi = self.state.momentum(i) - work.moments[i];
            if !pi.iter().all(|v| v.is_finite()) {
                return Err(StepError::NonFinite {
                    what: "the body angular momentum Π",
                });
            }
            self.state.set_momentum(i, &pi);
        }
        for &i in &self.free {
            let p = self.state.linear_momentum(i) - work.forces[i];
            if !p.iter().all(|v| v.is_finite()) {
                return Err(StepError::NonFinite {
                    what: "the linear momentum p",
                });
            }
            self.state.set_linear_momentum(i, &p);
        }
        Ok(())
    }

    fn factor(&mut self, iteration: usize) -> Result<(), StepError> {
        self.work
            .lu
            .factor(&self.work.a)
            .map_err(|singular| StepError::SingularJacobian {
                iteration,
                pivot: singular.pivot,
            })
    }

    /// The step error of a Newton on `λ` that failed: the most violated row.
    fn constraint_failure(&self, failure: NewtonFailure) -> StepError {
        let report = match failure {
            NewtonFailure::NotConverged(report) | NewtonFailure::NonFinite(report) => report,
            NewtonFailure::Singular { iteration, pivot } => {
                return StepError::SingularJacobian { iteration, pivot };
            }
        };
        let values = &self.next_rows.values;
        let index = (0..values.len())
            .max_by(|&a, &b| values[a].abs().total_cmp(&values[b].abs()))
            .unwrap_or(0);
        StepError::ConstraintNotSatisfied {
            index,
            residual: values.get(index).copied().unwrap_or(f64::NAN),
            iterations: report.iterations,
        }
    }
}

/// `K` with `K ζ = vee(F ζ^ J_d + J_d ζ^ Fᵀ)`: the derivative of the Cayley equation
/// `(h q)^ = F J_d − J_d Fᵀ` along `F ↦ F exp(ζ^)` (module docs).
fn cayley_derivative(f: &Mat3, j_d: &Mat3) -> Mat3 {
    let mut k = Mat3::zeros();
    for c in 0..3 {
        let e = hat(&Vec3::ith(c, 1.0));
        k.set_column(c, &vee(&(f * e * j_d + j_d * e * f.transpose())));
    }
    k
}
