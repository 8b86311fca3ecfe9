//! `[system]` → [`SystemSpec`]: which Lagrangian, its coordinates and parameters, and the
//! forces, constraints and symmetries compiled against them.

use toml::Spanned;

use super::check::{Checker, count_coordinates};
use super::nbody_file::BodiesFile;
use super::parameters::{self, Parameters};
use super::raw::{RawSymmetry, RawSystem, SpannedList};
use super::resolved::{Resolved, symbols};
use super::spec::{LagrangianSpec, SystemSpec};
use crate::catalog::{Builtin, MASSES};
use crate::error::Diagnostic;
use crate::model::hamiltonian::cotangent_inputs;
use crate::model::slots::{tangent_inputs, velocity_name};
use crate::model::{
    ExprConstraint, ExprForce, ExprLagrangian, ForceInputs, MomentumMap as _, Symmetry,
};
use marsden_expr::closest;
use marsden_expr::{Expr, Program, Span, Symbols};

/// The expressions besides the Lagrangian, parsed (syntax checked) before names are resolved.
struct Parsed {
    forces: Vec<Expr>,
    constraints: Vec<Expr>,
    generators: Vec<Vec<Expr>>,
}

impl Parsed {
    fn read(ck: &Checker<'_>, system: &RawSystem) -> Result<Self, Diagnostic> {
        let list = |what: &str, l: Option<&SpannedList<String>>| -> Result<Vec<Expr>, Diagnostic> {
            l.map_or(&[][..], |l| l.get_ref().as_slice())
                .iter()
                .enumerate()
                .map(|(i, v)| ck.parse_expr(&format!("[system] {what}[{i}]"), v))
                .collect()
        };
        let mut generators = Vec::new();
        for (k, s) in symmetries(system).iter().enumerate() {
            let what = format!("symmetry {} generator", symmetry_label(s.get_ref(), k));
            generators.push(list(&what, s.get_ref().generator.as_ref())?);
        }
        Ok(Self {
            forces: list("forces", system.forces.as_ref())?,
            constraints: list("constraints", system.constraints.as_ref())?,
            generators,
        })
    }

    /// Every name the expressions use.
    fn names(&self) -> Vec<String> {
        let all = self.forces.iter().chain(&self.constraints);
        let mut names: Vec<String> = all
            .chain(self.generators.iter().flatten())
            .flat_map(|e| e.names().into_iter().map(str::to_owned))
            .collect();
        names.sort_unstable();
        names.dedup();
        names
    }
}

fn symmetries(system: &RawSystem) -> &[Spanned<RawSymmetry>] {
    system.symmetry.as_deref().unwrap_or(&[])
}

fn symmetry_label(s: &RawSymmetry, k: usize) -> String {
    s.name
        .as_ref()
        .map_or(format!("#{}", k + 1), |n| format!("`{}`", n.get_ref()))
}

