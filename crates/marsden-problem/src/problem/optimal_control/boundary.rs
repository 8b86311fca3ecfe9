//! `start`, `end` and `bounds` of `[optimal_control]`: boundary data with free components, and
//! simple bounds on controls and coordinates.

use toml::Spanned;

use super::super::check::{Checker, count_coordinates, plural};
use super::super::raw::{Ordered, SpannedList};
use super::raw::{RawComponent, RawEnd};
use crate::error::Diagnostic;

/// The rate given at one end, component by component (`None`: free).
#[derive(Debug, Clone, PartialEq)]
pub enum RateSpec {
    /// Velocities `v`: every component fixed, or none.
    Velocity(Vec<Option<f64>>),
    /// Momenta `p`, each component fixed or free.
    Momentum(Vec<Option<f64>>),
}

/// The conditions at one end of the horizon.
#[derive(Debug, Clone, PartialEq)]
pub struct EndSpec {
    /// Positions (`None`: free).
    pub q: Vec<Option<f64>>,
    /// Velocities or momenta.
    pub rate: RateSpec,
}

/// `lower ≤ x ≤ upper` per component (infinite: no bound).
#[derive(Debug, Clone, PartialEq)]
pub struct BoundsSpec {
    /// Lower bounds.
    pub lower: Vec<f64>,
    /// Upper bounds.
    pub upper: Vec<f64>,
}

impl BoundsSpec {
    fn none(len: usize) -> Self {
        Self {
            lower: vec![f64::NEG_INFINITY; len],
            upper: vec![f64::INFINITY; len],
        }
    }

    /// Whether any component is bounded.
    pub fn any(&self) -> bool {
        self.lower.iter().chain(&self.upper).any(|b| b.is_finite())
    }
}

/// Checks `start` or `end` (`which`) against the coordinates; a missing table leaves
/// everything free.
///
/// # Errors
/// Both `v` and `p`; a list of the wrong length; a non-finite value; velocities partly free.
pub fn end(
    ck: &Checker<'_>,
    which: &str,
    raw: Option<&Spanned<RawEnd>>,
    coordinates: &[String],
) -> Result<EndSpec, Diagnostic> {
    let n = coordinates.len();
    let Some(raw) = raw else {
        return Ok(EndSpec {
            q: vec![None; n],
            rate: RateSpec::Momentum(vec![None; n]),
        });
    };
    let table = raw.get_ref();
    let q = match &table.q {
        Some(list) => components(ck, &format!("{which} q"), list, coordinates)?,
        None => vec![None; n],
    };
    let rate = match (&table.v, &table.p) {
        (Some(_), Some(p)) => {
            return Err(ck
                .error(
                    Some(p.span()),
                    format!(
                        "`{which}` gives both `v` and `p`: the rate at an end is one or the other"
                    ),
                )
                .help("keep `v` (velocities) or `p` (momenta); components may be \"free\""));
        }
        (Some(v), None) => {
            let values = components(ck, &format!("{which} v"), v, coordinates)?;
            let free = values.iter().filter(|x| x.is_none()).count();
            if free != 0 && free != n {
                return Err(ck
                    .error(
                        Some(v.span()),
                        format!("`{which} v` has free and fixed components"),
                    )
                    .note("a fixed momentum ∂L/∂v needs every component of v")
                    .help("fix every velocity, or give momenta `p` with free components"));
            }
            RateSpec::Velocity(values)
        }
        (None, Some(p)) => {
            RateSpec::Momentum(components(ck, &format!("{which} p"), p, coordinates)?)
        }
        (None, None) => RateSpec::Momentum(vec![None; n]),
    };
    Ok(EndSpec { q, rate })
}

fn components(
    ck: &Checker<'_>,
    what: &str,
    list: &SpannedList<RawComponent>,
    coordinates: &[String],
) -> Result<Vec<Option<f64>>, Diagnostic> {
    let values = list.get_ref();
    if values.len() != coordinates.len() {
        return Err(ck.error(
            Some(list.span()),
            format!(
                "{what} has {} value{}, but the system has {}",
                values.len(),
                plural(values.len()),
                count_coordinates(coordinates)
            ),
        ));
    }
    values
        .iter()
        .enumerate()
        .map(|(i, v)| match *v.get_ref() {
            RawComponent::Free => Ok(None),
            RawComponent::Value(x) => ck
                .finite(&format!("{what}[{i}]"), &Spanned::new(v.span(), x))
                .map(Some),
        })
        .collect()
}

