//! Typed errors carrying the numbers a user needs to act on them, in three layers:
//!
//! * [`InputError`]: the caller's data is malformed (lengths, non-finite numbers, an invalid
//!   step, option or method name) — nothing was computed;
//! * [`SetupError`]: the data is well formed but the mechanics refuses it (a singular
//!   Lagrangian, initial data off the constraint manifold, a declared structure or symmetry
//!   that does not hold, a boundary value problem without solution);
//! * [`StepFailure`]: a step of a run failed; it names the step and the time once, and its
//!   [`StepError`] says why. A failed run still hands back the trajectory computed up to the
//!   failure (see [`crate::run::RunFailure`]).
//!
//! Every fallible function of the crate returns [`Error`](enum@Error), one of the three.

use thiserror::Error;

/// Everything that can go wrong in marsden's core.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum Error {
    /// Malformed input data.
    #[error(transparent)]
    Input(#[from] InputError),
    /// Well-formed data the mechanics refuses.
    #[error(transparent)]
    Setup(#[from] SetupError),
    /// A step of a run failed.
    #[error(transparent)]
    Step(#[from] StepFailure),
}

/// Malformed input: nothing was computed.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum InputError {
    /// Input data contains NaN or infinity.
    #[error("{what}[{index}] is not finite ({value})")]
    NonFinite {
        /// Which input.
        what: &'static str,
        /// Position in the input vector.
        index: usize,
        /// The value found.
        value: f64,
    },
    /// A vector has the wrong length.
    #[error("{what} has length {found}, expected {expected}")]
    DimensionMismatch {
        /// Which input.
        what: &'static str,
        /// Expected length.
        expected: usize,
        /// Length found.
        found: usize,
    },
    /// The time step is not a positive finite number.
    #[error("the time step h must be positive and finite, got {h}")]
    InvalidStep {
        /// The rejected step.
        h: f64,
    },
    /// The time span is empty or inconsistent.
    #[error("invalid time span: {reason}")]
    InvalidTimeSpan {
        /// What is wrong.
        reason: String,
    },
    /// An option is out of its valid range.
    #[error("invalid option {name} = {value}: {reason}")]
    InvalidOption {
        /// Option name.
        name: &'static str,
        /// Offending value.
        value: f64,
        /// Valid range.
        reason: &'static str,
    },
    /// An inertia tensor of a rigid body is not symmetric, not positive definite, or its
    /// principal moments violate a triangle inequality (`J₁ ≤ J₂ + J₃` and cyclic).
    #[error(
        "the inertia of rigid body {body} is not valid: {reason} (matrix, row-major: {matrix:?}; \
         principal moments {principal:?})"
    )]
    InvalidInertia {
        /// Index of the body.
        body: usize,
        /// What is wrong, with the offending numbers.
        reason: String,
        /// The inertia matrix given, row-major (9 entries).
        matrix: Vec<f64>,
        /// Its eigenvalues (principal moments), ascending (NaN when not symmetric).
        principal: [f64; 3],
    },
    /// A joint acts on a particle other than at its position, or constrains its attitude: a
    /// particle takes spherical and distance joints at its position only.
    #[error(
        "joint {joint} ({kind}) acts on particle {body}{where_}: a particle has no attitude, so it \
         takes spherical and distance joints at its position ([0, 0, 0] in its frame)"
    )]
    ParticleJoint {
        /// Index of the joint.
        joint: usize,
        /// Its kind.
        kind: &'static str,
        /// Index of the particle.
        body: usize,
        /// What is wrong (` at [a, b, c]` for a point off its position, empty for a kind that
        /// constrains attitudes).
        where_: String,
    },
    /// A matrix given as an attitude is not a rotation: `max |RᵀR − I|` above the tolerance,
    /// or `det R < 0`.
    #[error(
        "{what} is not a rotation matrix: max |RᵀR − I| = {defect:.3e} (tolerance \
         {tolerance:.1e}), det R = {determinant}"
    )]
    NotARotation {
        /// Which input.
        what: &'static str,
        /// The orthogonality defect `max |RᵀR − I|`.
        defect: f64,
        /// Its determinant.
        determinant: f64,
        /// The largest defect accepted.
        tolerance: f64,
    },
    /// A quadrature rule was asked for with an impossible number of points.
    #[error("no {family} quadrature with {points} points: valid choices are {valid}")]
    InvalidQuadrature {
        /// `"gauss"` or `"lobatto"`.
        family: &'static str,
        /// Points asked for.
        points: usize,
        /// The valid range.
        valid: String,
    },
    /// A Galerkin rule is inconsistent: degree out of range, or too few quadrature points for
    /// the degree (the quadrature of the kinetic energy would be degenerate).
    #[error(
        "Galerkin rule P{degree} with {points} {family} points is not valid: {reason}; valid \
         choices are 1 ≤ degree ≤ {max_degree} and points ≥ degree (gauss-s = P_s with s Gauss \
         points, lobatto-s = P_(s−1) with s Lobatto points)"
    )]
    InvalidGalerkin {
        /// Polynomial degree asked for.
        degree: usize,
        /// `"gauss"` or `"lobatto"`.
        family: &'static str,
        /// Quadrature points asked for.
        points: usize,
        /// What is wrong.
        reason: String,
        /// Largest degree accepted.
        max_degree: usize,
    },
    /// A method name could not be parsed.
    #[error("unknown method `{name}`: {reason}; valid methods are {valid}")]
    UnknownMethod {
        /// The name given.
        name: String,
        /// What is wrong with it.
        reason: String,
        /// The grammar of valid names.
        valid: String,
    },
    /// A method cannot impose holonomic constraints at the order it has (a Gauss rule: the
    /// constraint only at the step end would make the run order 2).
    #[error("the method `{method}` cannot be used with holonomic constraints: {reason}")]
    UnconstrainableMethod {
        /// The method's name.
        method: String,
        /// Why, and which method to use instead.
        reason: String,
    },
    /// A group action acts on a configuration space of the wrong dimension: its generators
    /// `ξ_Q(q)` have the wrong number of components for this system.
    #[error(
        "the symmetry \"{symmetry}\" has generators with {found} components, but the system has \
         {expected} degrees of freedom"
    )]
    SymmetryDimension {
        /// Name of the group action.
        symmetry: String,
        /// Degrees of freedom of the system.
        expected: usize,
        /// Components of the generators (the action's `dof()`).
        found: usize,
    },
    /// A generator `ξ_Q(q)` returned a non-finite component (or left one unwritten).
    #[error(
        "the symmetry \"{symmetry}\": generator {generator} has component {component} = {value} \
         at q = {q:?} (not finite, or not written)"
    )]
    InvalidGenerator {
        /// Name of the group action.
        symmetry: String,
        /// Index of the Lie algebra basis element.
        generator: usize,
        /// Offending component of `ξ_Q(q)`.
        component: usize,
        /// The value found (NaN if the component was not written).
        value: f64,
        /// Where it was evaluated.
        q: Vec<f64>,
    },
    /// An input refused before a checkpoint, restored with its message (a resumed run keeps
    /// refusing what the checkpointed one refused, for the reason it gave).
    #[error("{reason}")]
    Restored {
        /// The message of the refusal.
        reason: String,
    },
}

