//! What every kind of `[system]` Lagrangian resolves to (a catalog system, `lagrangian`,
//! `hamiltonian`, `discrete_lagrangian`), and the symbol table their expressions compile
//! against: shared by [`super::system`] and the kinds it hands off to
//! ([`super::hamiltonian`], [`super::discrete`]).

use marsden_expr::Symbols;

use super::check::Checker;
use super::parameters::Parameters;
use super::spec::LagrangianSpec;
use crate::error::Diagnostic;

/// A `[system]`'s Lagrangian with its coordinates and parameters.
pub(super) struct Resolved {
    /// The Lagrangian (or `L_d`).
    pub lagrangian: LagrangianSpec,
    /// Coordinate names.
    pub coordinates: Vec<String>,
    /// Every scalar parameter with its value.
    pub parameters: Vec<(String, f64)>,
    /// `nbody` masses.
    pub masses: Option<Vec<f64>>,
}

impl Resolved {
    /// An expression system: no masses.
    pub(super) fn expression(
        lagrangian: LagrangianSpec,
        coordinates: Vec<String>,
        parameters: Vec<(String, f64)>,
    ) -> Self {
        Resolved {
            lagrangian,
            coordinates,
            parameters,
            masses: None,
        }
    }
}

/// A symbol table of `inputs` (slots in order) and the parameters as constants.
pub(super) fn symbols(
    ck: &Checker<'_>,
    inputs: Vec<String>,
    constants: &[(String, f64)],
    params: &Parameters,
) -> Result<Symbols, Diagnostic> {
    let mut symbols = Symbols::with_inputs(&inputs).map_err(|e| Diagnostic::new(e.to_string()))?;
    for (name, value) in constants {
        if let Err(e) = symbols.add_constant(name, *value) {
            let span = params.number(name).map(|w| w.span.clone());
            let clash = if inputs.contains(name) {
                format!("parameter `{name}` has the name of a coordinate, a velocity or `t`")
            } else {
                format!("parameter `{name}`: {e}")
            };
            return Err(ck.error(span, clash));
        }
    }
    Ok(symbols)
}
