//! `[optimal_control]` and `[system] controls`: a discrete mechanics and optimal control
//! (DMOC, [OJM11]) problem from a problem file, checked into an [`OptimalControlSpec`] that
//! `marsden optimize` solves.
//!
//! The controls `u` enter the dynamics only through `[system] forces`, which then read
//! `[q, q̇, t, u]`; the running cost `C(t, q, q̇, u)` and the path inequalities
//! `g(t, q, q̇, u) ≤ 0` read the same inputs and the final cost `Φ(q_N, p_N)` reads `[q, p, t]`
//! (momenta named `p_<coordinate>`). Any rule with a discrete
//! Lagrangian transcribes: a two-point rule or a composition with controls piecewise constant
//! per step, a Galerkin rule (`gauss-<s>`, `lobatto-<s>`) with one control value per quadrature
//! node (`marsden_control::stages`). A file with `[optimal_control]` is refused by
//! `marsden run` (see [`refuse_in_run`]); `[system] controls` alone run as zero controls, or
//! as the values of a `[system] control_table` ([`super::control_table`]).
//!
//! [OJM11]: marsden#references

pub mod boundary;
pub mod controls;
mod options;
pub mod raw;
#[cfg(test)]
mod tests;

use std::path::{Path, PathBuf};

use marsden_expr::{Program, ProgramSet, Symbols};
use toml::Spanned;

use super::check::Checker;
use super::method::Method;
use super::parameters::Parameters;
use super::raw::{RawOutput, RawProblem, RawSystem, SpannedList};
use super::resolved::symbols;
use super::spec::{LagrangianSpec, OutputSpec, Overrides, SystemSpec};
use super::{settings, system, toml_error};
use crate::error::Diagnostic;
use crate::model::hamiltonian::cotangent_inputs;
use crate::model::slots::tangent_inputs;
use crate::model::{ExprLagrangian, ForceInputs, Symmetry};
use crate::source::SourceFile;
pub use boundary::{BoundsSpec, EndSpec, RateSpec};
use controls::Control;
use raw::RawOptimalControl;

/// How the solver's first iterate is made.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GuessKind {
    /// The forward simulation from a complete `start` with zero controls (the default when
    /// the start is complete).
    Simulation,
    /// The straight line between the boundary positions, zero controls (free positions held
    /// at the other end's value or 0).
    Line,
}

/// The SQP solver's budget and tolerances.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverSpec {
    /// Iteration budget.
    pub max_iterations: usize,
    /// Tolerance on the KKT residual.
    pub tolerance: f64,
    /// Tolerance on `max |c_i|`.
    pub constraint_tolerance: f64,
}

/// A checked `[optimal_control]` problem.
#[derive(Debug, Clone)]
pub struct OptimalControlSpec {
    /// The file it came from.
    pub source: SourceFile,
    /// The run's name (`[system] name`, else the file's stem).
    pub name: String,
    /// The Lagrangian.
    pub lagrangian: ExprLagrangian,
    /// Coordinate names.
    pub coordinates: Vec<String>,
    /// Control names, in declared order.
    pub controls: Vec<String>,
    /// Every scalar parameter with its value, in the file's order.
    pub parameters: Vec<(String, f64)>,
    /// `[[system.symmetry]]`: momentum maps whose forced Noether balance is reported.
    pub symmetries: Vec<Symmetry>,
    /// The forces, one per coordinate, over `[q, q̇, t, u]`.
    pub force: ProgramSet,
    /// The running cost over `[q, q̇, t, u]`.
    pub cost: Program,
    /// The final cost over `[q, p, t]`, if given.
    pub final_cost: Option<Program>,
    /// The path inequalities `g ≤ 0` over `[q, q̇, t, u]` (empty: none).
    pub path: ProgramSet,
    /// The path inequalities as written, in order.
    pub path_texts: Vec<String>,
    /// The rule.
    pub method: Method,
    /// Initial time.
    pub t0: f64,
    /// Final time.
    pub t_end: f64,
    /// Steps `N`.
    pub steps: usize,
    /// Conditions at `t0`.
    pub start: EndSpec,
    /// Conditions at `t_end`.
    pub end: EndSpec,
    /// Bounds on the controls.
    pub control_bounds: BoundsSpec,
    /// Bounds on the coordinates at every node.
    pub state_bounds: BoundsSpec,
    /// The first iterate.
    pub guess: GuessKind,
    /// Solver options.
    pub solver: SolverSpec,
    /// Where the results go (`dir`, `plots`, `angles`).
    pub output: OutputSpec,
}

