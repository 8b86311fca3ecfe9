//! Named symmetries: `translation = "x"` and `rotation = "z"` in a `[[system.symmetry]]`, instead
//! of a generator list.
//!
//! The names refer to Cartesian coordinates. A coordinate belongs to axis `a` (`x`, `y` or `z`)
//! if its name is `a` itself or `a` followed by a particle label: digits, optionally after `_`
//! (`x`, `x1`, `x_2`; the N-body coordinates `x1 y1 z1 x2 …`). Then
//!
//! | key | generator `ξ_Q(q)` | momentum map `J = ⟨p, ξ_Q⟩` | default name |
//! |---|---|---|---|
//! | `translation = "x"` | `1` on every `x`-coordinate, `0` elsewhere | total momentum `Σᵢ p_xᵢ` | `Px` |
//! | `rotation = "z"` | `(−yᵢ, xᵢ)` on every pair `(xᵢ, yᵢ)` | total angular momentum `Σᵢ xᵢ p_yᵢ − yᵢ p_xᵢ` | `Lz` |
//!
//! `rotation = "x"` pairs `(yᵢ, zᵢ)`, `rotation = "y"` pairs `(zᵢ, xᵢ)` (right-handed: the
//! generator is `e_a × qᵢ`, [MR99] §9.2). For `builtin = "nbody"` these are the total linear
//! and angular momenta of the bodies, component by component. The generator lists written
//! out are the same expressions, so a named symmetry and its list give identical runs.
//!
//! [MR99]: marsden#references

use toml::Spanned;

use super::check::Checker;
use super::raw::RawSymmetry;
use crate::error::Diagnostic;
use crate::model::Symmetry;
use marsden_expr::{Expr, ProgramSet, Symbols};

/// The axes a symmetry can name.
const AXES: [&str; 3] = ["x", "y", "z"];

/// A named symmetry, expanded: its default name and one generator expression per coordinate.
#[derive(Debug, Clone, PartialEq)]
pub struct Named {
    /// `Px`, `Lz`, …
    pub default_name: String,
    /// `ξ_Q(q)`, one expression per coordinate.
    pub generator: Vec<String>,
    /// Where the key's value is written.
    pub span: std::ops::Range<usize>,
}

impl Named {
    /// The symmetry called `name`, compiled against `symbols` (the coordinates).
    ///
    /// # Errors
    /// Only if an expression does not compile (it is built from the coordinate names, so it
    /// does), pointed at the key.
    pub fn compile(
        &self,
        ck: &Checker<'_>,
        name: String,
        symbols: &Symbols,
    ) -> Result<Symmetry, Diagnostic> {
        let programs = self
            .generator
            .iter()
            .map(|text| {
                Expr::parse(text)
                    .and_then(|e| e.compile(symbols))
                    .map_err(|e| ck.error(Some(self.span.clone()), e.kind().to_string()))
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Symmetry::new(name, ProgramSet::from_programs(programs)))
    }
}

/// The named symmetry of `raw` (`None` if it names none).
///
/// # Errors
/// Both a name and a `generator`, two names, or a name that does not fit the coordinates (with
/// the names that do).
pub fn expand(
    ck: &Checker<'_>,
    raw: &Spanned<RawSymmetry>,
    coordinates: &[String],
) -> Result<Option<Named>, Diagnostic> {
    let s = raw.get_ref();
    let key = match (&s.translation, &s.rotation) {
        (None, None) => return Ok(None),
        (Some(_), Some(r)) => {
            return Err(ck
                .error(
                    Some(r.span()),
                    "give either `translation` or `rotation`, not both",
                )
                .help("declare each symmetry in its own [[system.symmetry]]"));
        }
        (Some(t), None) => (Kind::Translation, t),
        (None, Some(r)) => (Kind::Rotation, r),
    };
    let (kind, value) = key;
    if let Some(g) = &s.generator {
        return Err(ck
            .error(
                Some(g.span()),
                format!("give either `generator` or `{}`, not both", kind.key()),
            )
            .help("a named symmetry builds its generator from the coordinate names"));
    }
    let axis = value.get_ref().as_str();
    match kind.generator(axis, coordinates) {
        Ok(generator) => Ok(Some(Named {
            default_name: kind.default_name(axis),
            generator,
            span: value.span(),
        })),
        Err(why) => Err(ck
            .error(
                Some(value.span()),
                format!(
                    "`{} = \"{axis}\"` does not fit this system: {why}",
                    kind.key()
                ),
            )
            .help(kind.valid_names(coordinates))),
    }
}

/// Which named symmetry.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    Translation,
    Rotation,
}

