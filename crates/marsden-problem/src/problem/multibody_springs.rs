//! `[[system.spring]]` and `[[system.damper]]` of a multibody file: springs and dampers between
//! points of bodies (or a body and the ground), checked against the file's bodies.
//!
//! ```toml
//! [[system.spring]]
//! bodies = ["a", "b"]                        # body names, or "ground"
//! at = [[0.1, 0.0, 0.0], [0.0, 0.0, -0.1]]   # the point in each side's frame
//! stiffness = 40.0                           # k ≥ 0
//! rest_length = 0.8                          # ℓ₀ ≥ 0; default: the distance at the start
//! [[system.damper]]
//! bodies = ["a", "b"]
//! at = [[0.1, 0.0, 0.0], [0.0, 0.0, -0.1]]
//! coefficient = 0.5                          # c ≥ 0
//! ```
//!
//! A spring adds `½ k (‖p_b − p_a‖ − ℓ₀)²` to the potential (so to the energy the run reports);
//! a damper acts with `−c (ḋ·e) e` along the line of its points (`marsden::lie::multibody`'s
//! `spring` and `damper`).

use std::ops::Range;

use toml::Spanned;

use super::check::Checker;
use super::multibody::{BodySpec, GROUND, pair_of_vectors, quoted, valid_name};
use super::multibody_particles::{Sides, check_sides};
use super::raw::RawSystem;
use crate::error::Diagnostic;

/// One spring.
#[derive(Debug, Clone, PartialEq)]
pub struct SpringSpec {
    /// Its name (for messages).
    pub name: String,
    /// The body index of each side (`None`: the ground).
    pub bodies: [Option<usize>; 2],
    /// The point in each side's frame.
    pub points: [[f64; 3]; 2],
    /// `k`.
    pub stiffness: f64,
    /// `ℓ₀`, if written (otherwise the distance in the initial state).
    pub rest_length: Option<f64>,
}

/// One damper.
#[derive(Debug, Clone, PartialEq)]
pub struct DamperSpec {
    /// Its name (for messages).
    pub name: String,
    /// The body index of each side (`None`: the ground).
    pub bodies: [Option<usize>; 2],
    /// The point in each side's frame.
    pub points: [[f64; 3]; 2],
    /// `c`.
    pub coefficient: f64,
}

/// The sides and points every element between two points has.
struct Ends {
    name: String,
    bodies: [Option<usize>; 2],
    points: [[f64; 3]; 2],
}

/// The element's name, sides and points as written (`what` is `spring` or `damper`).
struct Written<'a> {
    what: &'static str,
    index: usize,
    whole: Range<usize>,
    name: &'a Option<Spanned<String>>,
    sides: &'a Option<Spanned<Vec<String>>>,
    at: &'a Option<Spanned<Vec<Vec<f64>>>>,
}

/// The springs of `system`.
///
/// # Errors
/// An unknown body, `bodies` or `at` of the wrong shape, a missing or negative `stiffness`,
/// a negative `rest_length`, two springs of one name.
pub(super) fn springs(
    ck: &Checker<'_>,
    system: &RawSystem,
    bodies: &[BodySpec],
) -> Result<Vec<SpringSpec>, Diagnostic> {
    let mut springs: Vec<SpringSpec> = Vec::new();
    for (index, raw) in system.spring.as_deref().unwrap_or(&[]).iter().enumerate() {
        let s = raw.get_ref();
        let written = Written {
            what: "spring",
            index,
            whole: raw.span(),
            name: &s.name,
            sides: &s.bodies,
            at: &s.at,
        };
        let ends = ends(ck, &written, bodies)?;
        let stiffness = nonnegative(ck, &written, "stiffness", s.stiffness.as_ref(), true)?;
        let rest_length = match &s.rest_length {
            None => None,
            Some(l) => Some(nonnegative(ck, &written, "rest_length", Some(l), false)?),
        };
        if springs.iter().any(|o| o.name == ends.name) {
            return Err(duplicate(ck, &written, &ends.name));
        }
        springs.push(SpringSpec {
            name: ends.name,
            bodies: ends.bodies,
            points: ends.points,
            stiffness,
            rest_length,
        });
    }
    Ok(springs)
}

