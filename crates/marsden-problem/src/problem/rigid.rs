//! `[system] rigid_body`: a rigid body whose configuration is its attitude `R ∈ SO(3)` (body →
//! space) and, with a `mass`, its centre of mass `x ∈ ℝ³` — stepped by the Lie group
//! variational integrator of the core (`marsden::lie`), not by coordinates.
//!
//! ```toml
//! [system]
//! rigid_body = { inertia = [5.0, 5.0, 1.0] }   # or a symmetric 3×3 matrix; `mass = m` adds x
//! parameters = { mgl = 20.0 }
//! potential = "mgl*R33"                        # U in R11 … R33, x, y, z, t, parameters
//! torques = ["0", "0", "0"]                    # body-frame torque (optional)
//! [[system.symmetry]]
//! rotation = "z"                               # in space: J = e_z·(RΠ + x × p); or body_rotation
//! [initial]
//! rotation_vector = [0.05, 0.0, 0.0]           # or R = [[…], […], […]] or quaternion = [w, x, y, z]
//! Omega = [0.0, 0.0, 50.0]                     # body angular velocity, or Pi = [...]
//! [integrator]
//! method = "trapezoid"                         # the LGVI; or a composition of it
//! ```

use std::ops::Range;

use marsden::lie::body::{Inertia, Moments};
use marsden_expr::{ProgramSet, Symbols};
use toml::Spanned;

use super::check::Checker;
use super::parameters::Parameters;
use super::raw::{RawInertia, RawRigidBody, RawSymmetry, RawSystem};
use super::resolved::{Resolved, symbols};
use super::spec::LagrangianSpec;
use crate::error::Diagnostic;
use crate::model::rigid::{ExprRigidLoads, ExprRigidPotential, INPUTS};

/// The coordinates of a body with a mass: its centre of mass (columns `q_x`, … `p_z`).
pub const CENTRE: [&str; 3] = ["x", "y", "z"];

/// What a momentum map of a rigid body is the momentum of.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RigidAction {
    /// Rotations in space about axis `a` (left action): `J = e_a·(RΠ + x × p)`.
    Space(usize),
    /// Rotations about body axis `a` (right action): `J = Π_a`.
    Body(usize),
    /// Translations along axis `a` (a body with a mass): `J = p_a`.
    Translation(usize),
}

/// A declared symmetry of a rigid body, with the name of its column `J_<name>`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RigidSymmetry {
    /// The momentum map's name.
    pub name: String,
    /// The action.
    pub action: RigidAction,
}

impl RigidSymmetry {
    /// `J` at the attitude `r` (row-major), body momentum `pi`, centre `x` and momentum `p`.
    pub fn value(&self, r: &[f64], pi: &[f64], x: &[f64], p: &[f64]) -> f64 {
        match self.action {
            RigidAction::Space(a) => {
                let row = &r[3 * a..3 * a + 3];
                let spin = row[0] * pi[0] + row[1] * pi[1] + row[2] * pi[2];
                let (b, c) = ((a + 1) % 3, (a + 2) % 3);
                spin + x[b] * p[c] - x[c] * p[b]
            }
            RigidAction::Body(a) => pi[a],
            RigidAction::Translation(a) => p[a],
        }
    }
}

/// `[system]` of a rigid body, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct RigidSpec {
    /// The inertia about the fixed point (or the centre of mass of a body with a mass).
    pub inertia: Inertia,
    /// The mass of a free body (`None`: it turns about a fixed point).
    pub mass: Option<f64>,
    /// `U(R, x, t)`.
    pub potential: ExprRigidPotential,
    /// External torque and force.
    pub loads: ExprRigidLoads,
    /// Declared symmetries.
    pub symmetries: Vec<RigidSymmetry>,
}

impl RigidSpec {
    /// The names of the momentum maps, in the file's order.
    pub fn momentum_names(&self) -> Vec<String> {
        self.symmetries.iter().map(|s| s.name.clone()).collect()
    }
}

/// The initial attitude and body momentum of a rigid body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidInitial {
    /// `R₀`, row-major, orthonormal to round-off.
    pub attitude: [f64; 9],
    /// `Π₀` (body frame).
    pub momentum: [f64; 3],
}

