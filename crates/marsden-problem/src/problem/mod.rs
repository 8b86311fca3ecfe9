//! Problem files, in two stages (as ripgrep separates raw flags from validated arguments):
//!
//! 1. [`raw`]: the TOML as written — serde structs with `deny_unknown_fields`, every value
//!    with its span; `toml`'s errors are reworded by [`toml_error`].
//! 2. [`spec`]: the validated [`RunSpec`] — every check made here ([`system`], [`parameters`],
//!    [`settings`], [`named_symmetry`], helpers in [`check`]), each failure a [`Diagnostic`] pointing at the
//!    value at fault. Building and running the problem is the engine's job (`marsden_engine`).
//!
//! Entry points: [`load`] (a file on disk), [`from_toml_str`] (text from anywhere, e.g. a
//! notebook cell), [`member`] (one member of a sweep).

pub mod check;
pub mod checkpoints;
pub mod constraint_regularity;
pub mod control_table;
pub mod discrete;
pub mod events;
#[cfg(test)]
mod events_tests;
pub mod grid;
pub mod hamiltonian;
pub mod last_step;
pub mod method;
pub mod multibody;
mod multibody_bodies;
pub mod multibody_initial;
pub mod multibody_particles;
mod multibody_potential;
pub mod multibody_springs;
pub mod named_symmetry;
pub mod nbody_file;
pub mod number;
pub mod optimal_control;
mod overrides;
pub mod parameters;
pub mod raw;
pub mod raw_multibody;
mod resolved;
pub mod rigid;
pub mod rigid_catalog;
pub mod rigid_settings;
pub mod sampled_times;
pub mod sensitivity;
pub mod settings;
pub mod spec;
pub mod sweep;
pub mod system;
pub mod toml_error;

use std::path::{Path, PathBuf};

pub use method::Method;
pub use sensitivity::SensitivitySpec;
pub use spec::{
    Format, InitialData, InitialSpec, IntegratorSpec, LagrangianSpec, OutputSpec, Overrides,
    RunSpec, SpecSpans, SystemSpec,
};
pub use sweep::{AxisValues, SweepAxis, SweepSpec, SweepTarget};

use crate::error::Diagnostic;
use crate::source::SourceFile;
use check::Checker;

/// Reads and validates the problem file at `path`, applying the command-line overrides.
///
/// # Errors
/// A diagnostic for the first mistake found (the command exits with status 2).
pub fn load(path: &Path, overrides: &Overrides) -> Result<RunSpec, Diagnostic> {
    let text = crate::source::read_bounded(path, "problem file").map_err(Diagnostic::new)?;
    validate(SourceFile::new(path, text), overrides)
}

/// Validates the text of a problem file; `origin` names it in the diagnostics and in the
/// provenance of the results (a path, or a label such as `<notebook>`), and relative paths in
/// the file (an N-body `file = "…"`) are read from the current directory.
///
/// ```
/// use marsden_problem::{Overrides, from_toml_str};
///
/// let text = "[system]\nbuiltin = \"pendulum\"\n[initial]\nq = [1.0]\nv = [0.0]\n\
///             [integrator]\nh = 0.1\nsteps = 10\n";
/// let spec = from_toml_str(text, "pendulum.toml", &Overrides::default())?;
/// assert_eq!(spec.integrator.grid.steps, 10);
///
/// let err = from_toml_str("[integrator]\nh = -1\n", "bad.toml", &Overrides::default());
/// assert!(err.unwrap_err().to_string().starts_with("error: "));
/// # Ok::<(), marsden_problem::Diagnostic>(())
/// ```
///
/// # Errors
/// A diagnostic for the first mistake found.
pub fn from_toml_str(
    text: &str,
    origin: impl Into<PathBuf>,
    overrides: &Overrides,
) -> Result<RunSpec, Diagnostic> {
    validate(SourceFile::new(origin, text.to_owned()), overrides)
}

