//! The initial state completed by the core (`p` from `v` by the Legendre transform, or `v`
//! from `p` by its inverse) and checked for regularity — before any file is written.

use marsden::{Constraint, Lagrangian, Problem, mechanics};
use num_dual::Dual64;

use crate::catalog::WithLagrangian;
use crate::error::Diagnostic;
use crate::problem::RunSpec;
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
        let problem = Problem::new(lagrangian, spec.initial.to_initial(), spec.integrator.grid)
            .map_err(|e| start_error(spec, &e))?;
        let start = problem.start();
        let v = problem.initial_velocity().to_vec();
        let energy = mechanics::energy(lagrangian, start.t, &start.q, &v);
        let mut warnings: Vec<String> = tangency(&spec.system.constraint, &start.q, &v)
            .into_iter()
            .collect();
        warnings.extend(non_symmetries(lagrangian, spec, (start.t, &start.q, &v)));
        Ok(Start {
            t: start.t,
            q: start.q.clone(),
            v,
            p: start.p.clone(),
            energy,
            warnings,
        })
    }
}

/// A warning if the initial velocities leave the constraint manifold: `Dφ(q₀) v₀ ≠ 0`
/// (beyond `1e-9 · max(1, |v₀|)`). SHAKE keeps `φ(q) = 0` anyway, but without RATTLE's
/// projection the momenta keep the normal component.
pub fn tangency<C: Constraint>(constraint: &C, q: &[f64], v: &[f64]) -> Option<String> {
    let d = constraint.count();
    if d == 0 {
        return None;
    }
    // One dual evaluation at q + εv gives Dφ(q)·v in the ε parts.
    let x: Vec<Dual64> = q.iter().zip(v).map(|(&q, &v)| Dual64::new(q, v)).collect();
    let mut phi = vec![Dual64::from(0.0); d];
    constraint.constraint(&x, &mut phi);
    let scale = v.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
    let (i, rate) = phi
        .iter()
        .map(|p| p.eps)
        .enumerate()
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))?;
    (rate.abs() > 1e-9 * scale || rate.is_nan()).then(|| {
        format!(
            "the initial velocities are not tangent to constraint [{i}]: dφ/dt = {rate:e}; \
             the positions stay on the constraint, but the momenta keep the normal part \
             (no RATTLE projection yet)"
        )
    })
}

/// The core's error about the initial state, pointed at the file.
pub fn start_error(spec: &RunSpec, e: &marsden::Error) -> Diagnostic {
    let source: &SourceFile = &spec.source;
    match e {
        marsden::Error::SingularLagrangian { .. } => Diagnostic::new(e.to_string())
            .at(source.locate_opt(spec.spans.lagrangian.clone()))
            .help("∂²L/∂q̇² must be invertible: every velocity must appear in L, quadratically for a mechanical system"),
        marsden::Error::InverseLegendre { .. } => Diagnostic::new(e.to_string())
            .at(source.locate_opt(spec.spans.initial_data.clone()))
            .help("give the initial velocities `v` instead of the momenta `p`"),
        _ => Diagnostic::new(format!("cannot set up the problem: {e}")),
    }
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