impl Kind {
    fn key(self) -> &'static str {
        match self {
            Kind::Translation => "translation",
            Kind::Rotation => "rotation",
        }
    }

    fn default_name(self, axis: &str) -> String {
        match self {
            Kind::Translation => format!("P{axis}"),
            Kind::Rotation => format!("L{axis}"),
        }
    }

    /// The generator expressions, or why the axis does not fit.
    fn generator(self, axis: &str, coordinates: &[String]) -> Result<Vec<String>, String> {
        if !AXES.contains(&axis) {
            return Err(format!(
                "the axis must be \"x\", \"y\" or \"z\", not \"{axis}\""
            ));
        }
        match self {
            Kind::Translation => translation(axis, coordinates),
            Kind::Rotation => rotation(axis, coordinates),
        }
    }

    /// `valid here: translation = "x", "y"` or why none is.
    fn valid_names(self, coordinates: &[String]) -> String {
        let fits: Vec<String> = AXES
            .iter()
            .filter(|a| self.generator(a, coordinates).is_ok())
            .map(|a| format!("\"{a}\""))
            .collect();
        if fits.is_empty() {
            format!(
                "no `{}` fits the coordinates ({}): name them x, y, z (or x1, y1, z1, …), or give \
                 `generator = [...]`, one expression per coordinate",
                self.key(),
                coordinates.join(", ")
            )
        } else {
            format!(
                "valid here: {} = {} (coordinates {})",
                self.key(),
                fits.join(", "),
                coordinates.join(", ")
            )
        }
    }
}

/// The particle label of `coordinate` on `axis`: `Some("")` for `x`, `Some("1")` for `x1`,
/// `Some("_2")` for `x_2`, `None` for another axis or name.
fn label<'c>(coordinate: &'c str, axis: &str) -> Option<&'c str> {
    let rest = coordinate.strip_prefix(axis)?;
    let digits = rest.strip_prefix('_').unwrap_or(rest);
    let is_label =
        rest.is_empty() || (!digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()));
    is_label.then_some(rest)
}

/// `1` on every coordinate of `axis`, `0` elsewhere.
fn translation(axis: &str, coordinates: &[String]) -> Result<Vec<String>, String> {
    if !coordinates.iter().any(|c| label(c, axis).is_some()) {
        return Err(format!(
            "no coordinate is named {axis} or {axis}<i> (coordinates {})",
            coordinates.join(", ")
        ));
    }
    Ok(coordinates
        .iter()
        .map(|c| if label(c, axis).is_some() { "1" } else { "0" }.to_owned())
        .collect())
}

/// `(−bᵢ, aᵢ)` on every pair `(aᵢ, bᵢ)` of the plane normal to `axis`, `0` elsewhere.
fn rotation(axis: &str, coordinates: &[String]) -> Result<Vec<String>, String> {
    let (a, b) = match axis {
        "x" => ("y", "z"),
        "y" => ("z", "x"),
        _ => ("x", "y"),
    };
    let mut generator = vec!["0".to_owned(); coordinates.len()];
    let mut pairs = 0;
    for (i, c) in coordinates.iter().enumerate() {
        let Some(l) = label(c, a) else { continue };
        let partner = format!("{b}{l}");
        let Some(j) = coordinates.iter().position(|d| *d == partner) else {
            return Err(format!("coordinate `{c}` has no partner `{partner}`"));
        };
        generator[i] = format!("-{partner}");
        generator[j] = c.clone();
        pairs += 1;
    }
    for c in coordinates {
        if let Some(l) = label(c, b)
            && !coordinates.iter().any(|d| *d == format!("{a}{l}"))
        {
            return Err(format!("coordinate `{c}` has no partner `{a}{l}`"));
        }
    }
    if pairs == 0 {
        return Err(format!(
            "no pair of coordinates ({a}, {b}) or ({a}<i>, {b}<i>) (coordinates {})",
            coordinates.join(", ")
        ));
    }
    Ok(generator)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(list: &[&str]) -> Vec<String> {
        list.iter().map(|s| (*s).to_owned()).collect()
    }

    #[test]
    fn nbody_lists_are_the_written_ones() {
        let c = names(&["x1", "y1", "z1", "x2", "y2", "z2"]);
        assert_eq!(
            translation("x", &c).unwrap(),
            names(&["1", "0", "0", "1", "0", "0"])
        );
        assert_eq!(
            rotation("z", &c).unwrap(),
            names(&["-y1", "x1", "0", "-y2", "x2", "0"])
        );
        assert_eq!(
            rotation("x", &c).unwrap(),
            names(&["0", "-z1", "y1", "0", "-z2", "y2"])
        );
        assert_eq!(
            rotation("y", &names(&["x", "y", "z"])).unwrap(),
            names(&["z", "0", "-x"])
        );
    }

    #[test]
    fn names_that_do_not_fit() {
        let planar = names(&["x", "y"]);
        assert!(translation("z", &planar).is_err());
        assert!(rotation("x", &planar).is_err());
        assert!(rotation("z", &names(&["x", "y", "x2"])).is_err());
        assert!(translation("x", &names(&["theta"])).is_err());
        assert!(label("xi", "x").is_none());
        assert_eq!(label("x_2", "x"), Some("_2"));
    }
}
