//! `[initial]`, `[integrator]` and `[output]` → their specs, with the command-line overrides.

use std::ops::Range;
use std::path::PathBuf;

use marsden::{NewtonOptions, TimeGrid};
use toml::Spanned;

use super::check::Checker;
use super::grid::{check_grid, check_steps, steps_until};
use super::method::{EXACT_NOTE, METHOD_NAMES, Method};
use super::nbody_file::BodiesFile;
use super::raw::{RawInitial, RawIntegrator, RawOutput, SpannedList};
use super::spec::{Format, InitialData, InitialSpec, IntegratorSpec, OutputSpec, Overrides};
use crate::error::Diagnostic;
use crate::model::ExprConstraint;
use marsden::Constraint;
use marsden_expr::closest;

/// Where `q` and `v`/`p` were written.
#[derive(Debug, Clone, PartialEq)]
pub struct InitialSpans {
    /// The `q` vector.
    pub q: Range<usize>,
    /// The `v` or `p` vector.
    pub data: Range<usize>,
}

/// Validates `[initial]` against the coordinates (`bodies`: the data of `file = "…"`).
pub fn initial(
    ck: &Checker<'_>,
    raw: Option<&Spanned<RawInitial>>,
    coordinates: &[String],
    bodies: Option<&BodiesFile>,
) -> Result<(InitialSpec, InitialSpans), Diagnostic> {
    let Some(raw) = raw else {
        return Err(Diagnostic::new("the problem file has no [initial] table")
            .help("add [initial] with `q = [...]` and `v = [...]` (or `p = [...]`)"));
    };
    let table = raw.get_ref();
    if let Some(bodies) = bodies {
        return from_file(ck, table, bodies);
    }
    let Some(q) = &table.q else {
        return Err(ck.error(
            Some(raw.span()),
            "[initial] needs the positions `q = [...]`",
        ));
    };
    let q_span = q.span();
    let q = ck.vector("initial.q", q, coordinates)?;
    let (data, span) = match (&table.v, &table.p) {
        (Some(_), Some(p)) => {
            return Err(ck
                .error(
                    Some(p.span()),
                    "give either `v` or `p` in [initial], not both",
                )
                .help("`v` are velocities q̇(t₀), `p` momenta ∂L/∂q̇; the other follows"));
        }
        (None, None) => {
            return Err(ck.error(
                Some(raw.span()),
                "[initial] needs the velocities `v = [...]` or the momenta `p = [...]`",
            ));
        }
        (Some(v), None) => (
            InitialData::Velocity(ck.vector("initial.v", v, coordinates)?),
            v.span(),
        ),
        (None, Some(p)) => (
            InitialData::Momentum(ck.vector("initial.p", p, coordinates)?),
            p.span(),
        ),
    };
    let t0 = table
        .t0
        .as_ref()
        .map_or(Ok(0.0), |t| ck.finite("initial.t0", t))?;
    let spans = InitialSpans {
        q: q_span,
        data: span,
    };
    let project = table.project.unwrap_or(false);
    Ok((
        InitialSpec {
            t0,
            q,
            data,
            project,
            rigid: None,
        },
        spans,
    ))
}

/// The initial state of an N-body file; `q`, `v` and `p` must not be written as well.
fn from_file(
    ck: &Checker<'_>,
    table: &RawInitial,
    bodies: &BodiesFile,
) -> Result<(InitialSpec, InitialSpans), Diagnostic> {
    let written = [&table.q, &table.v, &table.p];
    if let Some(list) = written.into_iter().flatten().next() {
        return Err(ck
            .error(
                Some(list.span()),
                "give the initial state either in `file` or as `q`, `v`/`p`, not both",
            )
            .help("the file holds the positions and velocities of every body"));
    }
    let t0 = table
        .t0
        .as_ref()
        .map_or(Ok(0.0), |t| ck.finite("initial.t0", t))?;
    let spec = InitialSpec {
        t0,
        q: bodies.data.q.clone(),
        data: InitialData::Velocity(bodies.data.v.clone()),
        project: table.project.unwrap_or(false),
        rigid: None,
    };
    let spans = InitialSpans {
        q: bodies.span.clone(),
        data: bodies.span.clone(),
    };
    Ok((spec, spans))
}

/// Checks that the initial positions satisfy the constraints: `|φᵢ(q₀)| ≤ 1e-9 · max(1, |q₀|)`.
pub fn constraints_at_start(
    ck: &Checker<'_>,
    constraint: &ExprConstraint,
    q: &[f64],
    span: Range<usize>,
) -> Result<(), Diagnostic> {
    let mut phi = vec![0.0; constraint.count()];
    constraint.constraint(q, &mut phi);
    let scale = q.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
    let programs = constraint.components().programs();
    for (i, (value, program)) in phi.iter().zip(programs).enumerate() {
        if value.abs() > 1e-9 * scale || value.is_nan() {
            return Err(ck
                .error(
                    Some(span),
                    format!(
                        "the initial positions violate constraint [{i}]: {} = {value:e}",
                        program.text()
                    ),
                )
                .help(
                    "start on the constraint manifold φ(q) = 0 (to about 1e-9), or set \
                     `project = true` in [initial] to move the start onto it",
                ));
        }
    }
    Ok(())
}