/// Validates `[system]`; `bodies` are the masses of an `[initial] file` (N-body only).
pub fn system(
    ck: &Checker<'_>,
    raw: Option<&Spanned<RawSystem>>,
    bodies: Option<&BodiesFile>,
) -> Result<SystemSpec, Diagnostic> {
    let Some(raw) = raw else {
        return Err(Diagnostic::new("the problem file has no [system] table").help(
            "add [system] with `builtin = \"pendulum\"`, or with `coordinates` and `lagrangian`",
        ));
    };
    let system = raw.get_ref();
    if let Some(h) = &system.hamiltonian
        && (system.lagrangian.is_some() || system.builtin.is_some())
    {
        return Err(ck.error(
            Some(h.span()),
            "give either `hamiltonian` or `lagrangian`/`builtin`, not both",
        ));
    }
    if let Some(ld) = &system.discrete_lagrangian {
        let other = [
            ("lagrangian", &system.lagrangian),
            ("builtin", &system.builtin),
            ("hamiltonian", &system.hamiltonian),
        ];
        if let Some((key, _)) = other.iter().find(|(_, v)| v.is_some()) {
            return Err(ck
                .error(
                    Some(ld.span()),
                    format!("give either `discrete_lagrangian` or `{key}`, not both"),
                )
                .note("`discrete_lagrangian` is the method itself: no continuous L goes with it"));
        }
    }
    if super::multibody::is_multibody(system) {
        let spec = super::multibody::system(ck, system)?;
        return Ok(SystemSpec {
            coordinates: spec.centre_names(),
            parameters: spec.parameters.clone(),
            lagrangian: LagrangianSpec::Multibody(Box::new(spec)),
            masses: None,
            force: crate::model::ExprForce::none(),
            constraint: crate::model::ExprConstraint::none(),
            symmetries: Vec::new(),
        });
    }
    let mut params = Parameters::read(ck, system)?;
    if let Some(body) = &system.rigid_body {
        let resolved = super::rigid::system(ck, system, body, &params)?;
        return Ok(rigid_system(resolved));
    }
    if let Some(name) = &system.builtin
        && let Some(entry) = super::rigid_catalog::rigid_builtin(name.get_ref())
    {
        let resolved = super::rigid_catalog::system(ck, system, name, entry, &params)?;
        return Ok(rigid_system(resolved));
    }
    if let Some(body_rotation) =
        (symmetries(system).iter()).find_map(|s| s.get_ref().body_rotation.as_ref())
    {
        return Err(ck
            .error(
                Some(body_rotation.span()),
                "`body_rotation` applies to a rigid body",
            )
            .help("declare the body with `rigid_body = { inertia = [J1, J2, J3] }`"));
    }
    if let Some(bodies) = bodies {
        file_masses(ck, system, &mut params, bodies)?;
    }
    let parsed = Parsed::read(ck, system)?;
    let Resolved {
        lagrangian,
        coordinates,
        parameters: constants,
        masses,
    } = match (&system.lagrangian, &system.builtin) {
        (Some(_), Some(b)) => {
            return Err(ck.error(
                Some(b.span()),
                "give either `lagrangian` or `builtin`, not both",
            ));
        }
        (None, None) => match (&system.hamiltonian, &system.discrete_lagrangian) {
            (Some(h), _) => super::hamiltonian::expression(ck, h, system, &params)?,
            (None, Some(ld)) => super::discrete::expression(ck, ld, system, &params)?,
            (None, None) => {
                return Err(ck
                    .error(
                        Some(raw.span()),
                        "[system] needs a `lagrangian` or a `builtin`",
                    )
                    .help("e.g. `builtin = \"pendulum\"`; `marsden systems` lists the builtins"));
            }
        },
        (None, Some(b)) => builtin(ck, b, system, &params, &parsed.names())?,
        (Some(l), None) => expression(ck, l, system, &params)?,
    };
    // The forces see `[system] controls` as 0 (a `marsden run` is the zero-control simulation)
    // or, with a `control_table`, as inputs after `[q, q̇, t]` read from the table.
    let zero = |s| super::optimal_control::controls::for_run(ck, system, s);
    let tangent = zero(symbols(
        ck,
        tangent_inputs(&coordinates),
        &constants,
        &params,
    )?)?;
    let positions = symbols(ck, coordinates.clone(), &constants, &params)?;
    let cotangent = || {
        zero(symbols(
            ck,
            cotangent_inputs(&coordinates),
            &constants,
            &params,
        )?)
    };
    let force = forces(ck, system, &parsed, &coordinates, &tangent, &cotangent)?;
    let constraint = constraints(ck, system, &parsed, &coordinates, &positions)?;
    let symmetries = compile_symmetries(ck, system, &parsed, &coordinates, &positions)?;
    Ok(SystemSpec {
        lagrangian,
        coordinates,
        parameters: constants,
        masses,
        force,
        constraint,
        symmetries,
    })
}

