//! Numbers of a problem file written as constant expressions: `t_end = "20*pi"`,
//! `h = "2*pi/100"`, `q = ["pi/2", 0]`. A string where a number is expected is compiled with
//! the expression language (`marsden_expr`: arithmetic, `pi`, the elementary functions; no
//! names of the file) and folded to its value, which must be finite; a plain number stays
//! exactly what TOML read.

use serde::de::{Deserialize, Deserializer, Error as _};
use toml::Spanned;

use super::raw::SpannedList;

/// A number, or the text of a constant expression evaluated at once.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Number(pub f64);

impl<'de> Deserialize<'de> for Number {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        #[derive(serde::Deserialize)]
        #[serde(untagged)]
        enum Written {
            Integer(i64),
            Float(f64),
            Text(String),
        }
        match Written::deserialize(deserializer).map_err(|_| {
            D::Error::custom("expected a number or a constant expression such as \"2*pi/100\"")
        })? {
            // Exact below 2⁵³, as TOML's own integers in float fields.
            Written::Integer(i) => Ok(Number(i as f64)),
            Written::Float(x) => Ok(Number(x)),
            Written::Text(text) => constant(&text).map(Number).map_err(D::Error::custom),
        }
    }
}

/// The value of the constant expression `text`.
///
/// # Errors
/// The expression's own message (an unknown name, a syntax error), or a value that is not
/// finite.
pub fn constant(text: &str) -> Result<f64, String> {
    let none: [&str; 0] = [];
    let symbols = marsden_expr::Symbols::with_inputs(none).map_err(|e| e.to_string())?;
    let program = marsden_expr::Program::compile(text, &symbols)
        .map_err(|e| format!("`{text}` is not a constant expression: {e}"))?;
    let value: f64 = program.eval(&[]);
    match value.is_finite() {
        true => Ok(value),
        false => Err(format!(
            "`{text}` evaluates to {value}, not a finite number"
        )),
    }
}

/// `deserialize_with` for an optional spanned number ([`Number`]).
///
/// # Errors
/// As [`Number`]'s deserialisation.
pub fn spanned<'de, D: Deserializer<'de>>(d: D) -> Result<Option<Spanned<f64>>, D::Error> {
    let written: Option<Spanned<Number>> = Option::deserialize(d)?;
    Ok(written.map(unwrap))
}

/// `deserialize_with` for an optional spanned list of numbers ([`Number`]).
///
/// # Errors
/// As [`Number`]'s deserialisation.
pub fn spanned_list<'de, D: Deserializer<'de>>(d: D) -> Result<Option<SpannedList<f64>>, D::Error> {
    let written: Option<SpannedList<Number>> = Option::deserialize(d)?;
    Ok(written.map(list))
}

/// A spanned list of [`Number`]s as numbers, spans kept.
pub fn list(written: SpannedList<Number>) -> SpannedList<f64> {
    let span = written.span();
    let values = written.into_inner().into_iter().map(unwrap).collect();
    Spanned::new(span, values)
}

/// A spanned [`Number`] as a number, its span kept.
pub fn unwrap(written: Spanned<Number>) -> Spanned<f64> {
    let span = written.span();
    Spanned::new(span, written.into_inner().0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(serde::Deserialize)]
    struct T {
        #[serde(default, deserialize_with = "spanned")]
        h: Option<Spanned<f64>>,
        #[serde(default, deserialize_with = "spanned_list")]
        q: Option<SpannedList<f64>>,
    }

    #[test]
    fn numbers_and_constant_expressions() {
        let t: T = toml::from_str("h = \"2*pi/100\"\nq = [\"pi/2\", 0, 1.5]").unwrap();
        assert_eq!(*t.h.unwrap().get_ref(), 2.0 * std::f64::consts::PI / 100.0);
        let q: Vec<f64> =
            t.q.unwrap()
                .into_inner()
                .into_iter()
                .map(|x| *x.get_ref())
                .collect();
        assert_eq!(q, [std::f64::consts::FRAC_PI_2, 0.0, 1.5]);
        let t: T = toml::from_str("h = 0.05").unwrap();
        assert_eq!(*t.h.unwrap().get_ref(), 0.05);
    }

    #[test]
    fn unknown_names_and_non_finite_values_are_refused() {
        let e = toml::from_str::<T>("h = \"2*pj\"")
            .err()
            .unwrap()
            .to_string();
        assert!(
            e.contains("not a constant expression") && e.contains("pj"),
            "{e}"
        );
        let e = toml::from_str::<T>("h = \"1/0\"")
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("not a finite number"), "{e}");
    }
}

/// Constant expressions beyond the grid and the initial state: parameters (scalars and lists),
/// the Newton tolerance, and a sweep's values and range, read through the whole validation.
#[cfg(test)]
mod in_a_file {
    use crate::{Overrides, from_toml_str};
    use std::f64::consts::PI;

    const TEXT: &str = "[system]\ncoordinates = [\"x\"]\n\
        parameters = { w = \"2*pi\" }\n\
        lagrangian = \"0.5*x_dot^2 - 0.5*w^2*x^2\"\n\
        [initial]\nq = [1]\nv = [0]\n\
        [integrator]\nh = 0.01\nsteps = 10\ntolerance = \"1e-12/10\"\n\
        [sweep]\nparameter = \"w\"\nvalues = [\"pi\", \"2*pi\"]\n";

    #[test]
    fn parameters_tolerance_and_sweep_values_take_constant_expressions() {
        let spec = from_toml_str(TEXT, "p.toml", &Overrides::default()).unwrap();
        let w = spec
            .system
            .parameters
            .iter()
            .find(|(n, _)| n == "w")
            .unwrap();
        assert_eq!(w.1, 2.0 * PI);
        assert_eq!(spec.integrator.newton.residual_tolerance, 1e-12 / 10.0);
        let sweep = spec.sweep.unwrap();
        assert_eq!(
            (sweep.values_of(0), sweep.values_of(1)),
            (vec![PI], vec![2.0 * PI])
        );
        let ranged = TEXT.replace(
            "values = [\"pi\", \"2*pi\"]",
            "range = { start = \"pi/2\", stop = \"pi\", count = 3 }",
        );
        let sweep = from_toml_str(&ranged, "p.toml", &Overrides::default())
            .unwrap()
            .sweep;
        assert_eq!(sweep.unwrap().values_of(0), vec![PI / 2.0]);
    }

    #[test]
    fn a_parameter_naming_an_unknown_symbol_is_refused_with_its_place() {
        let text = TEXT.replace("w = \"2*pi\"", "w = \"2*pj\"");
        let e = from_toml_str(&text, "p.toml", &Overrides::default()).unwrap_err();
        let shown = e.to_string();
        assert!(shown.contains("pj"), "{shown}");
    }
}
