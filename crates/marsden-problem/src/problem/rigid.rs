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

use marsden::discrete::rules::{BaseMethod, Method as CoreMethod};
use marsden::lie::body::{Inertia, Moments};
use marsden::lie::so3::{self, Vec3};
use marsden_expr::{ProgramSet, Symbols};
use toml::Spanned;

use super::check::Checker;
use super::method::Method;
use super::parameters::Parameters;
use super::raw::{RawInertia, RawInitial, RawProblem, RawRigidBody, RawSymmetry, RawSystem};
use super::resolved::{Resolved, symbols};
use super::settings::InitialSpans;
use super::spec::{InitialData, InitialSpec, LagrangianSpec};
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

/// Whether the file describes a rigid body.
pub fn is_rigid(raw: &RawProblem) -> bool {
    (raw.system.as_ref()).is_some_and(|s| s.get_ref().rigid_body.is_some())
}

/// Refuses the rigid-body keys in a file that has no `rigid_body`.
///
/// # Errors
/// The first such key, with where it belongs.
pub fn refuse_rigid_keys(ck: &Checker<'_>, raw: &RawProblem) -> Result<(), Diagnostic> {
    let system = raw.system.as_ref().map(Spanned::get_ref);
    let initial = raw.initial.as_ref().map(Spanned::get_ref);
    let spans = [
        system.and_then(|s| s.potential.as_ref().map(|v| ("potential", v.span()))),
        system.and_then(|s| s.torques.as_ref().map(|v| ("torques", v.span()))),
        initial.and_then(|i| {
            i.rotation_vector
                .as_ref()
                .map(|v| ("rotation_vector", v.span()))
        }),
        initial.and_then(|i| i.r.as_ref().map(|v| ("R", v.span()))),
        initial.and_then(|i| i.quaternion.as_ref().map(|v| ("quaternion", v.span()))),
        initial.and_then(|i| i.omega.as_ref().map(|v| ("Omega", v.span()))),
        initial.and_then(|i| i.pi.as_ref().map(|v| ("Pi", v.span()))),
    ];
    let body_rotation = system
        .and_then(|s| s.symmetry.as_deref())
        .into_iter()
        .flatten()
        .find_map(|s| s.get_ref().body_rotation.as_ref())
        .map(|v| ("body_rotation", v.span()));
    match spans.into_iter().chain([body_rotation]).flatten().next() {
        Some((key, span)) => Err(ck
            .error(Some(span), format!("`{key}` applies to a rigid body"))
            .help("declare the body with `rigid_body = { inertia = [J1, J2, J3] }` in [system]")),
        None => Ok(()),
    }
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
    refuse_coordinate_keys(ck, system)?;
    params.numbers_only(ck, "a rigid body")?;
    let raw = body.get_ref();
    let inertia = inertia(ck, body)?;
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
    let inputs: Vec<String> = INPUTS.iter().map(|s| (*s).to_owned()).collect();
    let symbols = symbols(ck, inputs, &constants, params)?;
    let potential = match &system.potential {
        None => ExprRigidPotential::new(None),
        Some(text) => {
            let expr = ck.parse_expr("[system] potential", text)?;
            let program = expr
                .compile(&symbols)
                .map_err(|e| ck.expr_error("[system] potential", text, &e))?;
            if mass.is_none() {
                no_centre(ck, "potential", text.span(), program.inputs_used())?;
            }
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

/// The keys of a system in coordinates, which a rigid body does not take.
fn refuse_coordinate_keys(ck: &Checker<'_>, system: &RawSystem) -> Result<(), Diagnostic> {
    let keys = [
        (
            "coordinates",
            system.coordinates.as_ref().map(Spanned::span),
        ),
        ("lagrangian", system.lagrangian.as_ref().map(Spanned::span)),
        ("builtin", system.builtin.as_ref().map(Spanned::span)),
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
    ];
    match keys.into_iter().find_map(|(k, s)| s.map(|s| (k, s))) {
        Some((key, span)) => Err(ck
            .error(
                Some(span),
                format!("`{key}` cannot be used with `rigid_body`"),
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
    let rows = match written.get_ref() {
        RawInertia::Principal(j) if j.len() == 3 => {
            let rows = [j[0], 0.0, 0.0, 0.0, j[1], 0.0, 0.0, 0.0, j[2]];
            rows
        }
        RawInertia::Matrix(m) if m.len() == 3 && m.iter().all(|r| r.len() == 3) => {
            let mut rows = [0.0; 9];
            for (i, row) in m.iter().enumerate() {
                rows[3 * i..3 * i + 3].copy_from_slice(row);
            }
            rows
        }
        _ => {
            return Err(ck
                .error(Some(span), "the inertia must be three principal moments or a 3×3 matrix")
                .help("e.g. `inertia = [2.0, 1.0, 0.5]` or `inertia = [[2, 0, 0], [0, 1, 0], [0, 0, 0.5]]`"));
        }
    };
    Inertia::validated(0, &rows, Moments::Any).map_err(|e| {
        ck.error(Some(span), format!("invalid inertia: {e}"))
            .help("the inertia is symmetric with positive principal moments")
    })
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

/// The integrator's method for a rigid body: the LGVI is the trapezoidal rule on the group, so
/// `trapezoid` (the default) and its compositions.
///
/// # Errors
/// Another rule, pointing at the method.
pub(super) fn method(
    ck: &Checker<'_>,
    method: &Method,
    span: Option<Range<usize>>,
) -> Result<Method, Diagnostic> {
    let Some(span) = span else {
        return Ok(Method::Rule(CoreMethod::Single(BaseMethod::Trapezoid)));
    };
    match method {
        Method::Rule(CoreMethod::Single(BaseMethod::Trapezoid))
        | Method::Rule(CoreMethod::Composed(_, BaseMethod::Trapezoid)) => Ok(method.clone()),
        _ => Err(ck
            .error(Some(span), format!("the method `{method}` has no rigid-body version"))
            .note("a rigid body is stepped by the Lie group variational integrator, the trapezoidal rule on SO(3)")
            .help("use `trapezoid` (order 2) or a composition of it, e.g. `triple-jump-4(trapezoid)` or `kahan-li-6(trapezoid)`")),
    }
}

/// `[initial]` of a rigid body: the attitude (`rotation_vector`, `R` or `quaternion`; default
/// the identity), the body momentum (`Omega` or `Pi`), and with a mass the centre `q` and its
/// `v` or `p` (default: at rest at the origin).
///
/// # Errors
/// Two forms of the same datum, a matrix that is not a rotation to 1e-10, wrong lengths.
pub(super) fn initial(
    ck: &Checker<'_>,
    raw: Option<&Spanned<RawInitial>>,
    rigid: &RigidSpec,
) -> Result<(InitialSpec, InitialSpans), Diagnostic> {
    let Some(raw) = raw else {
        return Err(Diagnostic::new("the problem file has no [initial] table")
            .help("add [initial] with `Omega = [...]` (body angular velocity) or `Pi = [...]`"));
    };
    let table = raw.get_ref();
    let attitude = attitude(ck, table)?;
    let three_names: Vec<String> = CENTRE.iter().map(|c| (*c).to_owned()).collect();
    let (momentum, data_span) = match (&table.omega, &table.pi) {
        (Some(_), Some(pi)) => {
            return Err(ck
                .error(
                    Some(pi.span()),
                    "give either `Omega` or `Pi` in [initial], not both",
                )
                .help("`Omega` is the body angular velocity, `Pi = J Omega` the body momentum"));
        }
        (None, None) => {
            return Err(ck
                .error(Some(raw.span()), "[initial] needs the body angular velocity `Omega = [...]` or the body momentum `Pi = [...]`"));
        }
        (Some(w), None) => {
            let w = ck.vector("initial.Omega", w, &three_names)?;
            let pi = rigid.inertia.tensor() * Vec3::new(w[0], w[1], w[2]);
            (
                [pi.x, pi.y, pi.z],
                table.omega.as_ref().map_or(0..0, Spanned::span),
            )
        }
        (None, Some(p)) => {
            let p = ck.vector("initial.Pi", p, &three_names)?;
            ([p[0], p[1], p[2]], p_span(table))
        }
    };
    let centre = |list: &Option<super::raw::SpannedList<f64>>, what: &str| match (list, rigid.mass)
    {
        (None, _) => Ok(None),
        (Some(l), Some(_)) => ck.vector(what, l, &three_names).map(Some),
        (Some(l), None) => Err(ck
            .error(
                Some(l.span()),
                format!("`{}` applies to a body with a `mass`", &what[8..]),
            )
            .help("a body turning about a fixed point has no centre-of-mass data")),
    };
    let q = centre(&table.q, "initial.q")?;
    let v = centre(&table.v, "initial.v")?;
    let p = centre(&table.p, "initial.p")?;
    let n = if rigid.mass.is_some() { 3 } else { 0 };
    let data = match (v, p) {
        (Some(_), Some(_)) => {
            let span = table.p.as_ref().map_or(0..0, Spanned::span);
            return Err(ck.error(Some(span), "give either `v` or `p` in [initial], not both"));
        }
        (None, Some(p)) => InitialData::Momentum(p),
        (Some(v), None) => InitialData::Velocity(v),
        (None, None) => InitialData::Velocity(vec![0.0; n]),
    };
    if let Some(f) = &table.file {
        return Err(ck.error(
            Some(f.span()),
            "`file` gives N-body data, not a rigid body's",
        ));
    }
    let t0 = table
        .t0
        .as_ref()
        .map_or(Ok(0.0), |t| ck.finite("initial.t0", t))?;
    let spec = InitialSpec {
        t0,
        q: q.unwrap_or_else(|| vec![0.0; n]),
        data,
        project: false,
        rigid: None,
    };
    let spans = InitialSpans {
        q: table.q.as_ref().map_or(data_span.clone(), Spanned::span),
        data: data_span,
    };
    Ok((
        InitialSpec {
            rigid: Some(RigidInitial { attitude, momentum }),
            ..spec
        },
        spans,
    ))
}

fn p_span(table: &RawInitial) -> Range<usize> {
    table.pi.as_ref().map_or(0..0, Spanned::span)
}

/// The initial attitude, row-major, from the one form written (the identity if none).
fn attitude(ck: &Checker<'_>, table: &RawInitial) -> Result<[f64; 9], Diagnostic> {
    let forms = [
        table
            .rotation_vector
            .as_ref()
            .map(|v| ("rotation_vector", v.span())),
        table.r.as_ref().map(|v| ("R", v.span())),
        table.quaternion.as_ref().map(|v| ("quaternion", v.span())),
    ];
    let mut written = forms.into_iter().flatten();
    let first = written.next();
    if let (Some((a, _)), Some((b, span))) = (first.clone(), written.next()) {
        return Err(ck
            .error(
                Some(span),
                format!("give the initial attitude once: `{a}` and `{b}` are both written"),
            )
            .help("`rotation_vector` (axis × angle), `R` (rows) or `quaternion` ([w, x, y, z])"));
    }
    let numbers = |list: &super::raw::SpannedList<f64>,
                   what: &str,
                   n: usize|
     -> Result<Vec<f64>, Diagnostic> {
        let names: Vec<String> = (0..n).map(|i| i.to_string()).collect();
        ck.vector(what, list, &names)
    };
    let r = if let Some(v) = &table.rotation_vector {
        let v = numbers(v, "initial.rotation_vector", 3)?;
        so3::from_rotation_vector(&Vec3::new(v[0], v[1], v[2]))
    } else if let Some(q) = &table.quaternion {
        let w = numbers(q, "initial.quaternion", 4)?;
        so3::from_quaternion(&[w[0], w[1], w[2], w[3]])
            .map_err(|e| ck.error(Some(q.span()), format!("initial.quaternion: {e}")))?
    } else if let Some(m) = &table.r {
        let rows = matrix_rows(ck, m)?;
        so3::attitude("initial R", &rows).map_err(|e| {
            ck.error(Some(m.span()), format!("{e}"))
                .help("give an orthonormal matrix with det R = 1 (to 1e-10), or `rotation_vector` / `quaternion`")
        })?
    } else {
        so3::Mat3::identity()
    };
    Ok(so3::rows(&r))
}

fn matrix_rows(ck: &Checker<'_>, m: &Spanned<Vec<Vec<f64>>>) -> Result<[f64; 9], Diagnostic> {
    let written = m.get_ref();
    if written.len() != 3 || written.iter().any(|r| r.len() != 3) {
        return Err(ck.error(
            Some(m.span()),
            "`R` must be a 3×3 matrix: three rows of three numbers",
        ));
    }
    let mut rows = [0.0; 9];
    for (i, row) in written.iter().enumerate() {
        rows[3 * i..3 * i + 3].copy_from_slice(row);
    }
    if let Some(bad) = rows.iter().find(|v| !v.is_finite()) {
        return Err(ck.error(
            Some(m.span()),
            format!("`R` has a non-finite entry ({bad})"),
        ));
    }
    Ok(rows)
}

/// Refuses what a rigid-body run does not offer yet: an ensemble (`[sweep]`), derivatives
/// (`[sensitivity]`), the certificates (`[analysis] certify`), compensated summation.
///
/// # Errors
/// The first such table or key, saying so.
pub(super) fn refuse_unsupported(ck: &Checker<'_>, raw: &RawProblem) -> Result<(), Diagnostic> {
    let certify = (raw.analysis.as_ref())
        .and_then(|a| a.get_ref().certify.as_ref())
        .filter(|c| *c.get_ref())
        .map(Spanned::span);
    let compensated = (raw.integrator.as_ref())
        .and_then(|i| i.get_ref().compensated.as_ref())
        .filter(|c| *c.get_ref())
        .map(Spanned::span);
    let found = [
        raw.sweep.as_ref().map(|s| ("[sweep]", s.span())),
        raw.sensitivity
            .as_ref()
            .map(|s| ("[sensitivity]", s.span())),
        certify.map(|s| ("`certify = true`", s)),
        compensated.map(|s| ("`compensated = true`", s)),
    ];
    match found.into_iter().flatten().next() {
        Some((what, span)) => Err(ck
            .error(Some(span), format!("{what} is not available for a rigid body"))
            .note("a rigid body's run gives its trajectory, energy, momentum maps, Casimir and orthogonality defect")
            .help("remove it to run the body")),
        None => Ok(()),
    }
}