/// A rigid body's `[system]` ([`super::rigid`]): no coordinates but its centre of mass's.
fn rigid_system(resolved: Resolved) -> SystemSpec {
    let Resolved {
        lagrangian,
        coordinates,
        parameters,
        masses,
    } = resolved;
    SystemSpec {
        lagrangian,
        coordinates,
        parameters,
        masses,
        force: crate::model::ExprForce::none(),
        constraint: crate::model::ExprConstraint::none(),
        symmetries: Vec::new(),
    }
}

/// The masses of an `[initial] file` become the `masses` parameter of `builtin = "nbody"`.
fn file_masses(
    ck: &Checker<'_>,
    system: &RawSystem,
    params: &mut Parameters,
    bodies: &BodiesFile,
) -> Result<(), Diagnostic> {
    let builtin = system.builtin.as_ref().map(|b| b.get_ref().as_str());
    if builtin != Some(Builtin::NBody.name()) {
        return Err(ck
            .error(
                Some(bodies.span.clone()),
                "`[initial] file` holds N-body data: it needs `builtin = \"nbody\"`",
            )
            .help("for other systems give `q = [...]` and `v = [...]` (or `p`)"));
    }
    if let Some((_, _, span)) = params.lists.iter().find(|(name, ..)| name == MASSES) {
        return Err(ck
            .error(
                Some(span.clone()),
                "the masses are given twice: in `parameters` and in `[initial] file`",
            )
            .help("remove `masses` from `parameters`: the file's masses are used"));
    }
    let masses = bodies.data.masses.clone();
    params
        .lists
        .push((MASSES.to_owned(), masses, bodies.span.clone()));
    Ok(())
}

fn builtin(
    ck: &Checker<'_>,
    name: &Spanned<String>,
    system: &RawSystem,
    params: &Parameters,
    used: &[String],
) -> Result<Resolved, Diagnostic> {
    let Some(b) = Builtin::from_name(name.get_ref()) else {
        let rigid = super::rigid_catalog::RIGID_BUILTINS.iter().map(|b| b.name);
        let names: Vec<&str> = Builtin::ALL.iter().map(|b| b.name()).chain(rigid).collect();
        return Err(ck
            .error(
                Some(name.span()),
                format!("unknown builtin `{}`", name.get_ref()),
            )
            .suggest(closest(name.get_ref(), names.iter().copied()))
            .note(format!("builtins: {}", names.join(", ")))
            .note("`marsden systems` lists them with their coordinates and parameters"));
    };
    let resolved = parameters::resolve_builtin(ck, (b, name.span()), params, used)?;
    let bodies = resolved.masses.len();
    let coordinates = parameters::builtin_coordinates(ck, b, bodies, system.coordinates.as_ref())?;
    let masses = b.needs_masses().then(|| resolved.masses.clone());
    let built = b.build(&resolved.values, resolved.masses);
    let spec = LagrangianSpec::Builtin {
        builtin: b,
        system: built,
    };
    Ok(Resolved {
        lagrangian: spec,
        coordinates,
        parameters: resolved.all,
        masses,
    })
}

fn expression(
    ck: &Checker<'_>,
    text: &Spanned<String>,
    system: &RawSystem,
    params: &Parameters,
) -> Result<Resolved, Diagnostic> {
    let help = "e.g. `coordinates = [\"theta\"]`; velocities are then named `theta_dot`";
    let coordinates = parameters::expression_coordinates(ck, "lagrangian", text, system, help)?;
    params.numbers_only(ck, "an expression Lagrangian")?;
    let constants: Vec<(String, f64)> = params
        .numbers
        .iter()
        .map(|w| (w.name.clone(), w.value))
        .collect();
    let expr = ck.parse_expr("[system] lagrangian", text)?;
    let symbols = symbols(ck, tangent_inputs(&coordinates), &constants, params)?;
    let program: Program = expr
        .compile(&symbols)
        .map_err(|e| ck.expr_error("[system] lagrangian", text, &e))?;
    let l = ExprLagrangian::new(program, coordinates.len());
    let l = LagrangianSpec::Expression(l);
    Ok(Resolved::expression(l, coordinates, constants))
}