/// Well-formed data that the mechanics refuses.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum SetupError {
    /// The Lagrangian is singular: `∂²L/∂v²` cannot be inverted at this state.
    #[error(
        "the Lagrangian is singular at t = {t}, q = {q:?}, v = {v:?}: the velocity Hessian \
         ∂²L/∂v² has pivot {pivot:.3e} (relative to its largest entry {scale:.3e}), so the \
         Legendre transform is not invertible and the equations of motion are not defined"
    )]
    SingularLagrangian {
        /// Time of the state.
        t: f64,
        /// Positions.
        q: Vec<f64>,
        /// Velocities.
        v: Vec<f64>,
        /// Smallest pivot met in the factorisation.
        pivot: f64,
        /// Largest absolute entry of the velocity Hessian.
        scale: f64,
    },
    /// A Lagrangian declared separable is not: `∂²L/∂v²` differs from the declared mass matrix
    /// or `∂²L/∂v∂q`, `∂²L/∂v∂t` are not zero.
    #[error(
        "the Lagrangian is declared separable (L = ½ vᵀMv − V(q)) but is not at q = {q:?}, v = \
         {v:?}: {what} is off by {defect:.3e}"
    )]
    StructureMismatch {
        /// Positions of the probe.
        q: Vec<f64>,
        /// Velocities of the probe.
        v: Vec<f64>,
        /// Which block of second derivatives disagrees.
        what: &'static str,
        /// Largest absolute discrepancy.
        defect: f64,
    },
    /// The inverse Legendre transform `v = FH(q, p)` did not converge.
    #[error(
        "could not invert the Legendre transform at t = {t}: residual {residual:.3e} after \
         {iterations} Newton iterations"
    )]
    InverseLegendre {
        /// Time of the state.
        t: f64,
        /// Iterations performed.
        iterations: usize,
        /// Final residual `|∂L/∂v(q, v) − p|`.
        residual: f64,
    },
    /// The initial positions violate the holonomic constraints beyond the tolerance.
    #[error(
        "the initial positions q0 violate constraint {index}: |φ_{index}(q0)| = {residual:.3e} \
         > tolerance {tolerance:.1e}; move q0 onto the constraint manifold (e.g. with \
         marsden::holonomic::project_position or Initial::project_onto)"
    )]
    InitialPositionOffConstraint {
        /// Index of the most violated constraint.
        index: usize,
        /// Its value `φ_index(q₀)`.
        residual: f64,
        /// The tolerance it was checked against (already scaled).
        tolerance: f64,
    },
    /// The initial velocities (or the velocities `FH(q₀, p₀)` of the initial momenta) are not
    /// tangent to the constraint manifold.
    #[error(
        "the initial {what} is not tangent to the constraint manifold: the velocity constraint \
         {index} has residual (Dφ(q0)·v0)_{index} = {residual:.3e} > tolerance {tolerance:.1e}; \
         project it with Initial::project_onto"
    )]
    InitialVelocityNotTangent {
        /// `"velocity v0"` or `"momentum p0"`.
        what: &'static str,
        /// Index of the most violated velocity constraint.
        index: usize,
        /// Its value `(Dφ(q₀) v₀)_index`.
        residual: f64,
        /// The tolerance it was checked against (already scaled).
        tolerance: f64,
    },
    /// The constraint Jacobian `Dφ` does not have full row rank: some constraints are redundant.
    #[error(
        "the {count} constraints are redundant at q = {q:?}: Dφ has rank {rank} < {count} \
         (singular values {singular_values:?}; rank counts those above {threshold:.1e}); remove \
         the dependent constraints"
    )]
    RedundantConstraints {
        /// Number of constraints `d`.
        count: usize,
        /// Numerical rank of `Dφ(q)`.
        rank: usize,
        /// The singular values of `Dφ(q)`, largest first.
        singular_values: Vec<f64>,
        /// The threshold below which a singular value counts as zero.
        threshold: f64,
        /// The positions at which `Dφ` was factored.
        q: Vec<f64>,
    },
    /// The multipliers cannot be computed from the state: `Dφ W⁻¹ Dφᵀ` (`W = ∂²L/∂v²`) is
    /// singular, i.e. the constraints are redundant there.
    #[error(
        "cannot compute the constraint multipliers at t = {t}, q = {q:?}: Dφ W⁻¹ Dφᵀ has pivot \
         {pivot:.3e} (the constraints are redundant or singular there)"
    )]
    SingularConstraintMass {
        /// Time of the state.
        t: f64,
        /// Positions.
        q: Vec<f64>,
        /// Smallest pivot of the factorisation.
        pivot: f64,
    },
    /// Projecting positions onto the constraint manifold `φ(q) = 0` failed.
    #[error(
        "could not project q onto the constraint manifold: |φ_{index}(q)| = {residual:.3e} after \
         {iterations} Newton iterations; the constraint may be unsatisfiable (φ(q) = 0 has no \
         solution near q) or singular there"
    )]
    PositionProjectionFailed {
        /// Iterations performed.
        iterations: usize,
        /// Index of the most violated constraint at the last iterate.
        index: usize,
        /// Its value at the last iterate.
        residual: f64,
    },
    /// A declared group action is not a symmetry: `⟨dL, ξ_TQ⟩ ≠ 0` (or `L_d`, `H` not invariant).
    #[error(
        "\"{symmetry}\" is not a symmetry of {of}: generator {generator} gives a defect \
         ⟨dL, ξ⟩ = {defect:.3e} (relative {relative:.3e}, tolerance {tolerance:.1e})"
    )]
    NotASymmetry {
        /// Name of the group action.
        symmetry: String,
        /// What was checked (`"L"`, `"L_d"`, `"H"`).
        of: &'static str,
        /// Index of the worst Lie algebra basis element.
        generator: usize,
        /// Largest `|⟨dL, ξ⟩|` over the samples.
        defect: f64,
        /// The defect relative to the size of the terms that should cancel.
        relative: f64,
        /// Relative tolerance used.
        tolerance: f64,
    },
    /// The shooting method for the exact discrete Lagrangian did not converge.
    #[error(
        "shooting for the Euler–Lagrange boundary value problem over h = {h} did not converge: \
         |q(h) − q₁| = {residual:.3e} after {iterations} Newton iterations (is h beyond the \
         first conjugate point, or q₁ unreachable?)"
    )]
    ShootingDidNotConverge {
        /// Step length of the boundary value problem.
        h: f64,
        /// Newton iterations performed.
        iterations: usize,
        /// Final mismatch of the end position (max-norm).
        residual: f64,
    },
    /// A step of the exact discrete Lagrangian `L_d^E` failed: its boundary value problem could
    /// not be solved (the integrator sees a non-finite `L_d^E`; this is why).
    #[error(
        "the exact discrete Lagrangian could not be evaluated in step {step} (t = {t}): \
         {reason}; take a smaller h (the shooting solves the boundary value problem of each \
         step from the chord, and fails beyond the first conjugate time)"
    )]
    ExactStepFailed {
        /// The step that failed.
        step: usize,
        /// Its start time.
        t: f64,
        /// The shooting's error.
        reason: String,
    },
    /// The extrapolation integrator of the Euler–Lagrange equations could not reach its
    /// tolerance even on very small substeps.
    #[error(
        "the Euler–Lagrange flow did not reach tolerance {tolerance:.1e} at t = {t} (substep \
         {substep:.3e}): error estimate {estimate:.3e}"
    )]
    FlowDidNotConverge {
        /// Time where the substep started.
        t: f64,
        /// Smallest substep tried.
        substep: f64,
        /// Error estimate of the last try.
        estimate: f64,
        /// Tolerance asked for.
        tolerance: f64,
    },
}