/// The dampers of `system`.
///
/// # Errors
/// As [`springs`], for `coefficient`.
pub(super) fn dampers(
    ck: &Checker<'_>,
    system: &RawSystem,
    bodies: &[BodySpec],
) -> Result<Vec<DamperSpec>, Diagnostic> {
    let mut dampers: Vec<DamperSpec> = Vec::new();
    for (index, raw) in system.damper.as_deref().unwrap_or(&[]).iter().enumerate() {
        let d = raw.get_ref();
        let written = Written {
            what: "damper",
            index,
            whole: raw.span(),
            name: &d.name,
            sides: &d.bodies,
            at: &d.at,
        };
        let ends = ends(ck, &written, bodies)?;
        let coefficient = nonnegative(ck, &written, "coefficient", d.coefficient.as_ref(), true)?;
        if dampers.iter().any(|o| o.name == ends.name) {
            return Err(duplicate(ck, &written, &ends.name));
        }
        dampers.push(DamperSpec {
            name: ends.name,
            bodies: ends.bodies,
            points: ends.points,
            coefficient,
        });
    }
    Ok(dampers)
}

fn duplicate(ck: &Checker<'_>, w: &Written<'_>, name: &str) -> Diagnostic {
    let span = w.name.as_ref().map_or(w.whole.clone(), Spanned::span);
    ck.error(Some(span), format!("two {}s are named `{name}`", w.what))
}

/// The name, the two sides (body names or the ground, not the same twice) and the points.
fn ends(ck: &Checker<'_>, w: &Written<'_>, bodies: &[BodySpec]) -> Result<Ends, Diagnostic> {
    let number = w.index + 1;
    let Some(sides) = w.sides else {
        return Err(ck
            .error(
                Some(w.whole.clone()),
                format!("{} #{number} has no `bodies`", w.what),
            )
            .help("e.g. `bodies = [\"ground\", \"a\"]` (two bodies, or the ground and a body)"));
    };
    let [a, b] = sides.get_ref().as_slice() else {
        return Err(ck.error(
            Some(sides.span()),
            format!(
                "`bodies` names {} sides; a {} joins two",
                sides.get_ref().len(),
                w.what
            ),
        ));
    };
    let side = |name: &str| -> Result<Option<usize>, Diagnostic> {
        if name == GROUND {
            return Ok(None);
        }
        let found = bodies.iter().position(|b| b.name == name);
        found.map(Some).ok_or_else(|| {
            let names: Vec<&str> = bodies.iter().map(|b| b.name.as_str()).collect();
            ck.error(
                Some(sides.span()),
                format!("{} #{number} names an unknown body `{name}`", w.what),
            )
            .help(format!(
                "the bodies are {} (and \"ground\")",
                quoted(&names)
            ))
        })
    };
    let pair = [side(a)?, side(b)?];
    if pair[0] == pair[1] {
        return Err(ck.error(
            Some(sides.span()),
            format!(
                "a {} joins two different bodies (or a body and the ground)",
                w.what
            ),
        ));
    }
    let Some(at) = w.at else {
        return Err(ck
            .error(
                Some(w.whole.clone()),
                format!("{} #{number} has no `at`", w.what),
            )
            .help("the point in each frame: `at = [[x, y, z], [x, y, z]]`"));
    };
    let points = pair_of_vectors(ck, at, "at")?;
    let written = Sides {
        what: w.what,
        kind: None,
        bodies: pair,
        points,
        at: at.span(),
    };
    check_sides(ck, &written, bodies)?;
    let name = match w.name {
        Some(n) if valid_name(n.get_ref()) => n.get_ref().clone(),
        Some(n) => {
            return Err(ck
                .error(
                    Some(n.span()),
                    format!("`{}` is not a valid {} name", n.get_ref(), w.what),
                )
                .help("a name is letters, digits and `_`, starting with a letter"));
        }
        None => format!("{}{number}", w.what),
    };
    Ok(Ends {
        name,
        bodies: pair,
        points,
    })
}

/// A finite number `≥ 0` under `key`; `required` refuses its absence.
fn nonnegative(
    ck: &Checker<'_>,
    w: &Written<'_>,
    key: &str,
    value: Option<&Spanned<f64>>,
    required: bool,
) -> Result<f64, Diagnostic> {
    let Some(value) = value else {
        let number = w.index + 1;
        let error = ck.error(
            Some(w.whole.clone()),
            format!("{} #{number} has no `{key}`", w.what),
        );
        return Err(match required {
            true => error.help(format!("e.g. `{key} = 10.0`")),
            false => error,
        });
    };
    match ck.finite(key, value)? {
        v if v >= 0.0 => Ok(v),
        v => Err(ck.error(
            Some(value.span()),
            format!(
                "the {key} of a {} must be zero or positive, not {v}",
                w.what
            ),
        )),
    }
}
