//! The initial state completed by the core (`p` from `v` by the Legendre transform, or `v`
//! from `p` by its inverse) and checked for regularity — before any file is written.

use marsden::error::SetupError;
use marsden::{Constraint, Initial, Lagrangian, Problem, mechanics};

use crate::catalog::WithLagrangian;
use crate::error::Diagnostic;
use crate::problem::{InitialData, RunSpec};
use crate::source::SourceFile;

/// The complete initial state.
#[derive(Debug, Clone, PartialEq)]
pub struct Start {
    /// Initial time.
    pub t: f64,
    /// Positions.
    pub q: Vec<f64>,
    /// Velocities.
    pub v: Vec<f64>,
    /// Momenta.
    pub p: Vec<f64>,
    /// Energy `⟨p, v⟩ − L`.
    pub energy: f64,
    /// Remarks that do not stop the run (printed on stderr).
    pub warnings: Vec<String>,
}

/// Builds the problem once to complete and check the initial state.
///
/// # Errors
/// The core's objection (a singular Lagrangian, a Legendre transform that cannot be
/// inverted), pointing at the Lagrangian or the initial data.
pub fn prepare(spec: &RunSpec) -> Result<Start, Diagnostic> {
    spec.system.lagrangian.dispatch(Prepare(spec))
}

struct Prepare<'a>(&'a RunSpec);

impl WithLagrangian for Prepare<'_> {
    type Output = Result<Start, Diagnostic>;

    fn call<L: Lagrangian>(self, lagrangian: &L) -> Self::Output {
        let spec = self.0;
        let problem = constrained_problem(spec, lagrangian, &spec.system.constraint)?;
        let start = problem.start();
        let v = problem.initial_velocity().to_vec();
        let energy = mechanics::energy(lagrangian, start.t, &start.q, &v);
        if !energy.is_finite() {
            return Err(non_finite_energy(spec, energy));
        }
        let mut warnings = non_symmetries(lagrangian, spec, (start.t, &start.q, &v));
        warnings.extend(constraint_non_symmetries(spec, (start.t, &start.q, &v)));
        warnings.extend(super::step_system::large_step_system(spec, lagrangian));
        Ok(Start {
            t: start.t,
            q: start.q.clone(),
            v,
            p: start.p.clone(),
            energy,
            warnings,
        })
    }

    /// A file's own `L_d`: the state is `(q, p)` as given (the file was refused with `v`);
    /// there is no velocity and no energy (both NaN).
    fn discrete(self, ld: &crate::model::ExprDiscreteLagrangian) -> Self::Output {
        let spec = self.0;
        let InitialData::Momentum(p) = &spec.initial.data else {
            return Err(Diagnostic::new(
                "a `discrete_lagrangian` run starts from momenta: there is no continuous L to \
                 turn a velocity into a momentum",
            )
            .at(spec.source.locate_opt(spec.spans.initial_data.clone()))
            .help("give `p = [...]` in [initial]"));
        };
        let n = marsden::DiscreteLagrangian::dof(ld);
        let (t, q) = (spec.initial.t0, &spec.initial.q);
        Ok(Start {
            t,
            q: q.clone(),
            v: vec![f64::NAN; n],
            p: p.clone(),
            energy: f64::NAN,
            warnings: discrete_non_symmetries(ld, spec, (t, q, p)),
        })
    }
}

/// The initial data of `spec` in the core's form, projected onto the constraint manifold
/// (`φ(q) = 0`, then `Dφ(q) v = 0` by RATTLE's projection) when `[initial] project = true`.
///
/// # Errors
/// The core's objection to the projection (no point of the manifold nearby, redundant
/// constraints), pointed at the initial data.
pub fn initial_data<L: Lagrangian, C: Constraint>(
    spec: &RunSpec,
    lagrangian: &L,
    constraint: &C,
) -> Result<Initial, Diagnostic> {
    let initial = spec.initial.to_initial();
    if !spec.initial.project || constraint.count() == 0 {
        return Ok(initial);
    }
    initial
        .project_onto(lagrangian, constraint, spec.initial.t0)
        .map_err(|e| start_error(spec, &e))
}

