//! One `[[system.body]]` or `[[system.particle]]` of a multibody file: a valid name, a
//! positive mass, and a body's inertia (the triangle inequalities required).

use std::ops::Range;

use marsden::lie::body::{Inertia, Moments};
use toml::Spanned;

use super::check::Checker;
use super::multibody::{BodySpec, valid_name};
use super::raw::RawInertia;
use super::raw_multibody::{RawBody, RawParticle};
use crate::error::Diagnostic;

/// `[[system.body]]`: a name, a mass and an inertia.
pub(super) fn body(
    ck: &Checker<'_>,
    raw: &Spanned<RawBody>,
    index: usize,
) -> Result<BodySpec, Diagnostic> {
    let b = raw.get_ref();
    let written = Named {
        what: "body",
        whole: raw.span(),
        index,
        name: b.name.as_ref(),
        mass: b.mass.as_ref(),
    };
    let (name, mass) = named_mass(ck, &written)?;
    let Some(written) = &b.inertia else {
        return Err(ck
            .error(Some(raw.span()), format!("body `{name}` has no `inertia`"))
            .help("e.g. `inertia = [0.0833, 0.0833, 0.001]` (principal moments about the centre of mass; or `[[system.particle]]` for a point mass)"));
    };
    let inertia = inertia(ck, written, index)?;
    Ok(BodySpec {
        name,
        mass,
        inertia,
        particle: false,
    })
}

/// `[[system.particle]]`: a name and a mass.
pub(super) fn particle(
    ck: &Checker<'_>,
    raw: &Spanned<RawParticle>,
    index: usize,
) -> Result<BodySpec, Diagnostic> {
    let p = raw.get_ref();
    let written = Named {
        what: "particle",
        whole: raw.span(),
        index,
        name: p.name.as_ref(),
        mass: p.mass.as_ref(),
    };
    let (name, mass) = named_mass(ck, &written)?;
    Ok(BodySpec {
        name,
        mass,
        inertia: Inertia::point(),
        particle: true,
    })
}

/// The name and mass of a body or particle as written.
struct Named<'a> {
    what: &'static str,
    whole: Range<usize>,
    index: usize,
    name: Option<&'a Spanned<String>>,
    mass: Option<&'a Spanned<f64>>,
}

/// A valid name and a positive mass.
fn named_mass(ck: &Checker<'_>, w: &Named<'_>) -> Result<(String, f64), Diagnostic> {
    let Some(name) = w.name else {
        return Err(ck
            .error(
                Some(w.whole.clone()),
                format!("{} #{} has no `name`", w.what, w.index + 1),
            )
            .help("its columns are `<name>_x`, `<name>_p_x`, …: e.g. `name = \"link1\"`"));
    };
    if !valid_name(name.get_ref()) {
        return Err(ck
            .error(
                Some(name.span()),
                format!("`{}` is not a valid {} name", name.get_ref(), w.what),
            )
            .help("a name is letters, digits and `_`, starting with a letter"));
    }
    let Some(mass) = w.mass else {
        return Err(ck
            .error(
                Some(w.whole.clone()),
                format!("{} `{}` has no `mass`", w.what, name.get_ref()),
            )
            .help("every body and particle of a multibody system moves: give its `mass`"));
    };
    match ck.finite("mass", mass)? {
        m if m > 0.0 => Ok((name.get_ref().clone(), m)),
        m => Err(ck.error(
            Some(mass.span()),
            format!("the mass must be positive, not {m}"),
        )),
    }
}

/// The inertia of a body of a mass distribution: the triangle inequalities are required.
fn inertia(
    ck: &Checker<'_>,
    written: &Spanned<RawInertia>,
    index: usize,
) -> Result<Inertia, Diagnostic> {
    let example = "e.g. `inertia = [0.0833, 0.0833, 0.001]`";
    let rows = super::rigid::inertia_rows(ck, written, example)?;
    Inertia::validated(index, &rows, Moments::Physical).map_err(|e| {
        ck.error(Some(written.span()), format!("invalid inertia: {e}"))
            .help(
                "a body's principal moments are positive and each at most the sum of the other two",
            )
    })
}