impl RunSpec {
    /// [`load`] without overrides.
    ///
    /// # Errors
    /// As [`load`].
    pub fn load(path: impl AsRef<Path>) -> Result<RunSpec, Diagnostic> {
        load(path.as_ref(), &Overrides::default())
    }

    /// [`from_toml_str`] without overrides.
    ///
    /// # Errors
    /// As [`from_toml_str`].
    pub fn from_toml_str(text: &str, origin: impl Into<PathBuf>) -> Result<RunSpec, Diagnostic> {
        from_toml_str(text, origin, &Overrides::default())
    }
}

/// Refuses what a sweep's members cannot give: `[sensitivity]`, `[analysis] certify` and
/// `every_step` describe one run's outputs, and a sweep writes one row per member — dropped
/// silently they would look done.
fn refuse_in_sweep(ck: &Checker<'_>, raw: &raw::RawProblem) -> Result<(), Diagnostic> {
    let analysis = raw.analysis.as_ref().map(|a| a.get_ref());
    let found = [
        raw.sensitivity
            .as_ref()
            .map(|s| ("[sensitivity]", s.span())),
        analysis
            .and_then(|a| a.certify.as_ref())
            .filter(|c| *c.get_ref())
            .map(|c| ("`certify = true`", c.span())),
        analysis
            .and_then(|a| a.every_step.as_ref())
            .filter(|c| *c.get_ref())
            .map(|c| ("`every_step = true`", c.span())),
        (raw.events.as_ref())
            .and_then(|e| e.first())
            .map(|e| ("[[events]]", e.span())),
        (raw.output.as_ref())
            .and_then(|o| o.get_ref().observables.as_ref())
            .map(|o| ("`observables`", o.span())),
        (raw.output.as_ref())
            .and_then(|o| o.get_ref().times.as_ref())
            .map(|o| ("`times`", o.span())),
    ];
    match found.into_iter().flatten().next() {
        Some((what, span)) => Err(ck
            .error(
                Some(span),
                format!("{what} cannot be used in a file with [sweep]: a sweep writes one row per member"),
            )
            .help("remove it to run the sweep, or remove [sweep] to run one member with it")),
        None => Ok(()),
    }
}

/// Validates the text of a problem file (stage 1 then stage 2), its `[sweep]` included.
///
/// # Errors
/// A diagnostic for the first mistake found.
pub fn validate(source: SourceFile, overrides: &Overrides) -> Result<RunSpec, Diagnostic> {
    let raw = raw::parse(source.text()).map_err(|e| toml_error::diagnose(&source, &e))?;
    validate_raw(source, &raw, overrides, true)
}

/// Member `k` of the sweep of `base`: the file with the swept value replaced by the member's
/// value, validated again (without its `[sweep]`).
///
/// # Errors
/// Refuses a constraint whose gradient vanishes on its zero set
/// ([`constraint_regularity::vanishing_gradient`]), pointing at it in `[system] constraints`.
fn refuse_vanishing_gradient(
    ck: &Checker<'_>,
    raw: &raw::RawProblem,
    constraint: &crate::model::ExprConstraint,
    q0: &[f64],
) -> Result<(), Diagnostic> {
    let Some(v) = constraint_regularity::vanishing_gradient(constraint, q0) else {
        return Ok(());
    };
    let item = (raw.system.as_ref())
        .and_then(|s| s.get_ref().constraints.as_ref())
        .and_then(|list| list.get_ref().get(v.index));
    let text = item.map_or(String::new(), |c| format!(" `{}`", c.get_ref()));
    let i = v.index;
    Err(ck
        .error(
            item.map(|c| c.span()),
            format!(
                "the gradient of constraint {i}{text} vanishes on its zero set: |∇φ_{i}| = \
                 {:.1e} at q = [{}] (where φ_{i} = 0), against {:.1e} at {:.0e} beside it",
                v.gradient,
                (v.at.iter().map(|x| format!("{x:.6}")))
                    .collect::<Vec<_>>()
                    .join(", "),
                v.beside,
                v.offset
            ),
        )
        .note(
            "the constraint forces −Dφ(q)ᵀλ cannot act where ∇φ = 0: the multipliers are \
             undetermined and every step's Newton matrix is singular (φ has a multiple root \
             there, as a square (…)^2 has)",
        )
        .help("write φ with a simple root, e.g. \"x^2 + y^2 - 1\" rather than its square"))
}