/// A failed step: which one, when, and why.
#[derive(Debug, Clone, PartialEq)]
pub struct StepFailure {
    /// Index of the step being taken (from `t` to `t + h`; for the momentum projection, the
    /// number of the step after which it ran, 0 for initial data).
    pub step: usize,
    /// Time at the start of the step (for the momentum projection: of the state projected).
    pub t: f64,
    /// What went wrong.
    pub cause: StepError,
}

/// Why a step failed.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum StepError {
    /// The Newton iteration of a step did not reach its tolerance.
    NewtonDidNotConverge {
        /// Iterations performed.
        iterations: usize,
        /// Residual (max-norm) at the last iterate.
        residual: f64,
        /// The residual tolerance that was asked for.
        tolerance: f64,
    },
    /// The Newton Jacobian of a step is singular (the discrete Lagrangian is degenerate there).
    SingularJacobian {
        /// Newton iteration at which the factorisation failed.
        iteration: usize,
        /// The offending pivot.
        pivot: f64,
    },
    /// A non-finite number (NaN or infinity) appeared during a step.
    NonFinite {
        /// Which quantity went non-finite.
        what: &'static str,
    },
    /// A constrained step could not satisfy `φ(q_{k+1}) = 0`.
    ConstraintNotSatisfied {
        /// Index of the most violated constraint at the last iterate.
        index: usize,
        /// Its value at the last iterate.
        residual: f64,
        /// Newton iterations performed.
        iterations: usize,
    },
    /// The RATTLE projection of the momenta onto the cotangent space of the constraint manifold
    /// failed.
    MomentumProjectionFailed {
        /// Newton iterations performed.
        iterations: usize,
        /// Residual (max-norm) at the last iterate.
        residual: f64,
    },
    /// An event function ([`crate::run::events`]) returned a non-finite value, at a state of
    /// the run or at a point of the step's interpolant.
    EventNotFinite {
        /// Index of the event in the detector's list.
        event: usize,
        /// Where it was evaluated.
        at: f64,
        /// The value it returned.
        value: f64,
    },
    /// The root of an event function inside a step was not located to the tolerance within
    /// the evaluation budget ([`crate::numerics::brent`]).
    EventNotLocated {
        /// Index of the event in the detector's list.
        event: usize,
        /// Lower end of the last bracket.
        low: f64,
        /// Upper end of the last bracket.
        high: f64,
    },
}