/// The problem of `spec` with its constraints, the initial data checked against them (or
/// projected first, see [`initial_data`]).
///
/// # Errors
/// A singular Lagrangian, a Legendre transform that cannot be inverted, initial data off the
/// constraint manifold: each pointed at the file.
pub fn constrained_problem<L: Lagrangian, C: Constraint>(
    spec: &RunSpec,
    lagrangian: L,
    constraint: C,
) -> Result<Problem<L, marsden::NoForce, C>, Diagnostic> {
    if spec.integrator.compensated && constraint.count() > 0 {
        return Err(Diagnostic::new(
            "`compensated = true` applies to unconstrained problems only: the momenta of a \
             constrained step come from RATTLE's projection, not from a sum of increments",
        )
        .help("remove `compensated` from [integrator], or the constraints"));
    }
    let initial = initial_data(spec, &lagrangian, &constraint)?;
    Problem::new(lagrangian, initial, spec.integrator.grid)
        .and_then(|p| p.with_constraint(constraint))
        .map_err(|e| start_error(spec, &e))
}

/// A Lagrangian (or its momenta) that is not finite at the initial state: every energy after
/// it would be too, and the run could report nothing true about it.
fn non_finite_energy(spec: &RunSpec, energy: f64) -> Diagnostic {
    Diagnostic::new(format!(
        "the energy ⟨p, q̇⟩ − L at the initial state is {energy}: the Lagrangian or its \
         derivatives are not finite there"
    ))
    .at(spec.source.locate_opt(spec.spans.initial_data.clone()))
    .help("start where L is defined (no log of a negative number, no two bodies at one point)")
}

/// The core's error about the initial state, pointed at the file.
pub fn start_error(spec: &RunSpec, e: &marsden::Error) -> Diagnostic {
    let source: &SourceFile = &spec.source;
    match e {
        marsden::Error::Setup(SetupError::SingularLagrangian { .. })
            if matches!(spec.system.lagrangian, crate::problem::LagrangianSpec::Hamiltonian(_)) =>
        {
            Diagnostic::new(format!("the Hamiltonian is not regular at the initial state ({e})"))
                .at(source.locate_opt(spec.spans.lagrangian.clone()))
                .help("∂²H/∂p² must be invertible for the run to go through L = ⟨p, v⟩ − H, e.g. H = p²/2m + V(q)")
        }
        marsden::Error::Setup(SetupError::SingularLagrangian { .. }) => Diagnostic::new(e.to_string())
            .at(source.locate_opt(spec.spans.lagrangian.clone()))
            .help("∂²L/∂q̇² must be invertible: every velocity must appear in L, quadratically for a mechanical system"),
        marsden::Error::Setup(SetupError::InverseLegendre { .. }) => Diagnostic::new(e.to_string())
            .at(source.locate_opt(spec.spans.initial_data.clone()))
            .help("give the initial velocities `v` instead of the momenta `p`"),
        marsden::Error::Setup(SetupError::InitialPositionOffConstraint { .. })
        | marsden::Error::Setup(SetupError::InitialVelocityNotTangent { .. }) => Diagnostic::new(off_manifold(e))
            .at(source.locate_opt(spec.spans.initial_data.clone()))
            .help(
                "set `project = true` in [initial] to project the data onto the constraint \
                 manifold (φ(q) = 0, then Dφ(q)·v = 0 by RATTLE's projection)",
            ),
        _ => Diagnostic::new(format!("cannot set up the problem: {e}")),
    }
}

/// The core's message about a start off the constraint manifold, in the file's terms (the
/// core's names a library function the file cannot call; the help says `project = true`).
fn off_manifold(e: &marsden::Error) -> String {
    match e {
        marsden::Error::Setup(SetupError::InitialPositionOffConstraint {
            index,
            residual,
            tolerance,
            ..
        }) => format!(
            "the initial positions q0 violate constraint {index}: |φ_{index}(q0)| = \
             {residual:.3e} > tolerance {tolerance:.1e}"
        ),
        marsden::Error::Setup(SetupError::InitialVelocityNotTangent {
            what,
            index,
            residual,
            tolerance,
            ..
        }) => format!(
            "the initial {what} is not tangent to the constraint manifold: the velocity \
             constraint {index} has residual (Dφ(q0)·v0)_{index} = {residual:.3e} > tolerance \
             {tolerance:.1e}"
        ),
        other => other.to_string(),
    }
}