/// Validates the `[system]` of a rigid body.
///
/// # Errors
/// A key that does not apply, an invalid inertia or mass, an expression naming an unknown
/// symbol, a symmetry that a rigid body does not have.
pub(super) fn system(
    ck: &Checker<'_>,
    system: &RawSystem,
    body: &Spanned<RawRigidBody>,
    params: &Parameters,
) -> Result<Resolved, Diagnostic> {
    refuse_coordinate_keys(ck, system, true)?;
    params.numbers_only(ck, "a rigid body")?;
    let raw = body.get_ref();
    let mass = match &raw.mass {
        None => None,
        Some(m) => match ck.finite("rigid_body.mass", m)? {
            m if m > 0.0 => Some(m),
            m => {
                return Err(ck.error(
                    Some(m_span(raw)),
                    format!("the mass must be positive, not {m}"),
                ));
            }
        },
    };
    let constants: Vec<(String, f64)> = (params.numbers.iter())
        .map(|w| (w.name.clone(), w.value))
        .collect();
    let parts = Parts {
        inertia: inertia(ck, body)?,
        mass,
        potential: system.potential.as_ref().map(Potential::Written),
        constants,
    };
    assemble(ck, system, parts, params)
}

/// Where a rigid body's potential comes from.
pub(super) enum Potential<'a> {
    /// `potential = "…"` in the file.
    Written(&'a Spanned<String>),
    /// A catalog entry's formula.
    Catalog(&'a str),
}

/// The parts of a rigid body's `[system]` read so far.
pub(super) struct Parts<'a> {
    /// The validated inertia.
    pub inertia: Inertia,
    /// The mass of a free body.
    pub mass: Option<f64>,
    /// The potential's text, if any.
    pub potential: Option<Potential<'a>>,
    /// Every parameter with its value (the symbols of the expressions).
    pub constants: Vec<(String, f64)>,
}

/// The body from its parts and the file's `torques`, `forces` and symmetries.
///
/// # Errors
/// An expression naming an unknown symbol (or `x`, `y`, `z` without a mass), forces without
/// a mass, a symmetry the body cannot have.
pub(super) fn assemble(
    ck: &Checker<'_>,
    system: &RawSystem,
    parts: Parts<'_>,
    params: &Parameters,
) -> Result<Resolved, Diagnostic> {
    let Parts {
        inertia,
        mass,
        potential,
        constants,
    } = parts;
    let inputs: Vec<String> = INPUTS.iter().map(|s| (*s).to_owned()).collect();
    let symbols = symbols(ck, inputs, &constants, params)?;
    let potential = match potential {
        None => ExprRigidPotential::new(None),
        Some(Potential::Written(text)) => {
            let expr = ck.parse_expr("[system] potential", text)?;
            let program = expr
                .compile(&symbols)
                .map_err(|e| ck.expr_error("[system] potential", text, &e))?;
            if mass.is_none() {
                no_centre(ck, "potential", text.span(), program.inputs_used())?;
            }
            ExprRigidPotential::new(Some(program))
        }
        Some(Potential::Catalog(text)) => {
            let program = marsden_expr::Program::compile(text, &symbols).map_err(|e| {
                Diagnostic::new(format!(
                    "internal error: the catalog's potential `{text}`: {e}"
                ))
            })?;
            ExprRigidPotential::new(Some(program))
        }
    };
    let three = |key: &str, list: Option<&super::raw::SpannedList<String>>| {
        list.map(|l| vector_of_three(ck, key, l, &symbols, mass.is_some()))
            .transpose()
    };
    let torques = three("torques", system.torques.as_ref())?;
    let forces = match (&system.forces, mass) {
        (Some(f), None) => {
            return Err(ck
                .error(
                    Some(f.span()),
                    "`forces` act on the centre of mass of a body with a `mass`",
                )
                .help("a body turning about a fixed point takes `torques` (body frame)"));
        }
        (f, _) => three("forces", f.as_ref())?,
    };
    let symmetries = rigid_symmetries(ck, system, mass.is_some())?;
    let coordinates = match mass {
        Some(_) => CENTRE.iter().map(|c| (*c).to_owned()).collect(),
        None => Vec::new(),
    };
    let spec = RigidSpec {
        inertia,
        mass,
        potential,
        loads: ExprRigidLoads { torques, forces },
        symmetries,
    };
    Ok(Resolved::expression(
        LagrangianSpec::Rigid(Box::new(spec)),
        coordinates,
        constants,
    ))
}