impl std::fmt::Display for StepFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (step, t) = (self.step, self.t);
        match self.cause {
            StepError::NewtonDidNotConverge {
                iterations,
                residual,
                tolerance,
            } => write!(
                f,
                "Newton's method did not converge in step {step} (t = {t}): residual \
                 {residual:.3e} after {iterations} iterations (tolerance {tolerance:.1e}); try a \
                 smaller step h or a larger max_iterations"
            ),
            StepError::SingularJacobian { iteration, pivot } => write!(
                f,
                "singular Newton Jacobian in step {step} (t = {t}) at iteration {iteration}: \
                 pivot {pivot:.3e}; the discrete Lagrangian is not regular here (is h too large, \
                 or are constraints redundant?)"
            ),
            StepError::NonFinite { what } => {
                write!(f, "non-finite value in {what} during step {step} (t = {t})")
            }
            StepError::ConstraintNotSatisfied {
                index,
                residual,
                iterations,
            } => write!(
                f,
                "constraint {index} could not be satisfied in step {step} (t = {t}): \
                 |φ_{index}(q)| = {residual:.3e} after {iterations} Newton iterations; the \
                 constraint may have no solution near q_k (is it satisfiable?), or the step h \
                 is too large"
            ),
            StepError::MomentumProjectionFailed {
                iterations,
                residual,
            } => write!(
                f,
                "the momentum projection (RATTLE) failed after step {step} (t = {t}): residual \
                 {residual:.3e} after {iterations} Newton iterations (the KKT matrix \
                 [[∂²L/∂v², Dφᵀ], [Dφ, 0]] may be singular: redundant constraints or a singular \
                 Lagrangian)"
            ),
            StepError::EventNotFinite { event, at, value } => write!(
                f,
                "event {event} is not finite in step {step} (t = {t}): g = {value} at \
                 t = {at}"
            ),
            StepError::EventNotLocated { event, low, high } => write!(
                f,
                "the crossing of event {event} in step {step} (t = {t}) was not located: it \
                 lies in [{low}, {high}]"
            ),
        }
    }
}

impl std::error::Error for StepFailure {}

impl Error {
    /// A failure of step `step` starting at `t`.
    pub fn step(step: usize, t: f64, cause: StepError) -> Self {
        Error::Step(StepFailure { step, t, cause })
    }

    /// The failed step, if this is a step failure.
    pub fn step_failure(&self) -> Option<&StepFailure> {
        match self {
            Error::Step(failure) => Some(failure),
            _ => None,
        }
    }
}

impl Error {
    /// Checks that every entry of `x` is finite.
    pub fn check_finite(what: &'static str, x: &[f64]) -> Result<(), Error> {
        match x.iter().position(|v| !v.is_finite()) {
            Some(index) => Err(Error::Input(InputError::NonFinite {
                what,
                index,
                value: x[index],
            })),
            None => Ok(()),
        }
    }

    /// Checks that `x` has length `expected`.
    #[inline]
    pub fn check_len(what: &'static str, x: &[f64], expected: usize) -> Result<(), Error> {
        if x.len() == expected {
            Ok(())
        } else {
            Err(Error::Input(InputError::DimensionMismatch {
                what,
                expected,
                found: x.len(),
            }))
        }
    }
}