/// Reads and checks the optimal control problem in the file at `path`.
///
/// # Errors
/// A diagnostic for the first mistake found (the command exits with status 2).
pub fn load(path: &Path, overrides: &Overrides) -> Result<OptimalControlSpec, Diagnostic> {
    let text = crate::source::read_bounded(path, "problem file").map_err(Diagnostic::new)?;
    validate(SourceFile::new(path, text), overrides)
}

/// Checks the text of a problem file with `[optimal_control]` (`origin` names it).
///
/// # Errors
/// A diagnostic for the first mistake found.
pub fn from_toml_str(
    text: &str,
    origin: impl Into<PathBuf>,
    overrides: &Overrides,
) -> Result<OptimalControlSpec, Diagnostic> {
    validate(SourceFile::new(origin, text.to_owned()), overrides)
}

/// Whether problem text has an `[optimal_control]` table (`false` for text that does not
/// parse: its error comes from the validation that follows).
pub fn is_optimal_control(text: &str) -> bool {
    super::raw::parse(text).is_ok_and(|raw| raw.optimal_control.is_some())
}

/// `marsden run` of a file with `[optimal_control]`: refused, pointing at `marsden optimize`.
///
/// # Errors
/// The refusal, at the section.
pub fn refuse_in_run(ck: &Checker<'_>, raw: &RawProblem) -> Result<(), Diagnostic> {
    match &raw.optimal_control {
        None => Ok(()),
        Some(section) => Err(ck
            .error(
                Some(section.span()),
                "this file is an optimal control problem: solve it with `marsden optimize`",
            )
            .help("`marsden optimize FILE` writes the optimal trajectory, controls and summary")),
    }
}

fn validate(source: SourceFile, overrides: &Overrides) -> Result<OptimalControlSpec, Diagnostic> {
    let raw = super::raw::parse(source.text()).map_err(|e| toml_error::diagnose(&source, &e))?;
    let ck = Checker::new(&source);
    let Some(section) = &raw.optimal_control else {
        return Err(
            Diagnostic::new("the problem file has no [optimal_control] table").help(
                "add [optimal_control] with `cost`, `t_end`, `steps`, `start` and `end`; \
                   `marsden run` runs a file without it",
            ),
        );
    };
    refuse_sections(&ck, &raw)?;
    let Some(raw_system) = raw.system.as_ref() else {
        return Err(Diagnostic::new("the problem file has no [system] table"));
    };
    if let Some(file) = &raw_system.get_ref().control_table {
        return Err(ck
            .error(
                Some(file.span()),
                "`control_table` feeds the controls to `marsden run`; `marsden optimize` computes them",
            )
            .help("remove it here, or run the file without [optimal_control]"));
    }
    let system = system::system(&ck, raw.system.as_ref(), None)?;
    supported_system(&ck, raw_system, &system)?;
    let LagrangianSpec::Expression(lagrangian) = system.lagrangian else {
        return Err(ck.error(
            Some(raw_system.span()),
            "optimal control needs `lagrangian`",
        ));
    };
    let coordinates = system.coordinates;
    let expressions =
        Expressions::compile(&ck, raw_system, section, &coordinates, &system.parameters)?;
    let table = section.get_ref();
    let (t0, t_end, steps) = options::horizon(&ck, section, overrides)?;
    let method = options::method(&ck, table.method.as_ref())?;
    let start = boundary::end(&ck, "start", table.start.as_ref(), &coordinates)?;
    let end = boundary::end(&ck, "end", table.end.as_ref(), &coordinates)?;
    let names: Vec<String> = expressions
        .controls
        .iter()
        .map(|c| c.name.clone())
        .collect();
    let (control_bounds, state_bounds) = boundary::bounds(
        &ck,
        table.bounds.as_ref(),
        &names,
        &coordinates,
        &start,
        &end,
    )?;
    let guess = options::guess(&ck, table.guess.as_ref())?;
    let solver = options::solver(&ck, table)?;
    let name = raw_system.get_ref().name.as_ref().map_or_else(
        || {
            source
                .path()
                .file_stem()
                .map_or("optimize".to_owned(), |s| s.to_string_lossy().into_owned())
        },
        |n| n.get_ref().clone(),
    );
    let output = settings::output(&ck, raw.output.as_ref(), &name, overrides, &coordinates)?;
    csv_only(&ck, raw.output.as_ref())?;
    Ok(OptimalControlSpec {
        name,
        lagrangian,
        coordinates,
        controls: names,
        parameters: system.parameters,
        symmetries: system.symmetries,
        force: expressions.force,
        cost: expressions.cost,
        final_cost: expressions.final_cost,
        path: expressions.path,
        path_texts: expressions.path_texts,
        method,
        t0,
        t_end,
        steps,
        start,
        end,
        control_bounds,
        state_bounds,
        guess,
        solver,
        output,
        source,
    })
}