/// Validates `[integrator]` with the overrides.
pub fn integrator(
    ck: &Checker<'_>,
    raw: Option<&Spanned<RawIntegrator>>,
    t0: f64,
    overrides: &Overrides,
) -> Result<IntegratorSpec, Diagnostic> {
    let Some(raw) = raw else {
        return Err(
            Diagnostic::new("the problem file has no [integrator] table")
                .help("add [integrator] with `h = ...` and `steps = ...` (or `t_end = ...`)"),
        );
    };
    let table = raw.get_ref();
    let method = method(ck, table.method.as_ref())?;
    let h = step_size(ck, raw, overrides.h)?;
    let (steps, t_end) = steps(ck, raw, t0, h, overrides.steps)?;
    let grid = match t_end {
        Some(end) => TimeGrid::ending_at(t0, end, h),
        None => TimeGrid::new(t0, h, steps),
    };
    let grid = grid.map_err(|e| ck.error(Some(raw.span()), e.to_string()))?;
    check_grid(&grid).map_err(|m| {
        let at = table.h.as_ref().map_or(raw.span(), Spanned::span);
        ck.error(Some(at), m)
            .help("shorten the run, or shift t0 (a Lagrangian without t does not depend on it)")
    })?;
    let mut newton = NewtonOptions::default();
    if let Some(tol) = &table.tolerance {
        newton.residual_tolerance = positive(ck, "tolerance", tol)?;
    }
    if let Some(max) = &table.max_iterations {
        newton.max_iterations = count(ck, "max_iterations", max)?;
    }
    let fast_paths = table.fast_paths.as_ref().is_none_or(|f| *f.get_ref());
    let compensated = table.compensated.as_ref().is_some_and(|c| *c.get_ref());
    Ok(IntegratorSpec {
        method,
        grid,
        newton,
        fast_paths,
        compensated,
        t_end,
    })
}

fn method(ck: &Checker<'_>, raw: Option<&Spanned<String>>) -> Result<Method, Diagnostic> {
    let Some(name) = raw else {
        return Ok(Method::midpoint());
    };
    Method::parse(name.get_ref()).map_err(|e| {
        ck.error(Some(name.span()), e.message)
            .suggest(e.suggestion.as_deref())
            .note(format!("methods: {METHOD_NAMES}, {EXACT_NOTE}"))
    })
}

fn step_size(
    ck: &Checker<'_>,
    raw: &Spanned<RawIntegrator>,
    flag: Option<f64>,
) -> Result<f64, Diagnostic> {
    if let Some(h) = flag {
        return check_h(h).map_err(|m| Diagnostic::new(format!("--h {m}")));
    }
    let Some(h) = &raw.get_ref().h else {
        return Err(ck.error(Some(raw.span()), "[integrator] needs the time step `h`"));
    };
    check_h(*h.get_ref()).map_err(|m| ck.error(Some(h.span()), format!("h {m}")))
}

fn check_h(h: f64) -> Result<f64, String> {
    if h.is_finite() && h > 0.0 {
        Ok(h)
    } else {
        Err(format!("must be a positive, finite time step, got {h}"))
    }
}

fn steps(
    ck: &Checker<'_>,
    raw: &Spanned<RawIntegrator>,
    t0: f64,
    h: f64,
    flag: Option<u64>,
) -> Result<(usize, Option<f64>), Diagnostic> {
    let table = raw.get_ref();
    if let Some(n) = flag {
        return usize::try_from(n)
            .ok()
            .filter(|n| *n >= 1)
            .ok_or_else(|| Diagnostic::new(format!("--steps must be at least 1, got {n}")))
            .and_then(|n| check_steps(n).map_err(|m| Diagnostic::new(format!("--steps: {m}"))))
            .map(|n| (n, None));
    }
    match (&table.steps, &table.t_end) {
        (Some(_), Some(t_end)) => Err(ck.error(
            Some(t_end.span()),
            "give either `steps` or `t_end` in [integrator], not both",
        )),
        (None, None) => Err(ck.error(
            Some(raw.span()),
            "[integrator] needs the length of the run: `steps = ...` or `t_end = ...`",
        )),
        (Some(n), None) => {
            let steps = count(ck, "steps", n)?;
            check_steps(steps).map_err(|m| ck.error(Some(n.span()), m))?;
            Ok((steps, None))
        }
        (None, Some(t_end)) => {
            let end = ck.finite("t_end", t_end)?;
            let steps = steps_until(t0, end, h).map_err(|m| ck.error(Some(t_end.span()), m))?;
            Ok((steps, Some(end)))
        }
    }
}

fn positive(ck: &Checker<'_>, what: &str, v: &Spanned<f64>) -> Result<f64, Diagnostic> {
    let x = ck.finite(what, v)?;
    if x > 0.0 {
        Ok(x)
    } else {
        Err(ck.error(Some(v.span()), format!("{what} must be positive, got {x}")))
    }
}