/// A warning for each declared symmetry that does not keep the constraints invariant at the
/// initial state (`Dφ(q)·ξ_Q(q) ≠ 0`, by the core's check): the constraint forces then push
/// along the generator and its momentum map is not conserved.
fn constraint_non_symmetries(spec: &RunSpec, (t, q, v): (f64, &[f64], &[f64])) -> Vec<String> {
    use marsden::symmetry::check::{DEFAULT_TOLERANCE, Sample, check_constraint};
    let constraint = &spec.system.constraint;
    if constraint.count() == 0 {
        return Vec::new();
    }
    let samples = [Sample::new(t, q, v)];
    spec.system
        .symmetries
        .iter()
        .filter_map(|s| check_constraint(constraint, s, &samples, DEFAULT_TOLERANCE).ok())
        .filter(|report| !report.is_symmetry())
        .map(|report| {
            let defect = report.worst().map_or(f64::NAN, |w| w.max_defect);
            format!(
                "\"{}\" does not keep the constraints invariant: Dφ(q)·ξ_Q(q) = {defect:.3e} at \
                 the initial state, so the constraint forces act along it and J_{} is monitored \
                 but not conserved",
                report.symmetry, report.symmetry
            )
        })
        .collect()
}

/// A warning for each declared symmetry that is not one of a file's own `L_d` at the first
/// step's sample `(q₀, q₀ + h p₀)` (any pair of points tests the invariance; `p₀` stands in for
/// the velocity, which an `L_d` alone does not define): `⟨dL_d, ξ_{Q×Q}⟩ ≠ 0` by the core's
/// check, so the discrete momentum map is monitored but not conserved.
fn discrete_non_symmetries<D: marsden::DiscreteLagrangian>(
    ld: &D,
    spec: &RunSpec,
    (t, q, p): (f64, &[f64], &[f64]),
) -> Vec<String> {
    use marsden::symmetry::check::{DEFAULT_TOLERANCE, Sample, check_discrete};
    let samples = [Sample::new(t, q, p)];
    let h = spec.integrator.grid.h;
    spec.system
        .symmetries
        .iter()
        .filter_map(|s| check_discrete(ld, s, h, &samples, DEFAULT_TOLERANCE).ok())
        .filter(|report| !report.is_symmetry())
        .map(|report| {
            let defect = report.worst().map_or(f64::NAN, |w| w.max_defect);
            format!(
                "\"{}\" is not a symmetry of the discrete Lagrangian: ⟨dL_d, ξ_Q×Q⟩ = \
                 {defect:.3e} at the first step (q0, q0 + h p0), so J_{} is monitored but not \
                 conserved",
                report.symmetry, report.symmetry
            )
        })
        .collect()
}

/// A warning for each declared symmetry that is not one of the Lagrangian at the initial state
/// (`⟨dL, ξ_TQ⟩ ≠ 0`, by the core's check): its momentum map is then monitored but not
/// conserved.
fn non_symmetries<L: Lagrangian>(
    lagrangian: &L,
    spec: &RunSpec,
    (t, q, v): (f64, &[f64], &[f64]),
) -> Vec<String> {
    use marsden::symmetry::check::{DEFAULT_TOLERANCE, Sample, check_lagrangian};
    let samples = [Sample::new(t, q, v)];
    spec.system
        .symmetries
        .iter()
        .filter_map(|s| check_lagrangian(lagrangian, s, &samples, DEFAULT_TOLERANCE).ok())
        .filter(|report| !report.is_symmetry())
        .map(|report| {
            let defect = report.worst().map_or(f64::NAN, |w| w.max_defect);
            format!(
                "\"{}\" is not a symmetry of the Lagrangian: ⟨dL, ξ_TQ⟩ = {defect:.3e} at the \
                 initial state, so J_{} is monitored but not conserved",
                report.symmetry, report.symmetry
            )
        })
        .collect()
}
