//! The text of `marsden check`: the problem as it will run, one labelled line per fact,
//! defaults filled in and the initial state completed.
//!
//! ```text
//! problem      examples/pendulum.toml (sha256 …)
//! system       pendulum: builtin pendulum
//! lagrangian   0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)
//! …
//! ok: the problem file is valid
//! ```

use std::fmt::Write as _;

use marsden_expr::ProgramSet;

use crate::model::MomentumMap as _;
use crate::problem::method::order_text;
use crate::problem::{InitialData, LagrangianSpec, RunSpec};
use crate::run::output;
use crate::run::start::Start;

/// Labelled lines: `label` padded to a column, then the text.
#[derive(Default)]
struct Lines(String);

impl Lines {
    fn line(&mut self, label: &str, text: impl AsRef<str>) {
        let _ = writeln!(self.0, "{label:<13}{}", text.as_ref());
    }
}

/// The resolved problem, one labelled line per fact.
pub fn render(spec: &RunSpec, start: &Start) -> String {
    let mut out = Lines::default();
    let (path, hash) = (spec.source.path().display(), spec.source.sha256());
    out.line("problem", format!("{path} (sha256 {hash})"));
    system(&mut out, spec);
    initial(&mut out, spec, start);
    integrator(&mut out, spec);
    output(&mut out, spec);
    sweep(&mut out, spec);
    out.0.push_str("ok: the problem file is valid\n");
    out.0
}

/// The `[sweep]`: what varies, how many members, the first and last values (nothing without
/// one).
fn sweep(out: &mut Lines, spec: &RunSpec) {
    let Some(sweep) = &spec.sweep else { return };
    let count = sweep.count();
    let first = sweep.values_of(0);
    let last = sweep.values_of(count.saturating_sub(1));
    let show = |values: &[f64]| {
        let items: Vec<String> = values.iter().map(|v| v.to_string()).collect();
        items.join(", ")
    };
    out.line(
        "sweep",
        format!(
            "{} members over {}: first ({}), last ({}); the run is the sweep (one row per \
             member)",
            count,
            sweep.label(),
            show(&first),
            show(&last)
        ),
    );
}

fn texts(set: &ProgramSet) -> Vec<String> {
    set.programs().iter().map(|p| p.text().to_owned()).collect()
}

fn or_none(items: Vec<String>, separator: &str) -> String {
    if items.is_empty() {
        "none".to_owned()
    } else {
        items.join(separator)
    }
}

