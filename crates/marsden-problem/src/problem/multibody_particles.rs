//! What a particle (`[[system.particle]]`, a point mass) accepts from the joints, springs and
//! dampers that name it: points at its position, and joints that do not constrain an attitude
//! it does not have (the core's `RigidBody::particle`).

use std::ops::Range;

use toml::Spanned;

use super::check::Checker;
use super::multibody::BodySpec;
use super::raw_multibody::RawBodyInitial;
use crate::error::Diagnostic;

/// The joint kinds a particle takes.
pub const PARTICLE_JOINTS: [&str; 2] = ["spherical", "distance"];

/// The sides of a joint, spring or damper as written, for the checks of its particles.
pub(super) struct Sides<'a> {
    /// `"joint"`, `"spring"` or `"damper"`.
    pub what: &'static str,
    /// Its kind's name and span (joints only).
    pub kind: Option<(&'a str, Range<usize>)>,
    /// The body index of each side (`None`: the ground).
    pub bodies: [Option<usize>; 2],
    /// The points in each side's frame.
    pub points: [[f64; 3]; 2],
    /// The span of `at`.
    pub at: Range<usize>,
}

/// Refuses a particle side whose point is not `[0, 0, 0]`, and a joint kind other than
/// spherical or distance on a particle.
///
/// # Errors
/// The first such side, at `kind` or `at`.
pub(super) fn check_sides(
    ck: &Checker<'_>,
    sides: &Sides<'_>,
    bodies: &[BodySpec],
) -> Result<(), Diagnostic> {
    for (side, body) in sides.bodies.iter().enumerate() {
        let Some(particle) = body.and_then(|b| bodies.get(b)).filter(|b| b.particle) else {
            continue;
        };
        if let Some((kind, span)) = &sides.kind
            && !PARTICLE_JOINTS.contains(kind)
        {
            return Err(ck
                .error(
                    Some(span.clone()),
                    format!(
                        "a {kind} joint cannot hold particle `{}`: a particle has no attitude",
                        particle.name
                    ),
                )
                .help("join a particle by a `spherical` or `distance` joint"));
        }
        let point = sides.points[side];
        if point != [0.0; 3] {
            return Err(ck
                .error(
                    Some(sides.at.clone()),
                    format!(
                        "a {} acts on particle `{}` at its position: its point is [0, 0, 0], not \
                         {point:?}",
                        sides.what, particle.name
                    ),
                )
                .help("write `[0.0, 0.0, 0.0]` on the particle's side of `at`"));
        }
    }
    Ok(())
}

/// Refuses an attitude or angular velocity in a particle's `[initial.<name>]`.
///
/// # Errors
/// The first such key, at its value.
pub(super) fn no_attitude(
    ck: &Checker<'_>,
    particle: &BodySpec,
    data: &RawBodyInitial,
) -> Result<(), Diagnostic> {
    let keys = [
        ("R", data.r.as_ref().map(Spanned::span)),
        ("quaternion", data.quaternion.as_ref().map(Spanned::span)),
        (
            "rotation_vector",
            data.rotation_vector.as_ref().map(Spanned::span),
        ),
        ("Omega", data.omega.as_ref().map(Spanned::span)),
        ("Pi", data.pi.as_ref().map(Spanned::span)),
    ];
    match keys
        .into_iter()
        .find_map(|(key, span)| span.map(|s| (key, s)))
    {
        None => Ok(()),
        Some((key, span)) => Err(ck
            .error(
                Some(span),
                format!(
                    "particle `{}` has no attitude: `{key}` cannot be given",
                    particle.name
                ),
            )
            .help("a particle's initial data are its position `x` and `v` (or `p`)")),
    }
}

/// The span of an optional key, or of the whole table.
pub(super) fn span_or<T>(key: Option<&Spanned<T>>, whole: &Range<usize>) -> Range<usize> {
    key.map_or(whole.clone(), Spanned::span)
}
