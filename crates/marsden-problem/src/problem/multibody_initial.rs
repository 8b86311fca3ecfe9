//! `[initial.<body>]` of a multibody file ([`super::multibody`]): each body's centre `x`, its
//! velocity `v` (or momentum `p`), its attitude (`R`, `quaternion` or `rotation_vector`) and its
//! body angular velocity `Omega` (or momentum `Pi`); `[initial]` itself takes `t0` and
//! `project` (move the state onto the joints before the run).

use std::ops::Range;

use marsden::lie::so3::{Mat3, Vec3};
use marsden::lie::state::BodyInitial;
use toml::Spanned;

use super::check::Checker;
use super::multibody::{BodySpec, MultibodySpec};
use super::multibody_particles::no_attitude;
use super::raw::{RawInitial, SpannedList};
use super::raw_multibody::RawBodyInitial;
use super::rigid_settings::{AttitudeForms, attitude_of};
use super::settings::InitialSpans;
use super::spec::{InitialData, InitialSpec};
use crate::error::Diagnostic;

const AXES: [&str; 3] = ["x", "y", "z"];

/// Fills `spec.initial` from the body tables and returns the run's `[initial]`.
///
/// # Errors
/// A missing `[initial]` or body table, a table naming no body, two forms of one datum, a
/// matrix that is not a rotation, keys of other systems in `[initial]`.
pub(super) fn initial(
    ck: &Checker<'_>,
    raw: Option<&Spanned<RawInitial>>,
    spec: &mut MultibodySpec,
) -> Result<(InitialSpec, InitialSpans), Diagnostic> {
    let Some(raw) = raw else {
        return Err(
            Diagnostic::new("the problem file has no [initial] table").help(format!(
                "add a table per body, e.g. `[initial.{}]` with `x = [...]`",
                spec.bodies[0].name
            )),
        );
    };
    let table = raw.get_ref();
    refuse_single_body_keys(ck, table)?;
    for named in &table.bodies {
        if !spec.bodies.iter().any(|b| b.name == named.name) {
            let names: Vec<String> = spec
                .bodies
                .iter()
                .map(|b| format!("[initial.{}]", b.name))
                .collect();
            return Err(ck
                .error(
                    Some(raw.span()),
                    format!("[initial.{}] names no body", named.name),
                )
                .help(format!("the bodies' tables are {}", names.join(", "))));
        }
    }
    let mut states = Vec::with_capacity(spec.bodies.len());
    for body in &spec.bodies {
        let Some(named) = table.bodies.iter().find(|b| b.name == body.name) else {
            return Err(ck
                .error(Some(raw.span()), format!("body `{}` has no initial data", body.name))
                .help(format!("add `[initial.{}]` with its centre `x = [...]` (and `R`, `v`, `Omega`: default identity and at rest)", body.name)));
        };
        states.push(body_initial(ck, raw.span(), body, &named.data)?);
    }
    spec.initial = states;
    let t0 = table
        .t0
        .as_ref()
        .map_or(Ok(0.0), |t| ck.finite("initial.t0", t))?;
    let spans = InitialSpans {
        q: raw.span(),
        data: raw.span(),
    };
    Ok((
        InitialSpec {
            t0,
            q: Vec::new(),
            data: InitialData::Velocity(Vec::new()),
            project: table.project.unwrap_or(false),
            rigid: None,
        },
        spans,
    ))
}

fn body_initial(
    ck: &Checker<'_>,
    table_span: Range<usize>,
    body: &BodySpec,
    data: &RawBodyInitial,
) -> Result<BodyInitial, Diagnostic> {
    if body.particle {
        no_attitude(ck, body, data)?;
    }
    let key = |k: &str| format!("initial.{}.{k}", body.name);
    let three = |list: &SpannedList<f64>, k: &str| -> Result<[f64; 3], Diagnostic> {
        let names = AXES.map(str::to_owned);
        let v = ck.vector(&key(k), list, &names)?;
        Ok([v[0], v[1], v[2]])
    };
    let Some(x) = &data.x else {
        return Err(ck
            .error(Some(table_span), format!("[initial.{}] needs the centre of mass `x = [...]`", body.name))
            .help("the joints are checked at the initial positions (or `project = true` in [initial] moves them onto the joints)"));
    };
    let position = three(x, "x")?;
    let either =
        |a: &Option<SpannedList<f64>>, b: &Option<SpannedList<f64>>, names: (&str, &str)| {
            if let (Some(_), Some(second)) = (a, b) {
                return Err(ck.error(
                    Some(second.span()),
                    format!(
                        "give either `{}` or `{}` in [initial.{}], not both",
                        names.0, names.1, body.name
                    ),
                ));
            }
            Ok(())
        };
    either(&data.v, &data.p, ("v", "p"))?;
    either(&data.omega, &data.pi, ("Omega", "Pi"))?;
    let linear_momentum = match (&data.v, &data.p) {
        (Some(v), _) => three(v, "v")?.map(|v| body.mass * v),
        (None, Some(p)) => three(p, "p")?,
        (None, None) => [0.0; 3],
    };
    let angular_momentum = match (&data.omega, &data.pi) {
        (Some(w), _) => {
            let w = three(w, "Omega")?;
            let pi: Vec3 = body.inertia.tensor() * Vec3::new(w[0], w[1], w[2]);
            [pi.x, pi.y, pi.z]
        }
        (None, Some(pi)) => three(pi, "Pi")?,
        (None, None) => [0.0; 3],
    };
    let table = format!("initial.{}", body.name);
    let forms = AttitudeForms {
        rotation_vector: data.rotation_vector.as_ref(),
        r: data.r.as_ref(),
        quaternion: data.quaternion.as_ref(),
        table: &table,
    };
    let attitude = attitude_of(ck, &forms)?;
    debug_assert!(Mat3::from_row_slice(&attitude).determinant() > 0.0);
    Ok(BodyInitial {
        attitude,
        angular_momentum,
        position,
        linear_momentum,
    })
}

