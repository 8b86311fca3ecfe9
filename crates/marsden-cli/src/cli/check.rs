//! `marsden check FILE`: validates the problem file and prints the problem as it will run,
//! defaults filled in and the initial state completed.

use std::fmt::Write as _;

use super::FileArgs;
use crate::error::{CliError, Status};
use crate::model::MomentumMap as _;
use crate::problem::{self, InitialData, LagrangianSpec, RunSpec};
use crate::run::{output, start};

/// Validates and prints; status 2 on the first mistake.
pub fn check(args: &FileArgs) -> Result<Status, CliError> {
    let spec = problem::load(&args.file, &args.overrides())?;
    let start = start::prepare(&spec)?;
    print!("{}", render(&spec, &start));
    Ok(Status::Completed)
}

/// The resolved problem, one labelled line per fact.
pub fn render(spec: &RunSpec, start: &start::Start) -> String {
    let mut out = String::new();
    let mut line = |label: &str, text: String| {
        let _ = writeln!(out, "{label:<13}{text}");
    };
    line(
        "problem",
        format!(
            "{} (sha256 {})",
            spec.source.path().display(),
            spec.source.sha256()
        ),
    );
    let s = &spec.system;
    match &s.lagrangian {
        LagrangianSpec::Builtin { builtin, .. } => {
            line(
                "system",
                format!("{}: builtin {}", spec.name, builtin.name()),
            );
            line("lagrangian", builtin.formula().to_owned());
        }
        LagrangianSpec::Expression(l) => {
            line("system", format!("{}: expression Lagrangian", spec.name));
            let ops = l.program().op_count();
            line(
                "lagrangian",
                format!("{} ({ops} instructions)", l.program().text()),
            );
        }
    }
    line("coordinates", s.coordinates.join(", "));
    let params: Vec<String> = s
        .parameters
        .iter()
        .map(|(n, v)| format!("{n} = {v}"))
        .collect();
    let mut params = params.join(", ");
    if let Some(m) = &s.masses {
        params = format!("masses = {m:?}, {params}");
    }
    line(
        "parameters",
        if params.is_empty() {
            "none".into()
        } else {
            params
        },
    );
    let listed = |set: &crate::expr::ProgramSet| -> Vec<String> {
        set.programs().iter().map(|p| p.text().to_owned()).collect()
    };
    let forces = listed(s.force.components());
    line(
        "forces",
        if forces.is_empty() {
            "none".into()
        } else {
            forces.join(", ")
        },
    );
    let constraints = listed(s.constraint.components());
    let constraints = if constraints.is_empty() {
        "none".to_owned()
    } else {
        format!(
            "{} = 0 (SHAKE; momenta not projected yet)",
            constraints.join(" = 0, ")
        )
    };
    line("constraints", constraints);
    for sym in &s.symmetries {
        let xi = listed(sym.generator()).join(", ");
        line(
            "symmetry",
            format!("{}: ξ_Q(q) = ({xi}), J = ⟨p, ξ_Q(q)⟩", sym.name()),
        );
    }
    let given = match &spec.initial.data {
        InitialData::Velocity(_) => "v given, p = ∂L/∂q̇",
        InitialData::Momentum(_) => "p given, v by the inverse Legendre transform",
    };
    line("initial", format!("t0 = {}, q = {:?}", start.t, start.q));
    line(
        "",
        format!("v = {:?}, p = {:?} ({given})", start.v, start.p),
    );
    line("", format!("energy E0 = {}", start.energy));
    let i = &spec.integrator;
    let length = match i.t_end {
        Some(t_end) => format!("t_end = {t_end} → {} steps", i.grid.steps),
        None => format!("{} steps", i.grid.steps),
    };
    line(
        "integrator",
        format!(
            "{} (order {}), h = {}, {length}, t = {} → {}",
            i.method,
            i.method.order(),
            i.grid.h,
            i.grid.t0,
            i.grid.t_end()
        ),
    );
    line(
        "",
        format!(
            "Newton: residual tolerance {:e}, at most {} iterations per step",
            i.newton.residual_tolerance, i.newton.max_iterations
        ),
    );
    let o = &spec.output;
    let plots = if o.plots { "plots" } else { "no plots" };
    line(
        "output",
        format!(
            "{}, {}, every {} step(s), {plots}",
            o.dir.display(),
            o.format.name(),
            o.every
        ),
    );
    if let Ok(layout) = output::layout(s) {
        line("", format!("columns: {}", layout.column_names().join(", ")));
    }
    out.push_str("ok: the problem file is valid\n");
    out
}