fn forces(
    ck: &Checker<'_>,
    system: &RawSystem,
    parsed: &Parsed,
    coordinates: &[String],
    tangent: &Symbols,
    cotangent: &dyn Fn() -> Result<Symbols, Diagnostic>,
) -> Result<ExprForce, Diagnostic> {
    let Some(list) = &system.forces else {
        return Ok(ExprForce::none());
    };
    ck.one_per_coordinate("`forces`", list, coordinates)?;
    let what = "[system] forces";
    match force_inputs(ck, list, &parsed.forces, coordinates, tangent)? {
        ForceInputs::Velocities => {
            let set = ck.compile_all(what, list, &parsed.forces, tangent)?;
            Ok(ExprForce::new(set))
        }
        ForceInputs::Momenta => {
            let set = ck.compile_all(what, list, &parsed.forces, &cotangent()?)?;
            Ok(ExprForce::with_inputs(set, ForceInputs::Momenta))
        }
    }
}

/// Whether the forces are written in the momenta (`f_H`, some name `p_…` that is not a
/// coordinate, velocity or parameter) or in the velocities (`f_L`); both at once is refused
/// at the second kind's first use.
fn force_inputs(
    ck: &Checker<'_>,
    list: &SpannedList<String>,
    parsed: &[Expr],
    coordinates: &[String],
    tangent: &Symbols,
) -> Result<ForceInputs, Diagnostic> {
    let known: Vec<&str> = tangent.names().collect();
    let velocities: Vec<String> = coordinates.iter().map(|c| velocity_name(c)).collect();
    let (mut momentum, mut velocity) = (None, None);
    for (i, expr) in parsed.iter().enumerate() {
        for id in expr.identifiers() {
            if id.name.starts_with("p_") && !known.contains(&id.name) {
                momentum.get_or_insert((i, id.name, id.span));
            } else if velocities.iter().any(|v| v == id.name) {
                velocity.get_or_insert((i, id.name, id.span));
            }
        }
    }
    match (momentum, velocity) {
        (None, _) => Ok(ForceInputs::Velocities),
        (Some(_), None) => Ok(ForceInputs::Momenta),
        (Some((_, p, _)), Some((i, v, span))) => {
            let msg = format!(
                "the forces use both the velocity `{v}` and the momentum `{p}`: write them all in \
                 velocities (f_L) or all in momenta (f_H, run as f_H ∘ FL)"
            );
            let e = parsed[i].error_at(span, msg, None);
            let value = &list.get_ref()[i];
            Err(ck.expr_error(&format!("[system] forces[{i}]"), value, &e))
        }
    }
}

fn constraints(
    ck: &Checker<'_>,
    system: &RawSystem,
    parsed: &Parsed,
    coordinates: &[String],
    symbols: &Symbols,
) -> Result<ExprConstraint, Diagnostic> {
    let Some(list) = &system.constraints else {
        return Ok(ExprConstraint::none());
    };
    let d = list.get_ref().len();
    if d >= coordinates.len() {
        let msg = format!(
            "{d} constraint(s) on {} leave no freedom to move",
            count_coordinates(coordinates)
        );
        return Err(ck.error(Some(list.span()), msg));
    }
    let what = "[system] constraints";
    positions_only(
        ck,
        what,
        list,
        &parsed.constraints,
        coordinates,
        "holonomic constraints φ(q)",
    )?;
    on_the_coordinates(ck, what, list, &parsed.constraints, coordinates)?;
    let set = ck.compile_all(what, list, &parsed.constraints, symbols)?;
    Ok(ExprConstraint::new(set))
}