fn m_span(raw: &RawRigidBody) -> Range<usize> {
    raw.mass.as_ref().map_or(0..0, Spanned::span)
}

/// The keys of a system in coordinates, which a rigid body does not take (`builtin` too, unless
/// the body is a catalog entry).
pub(super) fn refuse_coordinate_keys(
    ck: &Checker<'_>,
    system: &RawSystem,
    with_builtin: bool,
) -> Result<(), Diagnostic> {
    let builtin = system.builtin.as_ref().filter(|_| with_builtin);
    let keys = [
        (
            "coordinates",
            system.coordinates.as_ref().map(Spanned::span),
        ),
        ("lagrangian", system.lagrangian.as_ref().map(Spanned::span)),
        ("builtin", builtin.map(Spanned::span)),
        (
            "hamiltonian",
            system.hamiltonian.as_ref().map(Spanned::span),
        ),
        (
            "discrete_lagrangian",
            system.discrete_lagrangian.as_ref().map(Spanned::span),
        ),
        (
            "constraints",
            system.constraints.as_ref().map(Spanned::span),
        ),
        ("controls", system.controls.as_ref().map(Spanned::span)),
    ];
    match keys.into_iter().find_map(|(k, s)| s.map(|s| (k, s))) {
        Some((key, span)) => Err(ck
            .error(
                Some(span),
                format!("`{key}` cannot be used with a rigid body"),
            )
            .note(
                "a rigid body's configuration is its attitude R (and its centre of mass with a \
                 `mass`); its Lagrangian is ½ΩᵀJΩ (+ ½m|ẋ|²) − U",
            )
            .help("give the potential as `potential = \"...\"` in R11 … R33 (and x, y, z)")),
        None => Ok(()),
    }
}

/// `inertia = [J1, J2, J3]` or a symmetric 3×3 matrix, positive definite. The triangle
/// inequalities of a mass distribution are not required ([`Moments::Any`]): the test bodies of
/// Euler's equations, such as `J = diag(2, 1, 2/3)`, violate them.
fn inertia(ck: &Checker<'_>, body: &Spanned<RawRigidBody>) -> Result<Inertia, Diagnostic> {
    let Some(written) = &body.get_ref().inertia else {
        return Err(ck
            .error(Some(body.span()), "`rigid_body` needs its `inertia`")
            .help("e.g. `rigid_body = { inertia = [2.0, 1.0, 0.5] }` (principal moments)"));
    };
    let span = written.span();
    let example =
        "e.g. `inertia = [2.0, 1.0, 0.5]` or `inertia = [[2, 0, 0], [0, 1, 0], [0, 0, 0.5]]`";
    let rows = inertia_rows(ck, written, example)?;
    Inertia::validated(0, &rows, Moments::Any).map_err(|e| {
        ck.error(Some(span), format!("invalid inertia: {e}"))
            .help("the inertia is symmetric with positive principal moments")
    })
}

/// The nine entries (row-major) of an inertia written as three principal moments or a 3×3
/// matrix; `example` is the help for any other shape.
///
/// # Errors
/// Another shape, pointing at it.
pub(super) fn inertia_rows(
    ck: &Checker<'_>,
    written: &Spanned<RawInertia>,
    example: &str,
) -> Result<[f64; 9], Diagnostic> {
    match written.get_ref() {
        RawInertia::Principal(j) if j.len() == 3 => {
            Ok([j[0], 0.0, 0.0, 0.0, j[1], 0.0, 0.0, 0.0, j[2]])
        }
        RawInertia::Matrix(m) if m.len() == 3 && m.iter().all(|r| r.len() == 3) => {
            let mut rows = [0.0; 9];
            for (i, row) in m.iter().enumerate() {
                rows[3 * i..3 * i + 3].copy_from_slice(row);
            }
            Ok(rows)
        }
        _ => Err(ck
            .error(
                Some(written.span()),
                "the inertia must be three principal moments or a 3×3 matrix",
            )
            .help(example.to_owned())),
    }
}