/// Refuses `[initial.<name>]` tables in a file without `[[system.body]]` (the deserializer of
/// `[initial]` reads any table in it as a body's).
///
/// # Errors
/// The first such table, as an unknown key of `[initial]`.
pub(super) fn refuse_body_tables(
    ck: &Checker<'_>,
    raw: Option<&Spanned<RawInitial>>,
) -> Result<(), Diagnostic> {
    match raw.and_then(|r| r.get_ref().bodies.first().map(|b| (r.span(), &b.name))) {
        Some((span, name)) => Err(ck
            .error(Some(span), format!("unknown table [initial.{name}]"))
            .note("tables in [initial] give the initial data of the bodies of a multibody system (`[[system.body]]`)")
            .help("write this system's initial data as keys of [initial]: `q = [...]`, `v = [...]`")),
        None => Ok(()),
    }
}

/// `[initial]`'s keys of systems in coordinates and of one rigid body.
fn refuse_single_body_keys(ck: &Checker<'_>, table: &RawInitial) -> Result<(), Diagnostic> {
    let keys = [
        ("q", table.q.as_ref().map(Spanned::span)),
        ("v", table.v.as_ref().map(Spanned::span)),
        ("p", table.p.as_ref().map(Spanned::span)),
        ("file", table.file.as_ref().map(Spanned::span)),
        ("R", table.r.as_ref().map(Spanned::span)),
        ("quaternion", table.quaternion.as_ref().map(Spanned::span)),
        (
            "rotation_vector",
            table.rotation_vector.as_ref().map(Spanned::span),
        ),
        ("Omega", table.omega.as_ref().map(Spanned::span)),
        ("Pi", table.pi.as_ref().map(Spanned::span)),
    ];
    match keys.into_iter().find_map(|(k, s)| s.map(|s| (k, s))) {
        Some((key, span)) => Err(ck
            .error(
                Some(span),
                format!("`{key}` in [initial] does not say which body it is for"),
            )
            .help(format!(
                "write it in the body's table, e.g. `[initial.<body>]` with `{key} = [...]`"
            ))),
        None => Ok(()),
    }
}

/// Checks the initial state against the joints (unless `project = true` moves it onto them
/// when the run starts), pointing at the joint at fault.
///
/// # Errors
/// A state off a joint (the row and its residual), velocities that break a joint, redundant
/// or singular joints.
pub(super) fn check_joints(
    ck: &Checker<'_>,
    system: &super::raw::RawSystem,
    spec: &MultibodySpec,
    t0: f64,
) -> Result<(), Diagnostic> {
    use marsden::error::{Error, SetupError};
    let joint_span = |j: usize| {
        system
            .joint
            .as_ref()
            .and_then(|list| list.get(j))
            .map(Spanned::span)
    };
    let (core, joints, state) = crate::model::multibody::core(spec, t0)
        .map_err(|e| Diagnostic::new(format!("the multibody system: {e}")))?;
    let Err(error) = marsden::lie::multibody::initial::check(&core, &joints, &state) else {
        return Ok(());
    };
    let row_of = |index: usize| {
        let j = joints.joint_of_row(index);
        (
            j,
            index - joints.joint_rows(j).start,
            joints.joint_rows(j).len(),
        )
    };
    let help = "move the bodies onto the joints, or set `project = true` in [initial] to move them there before the run";
    Err(match error {
        Error::Setup(SetupError::InitialPositionOffConstraint { index, residual, tolerance }) => {
            let (j, row, rows) = row_of(index);
            ck.error(
                joint_span(j),
                format!(
                    "the bodies start off joint `{}`: its row {row} of {rows} is {residual:.3e} (tolerance {tolerance:.1e})",
                    spec.joints[j].name
                ),
            )
            .help(help)
        }
        Error::Setup(SetupError::InitialVelocityNotTangent { index, residual, tolerance, .. }) => {
            let (j, row, rows) = row_of(index);
            ck.error(
                joint_span(j),
                format!(
                    "the bodies' initial velocities break joint `{}`: the rate of its row {row} of {rows} is {residual:.3e} (tolerance {tolerance:.1e})",
                    spec.joints[j].name
                ),
            )
            .help("give velocities the joints allow, or set `project = true` in [initial] to project them")
        }
        Error::Setup(SetupError::SingularConstraintMass { pivot, .. }) => ck
            .error(
                joint_span(spec.joints.len().saturating_sub(1)),
                format!("the joints are redundant or singular at the initial state (pivot {pivot:.3e} of G M⁻¹ Gᵀ)"),
            )
            .note("two joints lock the same motion (e.g. two ball joints on the same points), or a joint is degenerate there")
            .help("remove the joint that repeats another's constraint"),
        other => Diagnostic::new(format!("the multibody system's initial state: {other}")),
    })
}