fn count(ck: &Checker<'_>, what: &str, v: &Spanned<i64>) -> Result<usize, Diagnostic> {
    usize::try_from(*v.get_ref())
        .ok()
        .filter(|n| *n >= 1)
        .ok_or_else(|| {
            ck.error(
                Some(v.span()),
                format!("{what} must be at least 1, got {}", v.get_ref()),
            )
        })
}

/// `name` as one directory inside `out/`: path separators and control characters become
/// `_`, and a name of dots only (`.`, `..`) or none becomes `run`, so `name = "../x"` or an
/// absolute path cannot steer the default output directory elsewhere.
pub fn directory_name(name: &str) -> String {
    let clean: String = name
        .chars()
        .map(|c| match c {
            '/' | '\\' => '_',
            c if c.is_control() => '_',
            c => c,
        })
        .collect();
    if clean.chars().all(|c| c == '.') {
        "run".to_owned()
    } else {
        clean
    }
}

/// Validates `[output]` with the overrides; `name` gives the default directory `out/<name>`.
pub fn output(
    ck: &Checker<'_>,
    raw: Option<&Spanned<RawOutput>>,
    name: &str,
    overrides: &Overrides,
    coordinates: &[String],
) -> Result<OutputSpec, Diagnostic> {
    let table = raw.map(Spanned::get_ref);
    let written_dir = table.and_then(|t| t.dir.as_ref());
    let dir = match (&overrides.out, written_dir) {
        (Some(dir), _) => dir.clone(),
        (None, Some(d)) if d.get_ref().trim().is_empty() => {
            return Err(ck.error(Some(d.span()), "`dir` is empty"));
        }
        (None, Some(d)) => PathBuf::from(d.get_ref()),
        (None, None) => PathBuf::from("out").join(directory_name(name)),
    };
    let format = match table.and_then(|t| t.format.as_ref()) {
        None => Format::Csv,
        Some(f) => match f.get_ref().as_str() {
            "csv" => Format::Csv,
            "npy" => Format::Npy,
            other => {
                return Err(ck
                    .error(Some(f.span()), format!("unknown output format `{other}`"))
                    .suggest(closest(other, ["csv", "npy"]))
                    .note("formats: csv (trajectory.csv), npy (t.npy, q.npy, p.npy, …)"));
            }
        },
    };
    let every = match (overrides.every, table.and_then(|t| t.every.as_ref())) {
        (Some(n), _) => every_override(n)?,
        (None, None) => 1,
        (None, Some(e)) => count(ck, "every", e)?,
    };
    let plots = table
        .and_then(|t| t.plots.as_ref())
        .is_none_or(|p| *p.get_ref());
    let angles = match table.and_then(|t| t.angles.as_ref()) {
        None => Vec::new(),
        Some(list) => angles(ck, list, coordinates)?,
    };
    let checkpoint_every = match (
        overrides.checkpoint_every,
        table.and_then(|t| t.checkpoint_every.as_ref()),
    ) {
        (Some(n), _) => Some(checkpoint_every_override(n)?),
        (None, Some(e)) => Some(count(ck, "checkpoint_every", e)?),
        (None, None) => None,
    };
    Ok(OutputSpec {
        dir,
        format,
        every,
        plots,
        angles,
        checkpoint_every,
        times: Vec::new(),
        exact_times: false,
    })
}

/// The override of `[output] every` (Python's `solve(every=…)`): at least 1. Shared by the
/// file's checks and [`RunSpec::with_overrides`](super::RunSpec::with_overrides), so both
/// refuse a 0 with the same words.
///
/// # Errors
/// A 0.
pub fn every_override(n: u64) -> Result<usize, Diagnostic> {
    match n {
        0 => Err(Diagnostic::new("`every` must be at least 1, got 0")),
        n => Ok(usize::try_from(n).unwrap_or(usize::MAX)),
    }
}

/// The override of `[output] checkpoint_every` (`--checkpoint-every`): at least 1 (as
/// [`every_override`]).
///
/// # Errors
/// A 0.
pub fn checkpoint_every_override(n: u64) -> Result<usize, Diagnostic> {
    match n {
        0 => Err(Diagnostic::new(
            "--checkpoint-every must be at least 1, got 0",
        )),
        n => Ok(usize::try_from(n).unwrap_or(usize::MAX)),
    }
}

/// `angles = ["theta"]`: each must name a coordinate.
fn angles(
    ck: &Checker<'_>,
    list: &SpannedList<String>,
    coordinates: &[String],
) -> Result<Vec<String>, Diagnostic> {
    let mut names = Vec::new();
    for a in list.get_ref() {
        let name = a.get_ref();
        if !coordinates.contains(name) {
            return Err(ck
                .error(
                    Some(a.span()),
                    format!("`{name}` in `angles` is not a coordinate"),
                )
                .suggest(closest(name, coordinates.iter().map(String::as_str)))
                .note(format!("the coordinates are {}", coordinates.join(", "))));
        }
        names.push(name.clone());
    }
    Ok(names)
}