/// What the transcription takes: an expression Lagrangian, no constraints, forces in the
/// velocities.
fn supported_system(
    ck: &Checker<'_>,
    raw_system: &Spanned<RawSystem>,
    system: &SystemSpec,
) -> Result<(), Diagnostic> {
    let at = Some(raw_system.span());
    if !matches!(system.lagrangian, LagrangianSpec::Expression(_)) {
        return Err(ck
            .error(
                at,
                "optimal control needs `lagrangian = \"...\"` in [system]",
            )
            .note("catalog, Hamiltonian and discrete-Lagrangian systems are not supported yet"));
    }
    if !system.constraint.components().is_empty() {
        return Err(ck.error(
            at,
            "optimal control with `constraints` is not supported yet",
        ));
    }
    if system.force.inputs() == ForceInputs::Momenta {
        return Err(ck.error(
            at,
            "optimal control needs `forces` written in the velocities (not momenta `p_…`)",
        ));
    }
    Ok(())
}

/// `marsden optimize` writes every node as CSV: `format = "npy"` and `every` are refused.
fn csv_only(ck: &Checker<'_>, raw: Option<&Spanned<RawOutput>>) -> Result<(), Diagnostic> {
    let Some(table) = raw.map(Spanned::get_ref) else {
        return Ok(());
    };
    if let Some(f) = table.format.as_ref().filter(|f| f.get_ref() != "csv") {
        return Err(ck.error(
            Some(f.span()),
            "`marsden optimize` writes CSV only (trajectory.csv, controls.csv)",
        ));
    }
    if let Some(every) = &table.every {
        return Err(ck
            .error(
                Some(every.span()),
                "`every` is not used by `marsden optimize`",
            )
            .note("every node of the optimal trajectory is written"));
    }
    Ok(())
}

/// Sections `marsden optimize` has no use for are refused, not ignored.
fn refuse_sections(ck: &Checker<'_>, raw: &RawProblem) -> Result<(), Diagnostic> {
    let found = [
        raw.initial.as_ref().map(|s| ("[initial]", s.span())),
        raw.integrator.as_ref().map(|s| ("[integrator]", s.span())),
        raw.sweep.as_ref().map(|s| ("[sweep]", s.span())),
        raw.sensitivity
            .as_ref()
            .map(|s| ("[sensitivity]", s.span())),
        raw.analysis.as_ref().map(|s| ("[analysis]", s.span())),
    ];
    match found.into_iter().flatten().next() {
        None => Ok(()),
        Some((what, span)) => Err(ck
            .error(
                Some(span),
                format!("{what} is not used by an optimal control problem"),
            )
            .help(
                "give the horizon, rule and boundary data in [optimal_control] \
                   (`t_end`, `steps`, `method`, `start`, `end`)",
            )),
    }
}