/// `[optimal_control.bounds]`: `name = [lo, hi]` for controls and coordinates, split into
/// control bounds and state bounds.
///
/// # Errors
/// An unknown name, a list that is not two numbers, NaN, `lo > hi`, a name given twice, a
/// coordinate's bounds that exclude its fixed `start` or `end` position (no trajectory could
/// meet both).
pub fn bounds(
    ck: &Checker<'_>,
    raw: Option<&Spanned<Ordered<SpannedList<f64>>>>,
    controls: &[String],
    coordinates: &[String],
    start: &EndSpec,
    end: &EndSpec,
) -> Result<(BoundsSpec, BoundsSpec), Diagnostic> {
    let mut on_u = BoundsSpec::none(controls.len());
    let mut on_q = BoundsSpec::none(coordinates.len());
    let Some(raw) = raw else {
        return Ok((on_u, on_q));
    };
    let mut seen: Vec<&str> = Vec::new();
    for (name, list) in &raw.get_ref().0 {
        let at = Some(list.span());
        let target = match (
            controls.iter().position(|c| c == name),
            coordinates.iter().position(|c| c == name),
        ) {
            (Some(j), _) => (&mut on_u, j, false),
            (None, Some(i)) => (&mut on_q, i, true),
            (None, None) => {
                let names = controls.iter().chain(coordinates).map(String::as_str);
                return Err(ck
                    .error(
                        at,
                        format!("bounds on `{name}`: it is neither a control nor a coordinate"),
                    )
                    .suggest(marsden_expr::closest(name, names))
                    .note(format!(
                        "controls: {}; coordinates: {}",
                        controls.join(", "),
                        coordinates.join(", ")
                    )));
            }
        };
        if seen.contains(&name.as_str()) {
            return Err(ck.error(at, format!("bounds on `{name}` are given twice")));
        }
        seen.push(name);
        let [lo, hi] = list.get_ref().as_slice() else {
            return Err(ck
                .error(
                    at,
                    format!("bounds on `{name}` must be two numbers [lo, hi]"),
                )
                .help("e.g. u = [-1.0, 1.0]; use -inf or inf for no bound on one side"));
        };
        let (lo, hi) = (*lo.get_ref(), *hi.get_ref());
        if lo.is_nan() || hi.is_nan() {
            return Err(ck.error(at, format!("bounds on `{name}` are not numbers (nan)")));
        }
        if lo > hi {
            return Err(ck.error(
                at,
                format!("bounds on `{name}`: the lower bound {lo} is above the upper bound {hi}"),
            ));
        }
        let (bounds, index, coordinate) = target;
        if coordinate {
            let bounds = CoordinateBounds {
                name,
                index,
                lo,
                hi,
            };
            excludes_an_end(ck, at.clone(), &bounds, start, end)?;
        }
        bounds.lower[index] = lo;
        bounds.upper[index] = hi;
    }
    Ok((on_u, on_q))
}

/// The bounds `[lo, hi]` given on one coordinate.
struct CoordinateBounds<'a> {
    /// The coordinate's name.
    name: &'a str,
    /// Its index among the coordinates.
    index: usize,
    /// The lower bound.
    lo: f64,
    /// The upper bound.
    hi: f64,
}

/// Refuses the `bounds` `[lo, hi]` of a coordinate if they exclude its fixed position at
/// `start` or `end`.
fn excludes_an_end(
    ck: &Checker<'_>,
    at: Option<std::ops::Range<usize>>,
    bounds: &CoordinateBounds<'_>,
    start: &EndSpec,
    end: &EndSpec,
) -> Result<(), Diagnostic> {
    let &CoordinateBounds {
        name,
        index,
        lo,
        hi,
    } = bounds;
    for (which, spec) in [("start", start), ("end", end)] {
        if let Some(q) = spec.q.get(index).copied().flatten()
            && !(lo..=hi).contains(&q)
        {
            return Err(ck
                .error(
                    at,
                    format!("bounds on `{name}` = [{lo}, {hi}] exclude its `{which}` value {q}"),
                )
                .note("the bounds hold at every node, the first and the last included")
                .help(format!(
                    "widen the bounds to contain {q}, or change `{which}`"
                )));
        }
    }
    Ok(())
}