/// A value the problem cannot take (e.g. initial positions off the constraints).
pub fn member(base: &RunSpec, overrides: &Overrides, k: usize) -> Result<RunSpec, Diagnostic> {
    let source = base.source.clone();
    let mut raw = raw::parse(source.text()).map_err(|e| toml_error::diagnose(&source, &e))?;
    if let Some(sweep) = &base.sweep
        && k < sweep.count()
    {
        sweep::apply_member(&mut raw, sweep, k);
    }
    validate_raw(source, &raw, overrides, false)
}

fn validate_raw(
    source: SourceFile,
    raw: &raw::RawProblem,
    overrides: &Overrides,
    with_sweep: bool,
) -> Result<RunSpec, Diagnostic> {
    let ck = Checker::new(&source);
    optimal_control::refuse_in_run(&ck, raw)?;
    discrete::refuse_unsupported(&ck, raw)?;
    let bodies = nbody_file::read(&ck, raw.initial.as_ref())?;
    let system = system::system(&ck, raw.system.as_ref(), bodies.as_ref())?;
    let mut system = system;
    let (initial, initial_spans) = if let LagrangianSpec::Multibody(bodies) = &mut system.lagrangian
    {
        let read = multibody_initial::initial(&ck, raw.initial.as_ref(), bodies)?;
        if let (false, Some(raw_system)) = (read.0.project, raw.system.as_ref()) {
            multibody_initial::check_joints(&ck, raw_system.get_ref(), bodies, read.0.t0)?;
        }
        read
    } else if let Some(body) = system.rigid() {
        multibody_initial::refuse_body_tables(&ck, raw.initial.as_ref())?;
        rigid_settings::initial(&ck, raw.initial.as_ref(), body)?
    } else {
        {
            rigid_settings::refuse_rigid_keys(&ck, raw)?;
            multibody_initial::refuse_body_tables(&ck, raw.initial.as_ref())?;
            settings::initial(
                &ck,
                raw.initial.as_ref(),
                &system.coordinates,
                bodies.as_ref(),
            )?
        }
    };
    let system = system;
    refuse_vanishing_gradient(&ck, raw, &system.constraint, &initial.q)?;
    // With `project = true` the start is projected onto the manifold when the run starts
    // (`run::start`), so positions off it are accepted here.
    if !initial.project {
        settings::constraints_at_start(&ck, &system.constraint, &initial.q, initial_spans.q)?;
    }
    let mut integrator = settings::integrator(&ck, raw.integrator.as_ref(), initial.t0, overrides)?;
    last_step::refuse_unsupported(&ck, raw, &system, &integrator.grid)?;
    let mut system = system;
    control_table::attach(&ck, raw, &mut system, &integrator)?;
    let system = system;
    if system.rigid().is_some() || system.multibody().is_some() {
        let span = (raw.integrator.as_ref())
            .and_then(|i| i.get_ref().method.as_ref())
            .map(|m| m.span());
        integrator.method = rigid_settings::method(&ck, &integrator.method, span)?;
        let what = match system.multibody() {
            Some(_) => "a multibody system",
            None => "a rigid body",
        };
        rigid_settings::refuse_unsupported(&ck, raw, what)?;
    }
    if !system.constraint.components().is_empty() {
        let written = (raw.integrator.as_ref()).and_then(|i| i.get_ref().method.as_ref());
        let name = written.map_or(integrator.method.to_string(), |m| m.get_ref().clone());
        if let Some(refusal) = integrator.method.constraint_refusal_as_written(&name) {
            let span = written.map(|m| m.span());
            return Err(ck.error(span, refusal.headline).note(refusal.note));
        }
    }
    if integrator.method == Method::Exact && system.force.is_active() {
        let span = (raw.integrator.as_ref())
            .and_then(|i| i.get_ref().method.as_ref())
            .map(|m| m.span());
        return Err(ck
            .error(span, "the method `exact` cannot be used with forces")
            .note(
                "the core computes the exact discrete Lagrangian of the unforced L by shooting; \
                 it has no exact discrete forces f_d^±",
            )
            .help("remove `forces`, or choose a rule, e.g. `method = \"gauss-3\"`"));
    }
    let name = run_name(raw, &system, source.path());
    let mut output = settings::output(
        &ck,
        raw.output.as_ref(),
        &name,
        overrides,
        &system.coordinates,
    )?;
    output.times = sampled_times::times(&ck, raw, &system, &integrator.grid)?;
    output.exact_times = sampled_times::exact(&ck, raw, &output.times)?;
    let sweep = match with_sweep {
        true => sweep::sweep(&ck, raw.sweep.as_ref(), &system, &initial, bodies.is_some())?,
        false => None,
    };
    if sweep.is_some() {
        refuse_in_sweep(&ck, raw)?;
    }
    let sensitivity = sensitivity::sensitivity(&ck, raw.sensitivity.as_ref(), &system)?;
    let kind = checkpoints::RunKind {
        system: &system,
        method: &integrator.method,
    };
    // A sweep (and each of its members) checkpoints whole members, whatever they are.
    if raw.sweep.is_none() {
        checkpoints::refuse_unsupported(&ck, raw, output.checkpoint_every, kind)?;
    }
    let events = events::events(&ck, raw, &system)?;
    let system_table = raw.system.as_ref().map(|s| s.get_ref());
    let lagrangian_span = system_table
        .and_then(|s| {
            (s.lagrangian.as_ref().or(s.builtin.as_ref()))
                .or(s.hamiltonian.as_ref())
                .or(s.discrete_lagrangian.as_ref())
        })
        .map(|v| v.span());
    let method_span = raw
        .integrator
        .as_ref()
        .and_then(|i| i.get_ref().method.as_ref())
        .map(|m| m.span());
    let spans = SpecSpans {
        lagrangian: lagrangian_span,
        initial_data: Some(initial_spans.data),
        method: method_span,
    };
    Ok(RunSpec {
        source,
        overrides: overrides.clone(),
        name,
        system,
        initial,
        integrator,
        output,
        spans,
        sweep,
        sensitivity,
        events,
        analysis: spec::AnalysisSpec {
            every_step: (raw.analysis.as_ref())
                .and_then(|a| a.get_ref().every_step.as_ref())
                .is_some_and(|e| *e.get_ref()),
            certify: (raw.analysis.as_ref())
                .and_then(|a| a.get_ref().certify.as_ref())
                .is_some_and(|e| *e.get_ref()),
        },
    })
}

/// `[system] name`, else the builtin's name, else the file's stem.
fn run_name(raw: &raw::RawProblem, system: &SystemSpec, path: &Path) -> String {
    let written = raw.system.as_ref().and_then(|s| s.get_ref().name.as_ref());
    if let Some(name) = written {
        return name.get_ref().clone();
    }
    match &system.lagrangian {
        LagrangianSpec::Builtin { builtin, .. } => builtin.name().to_owned(),
        LagrangianSpec::Expression(_)
        | LagrangianSpec::Hamiltonian(_)
        | LagrangianSpec::Discrete(_)
        | LagrangianSpec::Rigid(_)
        | LagrangianSpec::Multibody(_) => path
            .file_stem()
            .map_or("run".to_owned(), |s| s.to_string_lossy().into_owned()),
    }
}