/// The forces, costs and controls compiled with the controls as inputs.
struct Expressions {
    controls: Vec<Control>,
    force: ProgramSet,
    cost: Program,
    final_cost: Option<Program>,
    path: ProgramSet,
    path_texts: Vec<String>,
}

impl Expressions {
    fn compile(
        ck: &Checker<'_>,
        raw_system: &Spanned<RawSystem>,
        section: &Spanned<RawOptimalControl>,
        coordinates: &[String],
        constants: &[(String, f64)],
    ) -> Result<Self, Diagnostic> {
        let system = raw_system.get_ref();
        let params = Parameters::read(ck, system)?;
        let tangent = symbols(ck, tangent_inputs(coordinates), constants, &params)?;
        let controls = controls::declared(ck, system, &tangent)?;
        if controls.is_empty() {
            return Err(ck
                .error(
                    Some(raw_system.span()),
                    "optimal control needs `controls = [...]` in [system]",
                )
                .help("e.g. controls = [\"u\"] and forces = [\"u\"]"));
        }
        let with_u = controls::as_inputs(ck, &controls, tangent)?;
        let Some(list) = &system.forces else {
            return Err(ck
                .error(
                    Some(raw_system.span()),
                    "the controls act through `forces`, but [system] has none",
                )
                .help(format!("e.g. forces = [\"{}\"]", controls[0].name)));
        };
        let parsed = list
            .get_ref()
            .iter()
            .enumerate()
            .map(|(i, v)| ck.parse_expr(&format!("[system] forces[{i}]"), v))
            .collect::<Result<Vec<_>, _>>()?;
        controls::all_used(ck, &controls, &parsed)?;
        let force = ck.compile_all("[system] forces", list, &parsed, &with_u)?;
        let table = section.get_ref();
        let Some(cost) = &table.cost else {
            return Err(ck
                .error(
                    Some(section.span()),
                    "[optimal_control] needs a running `cost`",
                )
                .help(format!(
                    "e.g. cost = \"0.5*{}^2\" (the control effort)",
                    controls[0].name
                )));
        };
        let what = "[optimal_control] cost";
        let cost = ck
            .parse_expr(what, cost)?
            .compile(&with_u)
            .map_err(|e| ck.expr_error(what, cost, &e))?;
        let final_cost = match &table.final_cost {
            None => None,
            Some(text) => {
                let what = "[optimal_control] final_cost";
                let cotangent = symbols(ck, cotangent_inputs(coordinates), constants, &params)?;
                let program = ck
                    .parse_expr(what, text)?
                    .compile(&cotangent)
                    .map_err(|e| ck.expr_error(what, text, &e))?;
                Some(program)
            }
        };
        let PathInequalities { programs, texts } = path(ck, table.path.as_ref(), &with_u)?;
        Ok(Self {
            controls,
            force,
            cost,
            final_cost,
            path: programs,
            path_texts: texts,
        })
    }
}

/// The path inequalities, compiled and as written.
struct PathInequalities {
    programs: ProgramSet,
    texts: Vec<String>,
}

/// `path = ["g₁", …]`: each `g_i(t, q, q̇, u) ≤ 0`, compiled over the inputs of the forces.
fn path(
    ck: &Checker<'_>,
    list: Option<&SpannedList<String>>,
    with_u: &Symbols,
) -> Result<PathInequalities, Diagnostic> {
    let Some(list) = list else {
        return Ok(PathInequalities {
            programs: ProgramSet::default(),
            texts: Vec::new(),
        });
    };
    if list.get_ref().is_empty() {
        return Err(ck.error(Some(list.span()), "`path` is empty").help(
            "give each inequality g(t, q, q_dot, u) <= 0 as an expression, or remove `path`",
        ));
    }
    let parsed = (list.get_ref().iter().enumerate())
        .map(|(i, v)| ck.parse_expr(&format!("[optimal_control] path[{i}]"), v))
        .collect::<Result<Vec<_>, _>>()?;
    let programs = ck.compile_all("[optimal_control] path", list, &parsed, with_u)?;
    let texts = list.get_ref().iter().map(|v| v.get_ref().clone()).collect();
    Ok(PathInequalities { programs, texts })
}