fn system(out: &mut Lines, spec: &RunSpec) {
    let s = &spec.system;
    match &s.lagrangian {
        LagrangianSpec::Builtin { builtin, .. } => {
            out.line(
                "system",
                format!("{}: builtin {}", spec.name, builtin.name()),
            );
            out.line("lagrangian", builtin.formula());
        }
        LagrangianSpec::Expression(l) => {
            let program = l.program();
            out.line("system", format!("{}: expression Lagrangian", spec.name));
            out.line(
                "lagrangian",
                format!("{} ({} instructions)", program.text(), program.op_count()),
            );
        }
        LagrangianSpec::Hamiltonian(h) => {
            let program = h.general.hamiltonian.program();
            out.line("system", format!("{}: expression Hamiltonian", spec.name));
            let run_as = match h.separable {
                Some(_) => "separable: run as L = ½vᵀK⁻¹v − V(q) (the separable fast path)",
                None => "run as L = ⟨p, v⟩ − H at ∂H/∂p = v",
            };
            out.line(
                "hamiltonian",
                format!(
                    "{} ({} instructions), {run_as}",
                    program.text(),
                    program.op_count()
                ),
            );
        }
        LagrangianSpec::Discrete(ld) => {
            let program = ld.program();
            out.line("system", format!("{}: discrete Lagrangian", spec.name));
            out.line(
                "discrete_lagrangian",
                format!(
                    "{} ({} instructions), stepped by p_k = −D₁L_d, p_k+1 = D₂L_d",
                    program.text(),
                    program.op_count()
                ),
            );
        }
        LagrangianSpec::Rigid(body) => {
            out.line("system", format!("{}: rigid body", spec.name));
            out.line("lagrangian", spec.system.lagrangian.describe());
            let j = body.inertia.tensor();
            out.line(
                "inertia",
                format!(
                    "[[{}, {}, {}], [{}, {}, {}], [{}, {}, {}]], stepped by the Lie group \
                     variational integrator on SO(3){}",
                    j[(0, 0)],
                    j[(0, 1)],
                    j[(0, 2)],
                    j[(1, 0)],
                    j[(1, 1)],
                    j[(1, 2)],
                    j[(2, 0)],
                    j[(2, 1)],
                    j[(2, 2)],
                    if body.mass.is_some() { " × ℝ³" } else { "" }
                ),
            );
            if let Some(m) = body.mass {
                out.line("mass", m.to_string());
            }
        }
        LagrangianSpec::Multibody(m) => {
            out.line("system", format!("{}: multibody", spec.name));
            out.line("lagrangian", spec.system.lagrangian.describe());
            for b in &m.bodies {
                let j = b.inertia.principal_moments();
                out.line(
                    "body",
                    format!(
                        "{}: mass {}, principal moments [{}, {}, {}], on SO(3) × ℝ³",
                        b.name, b.mass, j[0], j[1], j[2]
                    ),
                );
            }
            for j in &m.joints {
                let side = |s: Option<usize>| s.map_or("ground", |b| m.bodies[b].name.as_str());
                out.line(
                    "joint",
                    format!(
                        "{}: {} between {} and {} ({} rows, stepped by SHAKE on the joints and a RATTLE projection of the momenta)",
                        j.name,
                        j.kind.name(),
                        side(j.bodies[0]),
                        side(j.bodies[1]),
                        j.kind.rows()
                    ),
                );
            }
        }
    }
    out.line("coordinates", s.coordinates.join(", "));
    let mut params: Vec<String> = s
        .parameters
        .iter()
        .map(|(n, v)| format!("{n} = {v}"))
        .collect();
    if let Some(m) = &s.masses {
        params.insert(0, format!("masses = {m:?}"));
    }
    out.line("parameters", or_none(params, ", "));
    out.line("forces", or_none(texts(s.force.components()), ", "));
    let mut constraints = or_none(texts(s.constraint.components()), " = 0, ");
    if constraints != "none" {
        constraints.push_str(
            " = 0 (SHAKE on the positions at the step end and at every stage, RATTLE \
             projection of the momenta onto T*N)",
        );
    }
    out.line("constraints", constraints);
    for sym in &s.symmetries {
        let xi = texts(sym.generator()).join(", ");
        out.line(
            "symmetry",
            format!("{}: ξ_Q(q) = ({xi}), J = ⟨p, ξ_Q(q)⟩", sym.name()),
        );
    }
}

fn initial(out: &mut Lines, spec: &RunSpec, start: &Start) {
    let given = match &spec.initial.data {
        InitialData::Velocity(_) => "v given, p = ∂L/∂q̇",
        InitialData::Momentum(_) => "p given, v by the inverse Legendre transform",
    };
    out.line("initial", format!("t0 = {}, q = {:?}", start.t, start.q));
    if !spec.system.has_energy() {
        out.line(
            "",
            format!("p = {:?} (given); v and energy: none without L", start.p),
        );
        return;
    }
    out.line(
        "",
        format!("v = {:?}, p = {:?} ({given})", start.v, start.p),
    );
    out.line("", format!("energy E0 = {}", start.energy));
}

fn integrator(out: &mut Lines, spec: &RunSpec) {
    let i = &spec.integrator;
    let g = &i.grid;
    let length = match i.t_end {
        Some(t_end) => format!("t_end = {t_end} → {} steps", g.steps),
        None => format!("{} steps", g.steps),
    };
    let (method, order) = (spec.method_name(), order_text(spec.method_order()));
    let span = format!("t = {} → {}", g.t0, g.t_end());
    let order = match spec.system.has_energy() {
        true => format!(" ({order})"),
        false => String::new(),
    };
    out.line(
        "integrator",
        format!("{method}{order}, h = {}, {length}, {span}", g.h),
    );

    let (tol, max) = (i.newton.residual_tolerance, i.newton.max_iterations);
    out.line(
        "",
        format!("Newton: residual tolerance {tol:e}, at most {max} iterations per step"),
    );
}

fn output(out: &mut Lines, spec: &RunSpec) {
    let o = &spec.output;
    let plots = if o.plots { "plots" } else { "no plots" };
    let (dir, format) = (o.dir.display(), o.format.name());
    out.line(
        "output",
        format!("{dir}, {format}, every {} step(s), {plots}", o.every),
    );
    if let Ok(layout) = output::layout(&spec.system) {
        out.line("", format!("columns: {}", layout.column_names().join(", ")));
    }
}