/// Rejects a constraint in which no coordinate appears (`"0"`, `"1"`, `"g - 9.81"`): `φ` is
/// then a constant, which holds everywhere or nowhere, and `Dφ = 0` has no rank to impose.
fn on_the_coordinates(
    ck: &Checker<'_>,
    context: &str,
    list: &SpannedList<String>,
    parsed: &[Expr],
    coordinates: &[String],
) -> Result<(), Diagnostic> {
    for (i, (expr, value)) in parsed.iter().zip(list.get_ref()).enumerate() {
        let names = expr.names();
        if names.iter().any(|n| coordinates.iter().any(|c| c == n)) {
            continue;
        }
        let msg = format!(
            "constraint {i} does not depend on the coordinates: φ_{i}(q) = {} is a constant, \
             which holds everywhere or nowhere (Dφ_{i} = 0)",
            expr.text().trim()
        );
        let help = format!(
            "write φ(q) = 0 in the coordinates ({}), e.g. \"x^2 + y^2 - 1\" for a circle",
            coordinates.join(", ")
        );
        let e = expr.error_at(Span::new(0, expr.text().len()), msg, Some(help));
        return Err(ck.expr_error(&format!("{context}[{i}]"), value, &e));
    }
    Ok(())
}

/// Rejects velocities and `t` in expressions of the coordinates only, with a precise message.
fn positions_only(
    ck: &Checker<'_>,
    context: &str,
    list: &SpannedList<String>,
    parsed: &[Expr],
    coordinates: &[String],
    what: &str,
) -> Result<(), Diagnostic> {
    for (i, (expr, value)) in parsed.iter().zip(list.get_ref()).enumerate() {
        for id in expr.identifiers() {
            let velocity = coordinates.iter().any(|c| velocity_name(c) == id.name);
            if velocity || id.name == "t" {
                let msg = format!(
                    "{what} depend on the coordinates only, not on `{}`",
                    id.name
                );
                let e = expr.error_at(id.span, msg, None);
                return Err(ck.expr_error(&format!("{context}[{i}]"), value, &e));
            }
        }
    }
    Ok(())
}

fn compile_symmetries(
    ck: &Checker<'_>,
    system: &RawSystem,
    parsed: &Parsed,
    coordinates: &[String],
    symbols: &Symbols,
) -> Result<Vec<Symmetry>, Diagnostic> {
    let mut out: Vec<Symmetry> = Vec::new();
    for (k, (raw, exprs)) in symmetries(system)
        .iter()
        .zip(&parsed.generators)
        .enumerate()
    {
        let s = raw.get_ref();
        let named = super::named_symmetry::expand(ck, raw, coordinates)?;
        let (label, span) = match (&s.name, &named) {
            (Some(name), _) => (name.get_ref(), name.span()),
            (None, Some(n)) => (&n.default_name, n.span.clone()),
            (None, None) => {
                return Err(ck.error(
                    Some(raw.span()),
                    format!("symmetry #{} has no `name`", k + 1),
                ));
            }
        };
        if !marsden_expr::is_identifier(label) || out.iter().any(|o| o.name() == label) {
            let msg = format!(
                "symmetry name `{label}` must be unique and made of letters, digits and '_' (its column is J_{label})"
            );
            return Err(ck.error(Some(span), msg));
        }
        if let Some(n) = &named {
            out.push(n.compile(ck, label.clone(), symbols)?);
            continue;
        }
        let Some(list) = &s.generator else {
            return Err(ck
                .error(
                    Some(raw.span()),
                    format!("symmetry `{label}` has no `generator`"),
                )
                .help("give `generator = [...]`, or name it: `translation = \"x\"`, `rotation = \"z\"`"));
        };
        ck.one_per_coordinate(&format!("the generator of `{label}`"), list, coordinates)?;
        let context = format!("symmetry `{label}` generator");
        positions_only(ck, &context, list, exprs, coordinates, "generators ξ_Q(q)")?;
        out.push(Symmetry::new(
            label.clone(),
            ck.compile_all(&context, list, exprs, symbols)?,
        ));
    }
    Ok(out)
}