/// Three expressions in the body's inputs.
fn vector_of_three(
    ck: &Checker<'_>,
    key: &str,
    list: &super::raw::SpannedList<String>,
    symbols: &Symbols,
    has_mass: bool,
) -> Result<ProgramSet, Diagnostic> {
    if list.get_ref().len() != 3 {
        return Err(ck.error(
            Some(list.span()),
            format!(
                "`{key}` has {} expressions, but a rigid body takes 3 (x, y, z)",
                list.get_ref().len()
            ),
        ));
    }
    let parsed = (list.get_ref().iter().enumerate())
        .map(|(i, v)| ck.parse_expr(&format!("[system] {key}[{i}]"), v))
        .collect::<Result<Vec<_>, _>>()?;
    let set = ck.compile_all(&format!("[system] {key}"), list, &parsed, symbols)?;
    if !has_mass {
        for (program, value) in set.programs().iter().zip(list.get_ref()) {
            no_centre(ck, key, value.span(), program.inputs_used())?;
        }
    }
    Ok(set)
}

/// Refuses `x`, `y`, `z` (input slots 9–11) in an expression of a body without a mass.
fn no_centre(
    ck: &Checker<'_>,
    key: &str,
    span: Range<usize>,
    used: &[usize],
) -> Result<(), Diagnostic> {
    match used.iter().find(|&&slot| (9..12).contains(&slot)) {
        Some(&slot) => Err(ck
            .error(
                Some(span),
                format!("`{key}` names `{}`, the centre of mass, but the body has no `mass`", INPUTS[slot]),
            )
            .help("give the body a `mass` (its centre of mass then moves), or write the expression in R11 … R33 and t")),
        None => Ok(()),
    }
}

/// `[[system.symmetry]]` of a rigid body: `rotation` (in space), `body_rotation`,
/// `translation` (with a mass).
fn rigid_symmetries(
    ck: &Checker<'_>,
    system: &RawSystem,
    has_mass: bool,
) -> Result<Vec<RigidSymmetry>, Diagnostic> {
    let mut out = Vec::new();
    for entry in system.symmetry.as_deref().unwrap_or(&[]) {
        let s = entry.get_ref();
        if let Some(g) = &s.generator {
            return Err(ck
                .error(Some(g.span()), "a rigid body's symmetries are named, not generated")
                .help("use `rotation = \"z\"` (in space) or `body_rotation = \"z\"` (about a body axis)"));
        }
        let action = action(ck, entry, s, has_mass)?;
        let (prefix, a) = match action {
            RigidAction::Space(a) => ("L", a),
            RigidAction::Body(a) => ("Pi", a),
            RigidAction::Translation(a) => ("P", a),
        };
        let name = s.name.as_ref().map_or_else(
            || format!("{prefix}_{}", CENTRE[a]),
            |n| n.get_ref().clone(),
        );
        if out.iter().any(|o: &RigidSymmetry| o.name == name) {
            let span = s.name.as_ref().map_or(entry.span(), Spanned::span);
            return Err(ck.error(Some(span), format!("two symmetries are named `{name}`")));
        }
        out.push(RigidSymmetry { name, action });
    }
    Ok(out)
}

fn action(
    ck: &Checker<'_>,
    entry: &Spanned<RawSymmetry>,
    s: &RawSymmetry,
    has_mass: bool,
) -> Result<RigidAction, Diagnostic> {
    let given = [
        s.rotation
            .as_ref()
            .map(|v| (v, RigidAction::Space as fn(usize) -> RigidAction)),
        s.body_rotation
            .as_ref()
            .map(|v| (v, RigidAction::Body as fn(usize) -> RigidAction)),
        s.translation
            .as_ref()
            .map(|v| (v, RigidAction::Translation as fn(usize) -> RigidAction)),
    ];
    let mut given = given.into_iter().flatten();
    let Some((axis, make)) = given.next() else {
        return Err(ck
            .error(Some(entry.span()), "the symmetry names no action")
            .help(
                "use `rotation = \"z\"` (in space) or `body_rotation = \"z\"` (about a body axis)",
            ));
    };
    if let Some((other, _)) = given.next() {
        return Err(ck.error(Some(other.span()), "give one action per symmetry"));
    }
    let Some(a) = CENTRE.iter().position(|c| c == axis.get_ref()) else {
        return Err(ck
            .error(
                Some(axis.span()),
                format!("unknown axis `{}`", axis.get_ref()),
            )
            .help("the axes are \"x\", \"y\" and \"z\""));
    };
    let action = make(a);
    if matches!(action, RigidAction::Translation(_)) && !has_mass {
        return Err(ck
            .error(
                Some(axis.span()),
                "a body turning about a fixed point has no translations",
            )
            .help("give the body a `mass` to let its centre of mass move"));
    }
    Ok(action)
}
