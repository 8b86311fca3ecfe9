//! The initial state completed by the core (`p` from `v` by the Legendre transform, or `v`
//! from `p` by its inverse) and checked for regularity — before any file is written.

use marsden::error::SetupError;
use marsden::symmetry::check::Sample;
use marsden::{Constraint, Initial, Lagrangian, Problem, mechanics};

use marsden_problem::error::Diagnostic;
use marsden_problem::problem::{InitialData, RunSpec};
use marsden_problem::source::SourceFile;

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
    /// What the check of each declared symmetry found (in the file's order).
    pub symmetries: Vec<SymmetryCheck>,
}

/// Builds the problem of `spec` with `lagrangian` to complete and check the initial state
/// ([`crate::engine::Engine::prepare`]).
///
/// # Errors
/// The core's objection (a singular Lagrangian, a Legendre transform that cannot be
/// inverted), pointing at the Lagrangian or the initial data.
pub fn prepare_with<L: Lagrangian>(spec: &RunSpec, lagrangian: &L) -> Result<Start, Diagnostic> {
    let memory = crate::step_system::available_memory();
    crate::step_system::fits_in_memory(spec, lagrangian, memory)?;
    let problem = constrained_problem(spec, lagrangian, &spec.system.constraint)?;
    let start = problem.start();
    let v = problem.initial_velocity().to_vec();
    let energy = mechanics::energy(lagrangian, start.t, &start.q, &v);
    if !energy.is_finite() {
        return Err(non_finite_energy(spec, energy));
    }
    let initial = Sample::new(start.t, &start.q, &v);
    let (symmetries, mut warnings) = non_symmetries(lagrangian, spec, &initial);
    warnings.extend(constraint_non_symmetries(spec, &initial));
    warnings.extend(crate::step_system::large_step_system(spec, lagrangian));
    Ok(Start {
        t: start.t,
        q: start.q.clone(),
        v,
        p: start.p.clone(),
        energy,
        warnings,
        symmetries,
    })
}

/// A file's own `L_d`: the state is `(q, p)` as given (the file was refused with `v`); there is
/// no velocity and no energy (both NaN).
///
/// # Errors
/// Initial data given as velocities; a singular `D₁₂L_d` at the first step.
pub fn prepare_discrete(
    spec: &RunSpec,
    ld: &marsden_problem::model::ExprDiscreteLagrangian,
) -> Result<Start, Diagnostic> {
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
    let initial = Sample::new(t, q, p);
    regular_discrete(ld, spec, &initial)?;
    let (symmetries, warnings) = discrete_non_symmetries(ld, spec, &initial);
    Ok(Start {
        t,
        q: q.clone(),
        v: vec![f64::NAN; n],
        p: p.clone(),
        energy: f64::NAN,
        warnings,
        symmetries,
    })
}

/// `L_d` as a function of `(q₀, q₁)` for the AD drivers.
struct DiscreteAt<'a, D> {
    ld: &'a D,
    t: f64,
    h: f64,
}

impl<D: marsden::DiscreteLagrangian> marsden::numerics::ad::MultiFunction for DiscreteAt<'_, D> {
    fn inputs(&self) -> usize {
        2 * self.ld.dof()
    }
    fn outputs(&self) -> usize {
        1
    }
    fn eval<S: marsden::Scalar>(&self, x: &[S], out: &mut [S]) {
        let n = self.ld.dof();
        out[0] = self
            .ld
            .discrete_lagrangian(self.t, self.h, &x[..n], &x[n..]);
    }
}

