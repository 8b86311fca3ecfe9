//! Problem files, in two stages (as ripgrep separates raw flags from validated arguments):
//!
//! 1. [`raw`]: the TOML as written — serde structs with `deny_unknown_fields`, every value
//!    with its span; `toml`'s errors are reworded by [`toml_error`].
//! 2. [`spec`]: the validated [`RunSpec`] — every check made here ([`system`], [`parameters`],
//!    [`settings`], helpers in [`check`]), each failure a [`Diagnostic`] pointing at the
//!    value at fault. Building and running the problem is [`crate::run`]'s job.

pub mod check;
pub mod method;
pub mod nbody_file;
pub mod parameters;
pub mod raw;
pub mod settings;
pub mod spec;
pub mod sweep;
pub mod system;
pub mod toml_error;

use std::path::Path;

pub use method::Method;
pub use spec::{
    Format, InitialData, InitialSpec, IntegratorSpec, LagrangianSpec, OutputSpec, Overrides,
    RunSpec, SpecSpans, SystemSpec,
};
pub use sweep::{SweepSpec, SweepTarget};

use crate::error::Diagnostic;
use crate::source::SourceFile;
use check::Checker;

/// Reads and validates the problem file at `path`, applying the command-line overrides.
///
/// # Errors
/// A diagnostic for the first mistake found (the command exits with status 2).
pub fn load(path: &Path, overrides: &Overrides) -> Result<RunSpec, Diagnostic> {
    let text = std::fs::read_to_string(path).map_err(|e| {
        Diagnostic::new(format!(
            "cannot read the problem file {}: {e}",
            path.display()
        ))
    })?;
    validate(SourceFile::new(path, text), overrides)
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
/// A value the problem cannot take (e.g. initial positions off the constraints).
pub fn member(base: &RunSpec, overrides: &Overrides, k: usize) -> Result<RunSpec, Diagnostic> {
    let source = base.source.clone();
    let mut raw = raw::parse(source.text()).map_err(|e| toml_error::diagnose(&source, &e))?;
    if let Some(sweep) = &base.sweep
        && let Some(value) = sweep.values.get(k)
    {
        sweep::apply(&mut raw, sweep, *value);
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
    let bodies = nbody_file::read(&ck, raw.initial.as_ref())?;
    let system = system::system(&ck, raw.system.as_ref(), bodies.as_ref())?;
    let (initial, initial_spans) = settings::initial(
        &ck,
        raw.initial.as_ref(),
        &system.coordinates,
        bodies.as_ref(),
    )?;
    settings::constraints_at_start(&ck, &system.constraint, &initial.q, initial_spans.q)?;
    let integrator = settings::integrator(&ck, raw.integrator.as_ref(), initial.t0, overrides)?;
    let name = run_name(raw, &system, source.path());
    let output = settings::output(&ck, raw.output.as_ref(), &name, overrides)?;
    let sweep = match with_sweep {
        true => {
            let parts = (&system, &initial, bodies.is_some());
            sweep::sweep(&ck, raw.sweep.as_ref(), parts)?
        }
        false => None,
    };
    let system_table = raw.system.as_ref().map(|s| s.get_ref());
    let lagrangian_span = system_table
        .and_then(|s| s.lagrangian.as_ref().or(s.builtin.as_ref()))
        .map(|v| v.span());
    let spans = SpecSpans {
        lagrangian: lagrangian_span,
        initial_data: Some(initial_spans.data),
    };
    Ok(RunSpec {
        source,
        name,
        system,
        initial,
        integrator,
        output,
        spans,
        sweep,
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
        LagrangianSpec::Expression(_) => path
            .file_stem()
            .map_or("run".to_owned(), |s| s.to_string_lossy().into_owned()),
    }
}
