//! `[system] controls`: the names of the controls `u`, checked, and the symbol tables the
//! forces compile against — with the controls as the constant 0 for a `marsden run` (the
//! forward simulation with zero controls), as extra input slots after `[q, q̇, t]` for
//! `marsden optimize` and for a run that reads them from a `control_table`.

use std::ops::Range;

use marsden_expr::{Expr, Symbols, is_identifier, is_reserved};

use super::super::check::Checker;
use super::super::raw::RawSystem;
use crate::error::Diagnostic;

/// A declared control: its name and where it is written.
#[derive(Debug, Clone, PartialEq)]
pub struct Control {
    /// The name, usable in `forces` and the costs.
    pub name: String,
    /// Its place in `controls = [...]`.
    pub span: Range<usize>,
}

/// The declared controls, checked against `symbols` (the coordinates, velocities, `t` and the
/// parameters): identifiers, distinct, no clash with another name.
///
/// # Errors
/// A diagnostic at the control's name.
pub fn declared(
    ck: &Checker<'_>,
    system: &RawSystem,
    symbols: &Symbols,
) -> Result<Vec<Control>, Diagnostic> {
    let Some(list) = &system.controls else {
        return Ok(Vec::new());
    };
    let mut out: Vec<Control> = Vec::new();
    for value in list.get_ref() {
        let name = value.get_ref();
        let at = Some(value.span());
        if !is_identifier(name) || is_reserved(name) {
            return Err(ck
                .error(at, format!("control `{name}` is not a usable name"))
                .help("use letters, digits and '_' (not a function name such as `sin`)"));
        }
        if out.iter().any(|c| &c.name == name) {
            return Err(ck.error(at, format!("control `{name}` is declared twice")));
        }
        if symbols.get(name).is_some() {
            return Err(ck.error(
                at,
                format!(
                    "control `{name}` has the name of a coordinate, a velocity, `t` or a parameter"
                ),
            ));
        }
        out.push(Control {
            name: name.clone(),
            span: value.span(),
        });
    }
    Ok(out)
}

/// `symbols` with every declared control as the constant 0: the forces of a `marsden run`.
///
/// # Errors
/// As [`declared`].
pub fn as_zero(
    ck: &Checker<'_>,
    system: &RawSystem,
    mut symbols: Symbols,
) -> Result<Symbols, Diagnostic> {
    for control in declared(ck, system, &symbols)? {
        symbols
            .add_constant(&control.name, 0.0)
            .map_err(|e| ck.error(Some(control.span.clone()), e.to_string()))?;
    }
    Ok(symbols)
}

/// The symbols of a `marsden run`'s forces: the controls as inputs read from the
/// `control_table` ([`super::super::control_table`]) if one is given, else as 0 ([`as_zero`]).
///
/// # Errors
/// As [`declared`].
pub fn for_run(
    ck: &Checker<'_>,
    system: &RawSystem,
    symbols: Symbols,
) -> Result<Symbols, Diagnostic> {
    match super::super::control_table::given(system) {
        true => {
            let controls = declared(ck, system, &symbols)?;
            as_inputs(ck, &controls, symbols)
        }
        false => as_zero(ck, system, symbols),
    }
}

/// `symbols` with the controls as input slots after the existing ones, in declared order.
///
/// # Errors
/// A diagnostic at the control if the table refuses it.
pub fn as_inputs(
    ck: &Checker<'_>,
    controls: &[Control],
    mut symbols: Symbols,
) -> Result<Symbols, Diagnostic> {
    let first = symbols.input_count();
    for (j, control) in controls.iter().enumerate() {
        symbols
            .add_input(&control.name, first + j)
            .map_err(|e| ck.error(Some(control.span.clone()), e.to_string()))?;
    }
    Ok(symbols)
}

/// Refuses a control that no force uses: it could not act on the system.
///
/// # Errors
/// A diagnostic at the unused control.
pub fn all_used(ck: &Checker<'_>, controls: &[Control], forces: &[Expr]) -> Result<(), Diagnostic> {
    for control in controls {
        let used = forces
            .iter()
            .any(|f| f.names().iter().any(|n| *n == control.name));
        if !used {
            return Err(ck
                .error(
                    Some(control.span.clone()),
                    format!("control `{}` is not used by any force", control.name),
                )
                .note("a control acts on the system only through `[system] forces`")
                .help(format!(
                    "use it in `forces`, e.g. forces = [\"{}\"], or remove it",
                    control.name
                )));
        }
    }
    Ok(())
}