/// Refuses a file's own `L_d` whose mixed derivative `D₁₂L_d` is singular at the first step
/// `(q₀, q₀ + h p₀)`: the step `p₀ = −D₁L_d(q₀, q₁)` then does not determine `q₁` (MW01 §1.3:
/// a regular discrete Lagrangian has an invertible `D₁₂L_d`), as a singular `∂²L/∂q̇²` is
/// refused for a continuous `L`. `L_d = 0` would otherwise "complete" with a constant trajectory.
fn regular_discrete<D: marsden::DiscreteLagrangian>(
    ld: &D,
    spec: &RunSpec,
    initial: &Sample,
) -> Result<(), Diagnostic> {
    use marsden::numerics::ad::{HessianParts, partial_hessian};
    use marsden::numerics::dense::{Lu, max_norm};
    // The sample's second vector is the momentum `p₀` here (as in `discrete_non_symmetries`).
    let Sample { t, q, v: p } = initial;
    let (t, n) = (*t, q.len());
    let h = spec.integrator.grid.h;
    let x: Vec<f64> = q
        .iter()
        .chain(q)
        .zip(0..)
        .map(|(x, i)| match i < n {
            true => *x,
            false => x + h * p[i - n],
        })
        .collect();
    let mut parts = HessianParts::default();
    partial_hessian(&DiscreteAt { ld, t, h }, &x, 0..n, n..2 * n, &mut parts);
    let scale = max_norm(&parts.hess);
    match Lu::new().factor(&parts.hess, n) {
        Ok(()) if scale.is_finite() => Ok(()),
        _ => Err(Diagnostic::new(format!(
            "the discrete Lagrangian is not regular at the first step: its mixed derivative \
             D₁₂L_d(q₀, q₀ + h p₀) is singular (largest entry {scale:.3e}), so \
             p₀ = −D₁L_d(q₀, q₁) does not determine q₁"
        ))
        .at(spec.source.locate_opt(spec.spans.lagrangian.clone()))
        .help("L_d must depend on q₀ and q₁ together, e.g. h*(0.5*((x_1 - x_0)/h)^2 - V((x_0 + x_1)/2))")),
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
            if matches!(spec.system.lagrangian, marsden_problem::problem::LagrangianSpec::Hamiltonian(_)) =>
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
fn constraint_non_symmetries(spec: &RunSpec, initial: &Sample) -> Vec<String> {
    use marsden::symmetry::check::{DEFAULT_TOLERANCE, check_constraint};
    let constraint = &spec.system.constraint;
    if constraint.count() == 0 {
        return Vec::new();
    }
    let samples = std::slice::from_ref(initial);
    spec.system
        .symmetries
        .iter()
        .filter_map(|s| check_constraint(constraint, s, samples, DEFAULT_TOLERANCE).ok())
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

/// The check of each declared symmetry of a file's own `L_d` at the first step's sample
/// `(q₀, q₀ + h p₀)` and the samples near it ([`nearby_samples`]; any pair of points tests the
/// invariance, and `p₀` stands in for the velocity, which an `L_d` alone does not define), with
/// the warning for each that is not one (`⟨dL_d, ξ_{Q×Q}⟩ ≠ 0` by the core's check).
fn discrete_non_symmetries<D: marsden::DiscreteLagrangian>(
    ld: &D,
    spec: &RunSpec,
    initial: &Sample,
) -> (Vec<SymmetryCheck>, Vec<String>) {
    use marsden::symmetry::check::{DEFAULT_TOLERANCE, check_discrete};
    let h = spec.integrator.grid.h;
    let samples = nearby_samples(initial, |s| {
        let q1: Vec<f64> = s.q.iter().zip(&s.v).map(|(q, v)| q + h * v).collect();
        ld.discrete_lagrangian(s.t, h, &s.q, &q1).is_finite()
    });
    let mut checks = Vec::new();
    let mut warnings = Vec::new();
    if samples.is_empty() {
        return unchecked(spec, "L_d is not finite at or near the first step");
    }
    for symmetry in &spec.system.symmetries {
        let Ok(report) = check_discrete(ld, symmetry, h, &samples, DEFAULT_TOLERANCE) else {
            continue;
        };
        let check = SymmetryCheck::of_report(&report);
        let initial = check_discrete(ld, symmetry, h, &samples[..1], DEFAULT_TOLERANCE);
        let initial = largest_defect(initial.ok().as_ref());
        let worst = largest_defect(Some(&report));
        warnings.extend(check.warning(initial, worst));
        checks.push(check);
    }
    (checks, warnings)
}

/// The largest absolute defect of a check's generators (NaN without a report).
fn largest_defect(report: Option<&marsden::symmetry::check::SymmetryReport>) -> f64 {
    report
        .and_then(|r| r.worst())
        .map_or(f64::NAN, |w| w.max_defect)
}

/// How many states near the initial one a declared symmetry is checked at, beside it.
pub const NEARBY_STATES: usize = 8;

/// Relative size of the neighbourhood: each coordinate moves by up to this fraction of
/// `max(|q|, 1)`, each velocity by this fraction of `max(|v|, 1)`, the time forward by up to
/// this fraction of `max(|t|, 1)`.
const NEARBY_RADIUS: f64 = 0.05;

/// The states a declared symmetry is checked at: the initial state and [`NEARBY_STATES`]
/// reproducible pseudo-random states around it, where `finite` holds (a state outside the
/// Lagrangian's domain says nothing about its invariance). A single state cannot tell a symmetry
/// from a coincidence: `L = ½ẋ² − ½x²` has `∂L/∂x = 0` at `x = 0`, and translations are no
/// symmetry of it.
pub fn nearby_samples(initial: &Sample, finite: impl Fn(&Sample) -> bool) -> Vec<Sample> {
    let Sample { t, q, v } = initial;
    let (t, n) = (*t, q.len());
    let q_scale = NEARBY_RADIUS * q.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
    let v_scale = NEARBY_RADIUS * v.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
    let t_scale = NEARBY_RADIUS * t.abs().max(1.0);
    // One more random coordinate moves the time forward (a Lagrangian that depends on `t` may
    // be invariant at `t₀` only: `∂L/∂x ∝ sin √t`), never before `t₀` (its domain may start
    // there).
    let offsets = Sample::random(n + 1, NEARBY_STATES, 0x005E_ED0F_5EED, 1.0);
    std::iter::once(initial.clone())
        .chain(offsets.into_iter().map(|o| Sample {
            t: t + t_scale * 0.5 * (1.0 + o.q[n]),
            q: q.iter().zip(&o.q).map(|(x, r)| x + q_scale * r).collect(),
            v: v.iter().zip(&o.v).map(|(x, r)| x + v_scale * r).collect(),
        }))
        .filter(|s| finite(s))
        .collect()
}

/// Symmetries that could not be checked at any state: none is called one (its momentum map is
/// monitored, and nothing says it is conserved), with a warning saying why.
fn unchecked(spec: &RunSpec, why: &str) -> (Vec<SymmetryCheck>, Vec<String>) {
    let checks = (spec.system.symmetries.iter())
        .map(|s| SymmetryCheck {
            name: marsden_problem::model::MomentumMap::name(s).to_owned(),
            of: "L",
            states: 0,
            max_relative_defect: f64::NAN,
            is_symmetry: false,
        })
        .collect::<Vec<_>>();
    let warnings = checks
        .iter()
        .map(|c| {
            format!(
                "\"{}\" could not be checked as a symmetry ({why}): J_{} is monitored, not \
                 known to be conserved",
                c.name, c.name
            )
        })
        .collect();
    (checks, warnings)
}

/// What the check of one declared symmetry found, for the summary and the printed report.
#[derive(Debug, Clone, PartialEq)]
pub struct SymmetryCheck {
    /// The symmetry's name.
    pub name: String,
    /// What was checked: `"L"` or `"L_d"`.
    pub of: &'static str,
    /// The states it was checked at (the initial one and those near it).
    pub states: usize,
    /// The largest relative defect `|⟨dL, ξ⟩| / Σ|∂L/∂xᵢ ξᵢ|` over them.
    pub max_relative_defect: f64,
    /// Whether it is a symmetry at every state (its momentum map is then conserved).
    pub is_symmetry: bool,
}

impl SymmetryCheck {
    fn of_report(report: &marsden::symmetry::check::SymmetryReport) -> Self {
        let worst = report.worst().map_or(0.0, |w| w.max_relative);
        SymmetryCheck {
            name: report.symmetry.clone(),
            of: report.of,
            states: report.samples,
            max_relative_defect: worst,
            is_symmetry: report.is_symmetry(),
        }
    }

    /// The warning for a declared symmetry that is not one (`None` for a symmetry), with the
    /// defect at the initial state and the largest over the states near it.
    pub fn warning(&self, initial: f64, worst: f64) -> Option<String> {
        let (what, at) = match self.of {
            "L_d" => ("the discrete Lagrangian: ⟨dL_d, ξ_Q×Q⟩", "the first step"),
            _ => ("the Lagrangian: ⟨dL, ξ_TQ⟩", "the initial state"),
        };
        (!self.is_symmetry).then(|| {
            format!(
                "\"{}\" is not a symmetry of {what} = {initial:.3e} at {at}, up to \
                 {worst:.3e} at the {} states near it, so J_{} is monitored but not conserved",
                self.name,
                self.states.saturating_sub(1),
                self.name
            )
        })
    }
}

/// The check of each declared symmetry of the Lagrangian at the initial state and the states
/// near it ([`nearby_samples`]), with the warning for each that is not one (`⟨dL, ξ_TQ⟩ ≠ 0`
/// by the core's check): its momentum map is then monitored but not conserved.
fn non_symmetries<L: Lagrangian>(
    lagrangian: &L,
    spec: &RunSpec,
    initial: &Sample,
) -> (Vec<SymmetryCheck>, Vec<String>) {
    use marsden::symmetry::check::{DEFAULT_TOLERANCE, check_lagrangian};
    let samples = nearby_samples(initial, |s| {
        let value = lagrangian.lagrangian(s.t, &s.q, &s.v);
        let mut p = vec![0.0; s.q.len()];
        mechanics::momentum(lagrangian, s.t, &s.q, &s.v, &mut p);
        value.is_finite() && p.iter().all(|x| x.is_finite())
    });
    let mut checks = Vec::new();
    let mut warnings = Vec::new();
    if samples.is_empty() {
        return unchecked(
            spec,
            "the Lagrangian is not finite at or near the initial state",
        );
    }
    for symmetry in &spec.system.symmetries {
        let Ok(report) = check_lagrangian(lagrangian, symmetry, &samples, DEFAULT_TOLERANCE) else {
            continue;
        };
        let check = SymmetryCheck::of_report(&report);
        let initial = check_lagrangian(lagrangian, symmetry, &samples[..1], DEFAULT_TOLERANCE);
        let initial = largest_defect(initial.ok().as_ref());
        let worst = largest_defect(Some(&report));
        warnings.extend(check.warning(initial, worst));
        checks.push(check);
    }
    (checks, warnings)
}
