//! `[initial]` and `[integrator]` of a rigid body ([`super::rigid`]): its attitude, body momentum
//! and centre-of-mass data, the methods that have a group version, and what a rigid body's run
//! does not offer yet.

use std::ops::Range;

use marsden::discrete::rules::{BaseMethod, Method as CoreMethod};
use marsden::lie::so3::{self, Vec3};
use toml::Spanned;

use super::check::Checker;
use super::method::Method;
use super::raw::{RawInitial, RawProblem};
use super::rigid::{CENTRE, RigidInitial, RigidSpec};
use super::settings::InitialSpans;
use super::spec::{InitialData, InitialSpec};
use crate::error::Diagnostic;

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
    let centre = |list: &Option<super::raw::SpannedList<f64>>, key: &str| match (list, rigid.mass) {
        (None, _) => Ok(None),
        (Some(l), Some(_)) => ck
            .vector(&format!("initial.{key}"), l, &three_names)
            .map(Some),
        (Some(l), None) => Err(ck
            .error(
                Some(l.span()),
                format!("`{key}` applies to a body with a `mass`"),
            )
            .help("a body turning about a fixed point has no centre-of-mass data")),
    };
    let q = centre(&table.q, "q")?;
    let v = centre(&table.v, "v")?;
    let p = centre(&table.p, "p")?;
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

/// The three ways an attitude is written, as a table has them.
pub(super) struct AttitudeForms<'a> {
    /// `rotation_vector = [...]`.
    pub rotation_vector: Option<&'a super::raw::SpannedList<f64>>,
    /// `R = [[...], [...], [...]]`.
    pub r: Option<&'a Spanned<Vec<Vec<f64>>>>,
    /// `quaternion = [w, x, y, z]`.
    pub quaternion: Option<&'a super::raw::SpannedList<f64>>,
    /// Where the keys are written, for the messages (`initial`, `initial.a`).
    pub table: &'a str,
}

/// The initial attitude, row-major, from the one form written (the identity if none).
fn attitude(ck: &Checker<'_>, table: &RawInitial) -> Result<[f64; 9], Diagnostic> {
    attitude_of(
        ck,
        &AttitudeForms {
            rotation_vector: table.rotation_vector.as_ref(),
            r: table.r.as_ref(),
            quaternion: table.quaternion.as_ref(),
            table: "initial",
        },
    )
}

/// The attitude, row-major, from the one form written in `table` (the identity if none).
///
/// # Errors
/// Two forms written, a wrong length, a quaternion of zero norm, a matrix that is not a
/// rotation to 1e-10.
pub(super) fn attitude_of(
    ck: &Checker<'_>,
    table: &AttitudeForms<'_>,
) -> Result<[f64; 9], Diagnostic> {
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
    let key = |k: &str| format!("{}.{k}", table.table);
    let r = if let Some(v) = table.rotation_vector {
        let v = numbers(v, &key("rotation_vector"), 3)?;
        so3::from_rotation_vector(&Vec3::new(v[0], v[1], v[2]))
    } else if let Some(q) = table.quaternion {
        let w = numbers(q, &key("quaternion"), 4)?;
        so3::from_quaternion(&[w[0], w[1], w[2], w[3]])
            .map_err(|e| ck.error(Some(q.span()), format!("{}: {e}", key("quaternion"))))?
    } else if let Some(m) = table.r {
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
pub(super) fn refuse_unsupported(
    ck: &Checker<'_>,
    raw: &RawProblem,
    what_system: &str,
) -> Result<(), Diagnostic> {
    let certify = (raw.analysis.as_ref())
        .and_then(|a| a.get_ref().certify.as_ref())
        .filter(|c| *c.get_ref())
        .map(Spanned::span);
    let compensated = (raw.integrator.as_ref())
        .and_then(|i| i.get_ref().compensated.as_ref())
        .filter(|c| *c.get_ref())
        .map(Spanned::span);
    let output = raw.output.as_ref().map(Spanned::get_ref);
    let found = [
        raw.sweep.as_ref().map(|s| ("[sweep]", s.span())),
        (raw.events.as_ref())
            .and_then(|e| e.first())
            .map(|e| ("[[events]]", e.span())),
        (output.and_then(|o| o.observables.as_ref())).map(|o| ("`observables`", o.span())),
        (output.and_then(|o| o.section.as_ref())).map(|o| ("`section`", o.span())),
        raw.sensitivity
            .as_ref()
            .map(|s| ("[sensitivity]", s.span())),
        certify.map(|s| ("`certify = true`", s)),
        compensated.map(|s| ("`compensated = true`", s)),
    ];
    match found.into_iter().flatten().next() {
        Some((what, span)) => Err(ck
            .error(Some(span), format!("{what} is not available for {what_system}"))
            .note(format!("{what_system}'s run gives its trajectory, energy, momentum maps and the monitors of its attitudes"))
            .help("remove it to run the system")),
        None => Ok(()),
    }
}
