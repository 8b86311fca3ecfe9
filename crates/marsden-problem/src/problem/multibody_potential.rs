//! A multibody file's `potential = "…"`: `U` over every body's attitude and every centre
//! ([`crate::model::multibody_potential::inputs`]) and the `parameters`, compiled.

use marsden_expr::Program;

use super::check::Checker;
use super::multibody::BodySpec;
use super::parameters::Parameters;
use super::raw::RawSystem;
use super::resolved::symbols;
use crate::error::Diagnostic;
use crate::model::multibody_potential::inputs;

/// The file's `potential` and `parameters`.
pub(super) struct Written {
    /// `U`, if written.
    pub potential: Option<Program>,
    /// The parameters with their values.
    pub parameters: Vec<(String, f64)>,
}

/// `potential = "…"` compiled over the bodies' entries and `parameters`.
pub(super) fn potential(
    ck: &Checker<'_>,
    system: &RawSystem,
    bodies: &[BodySpec],
) -> Result<Written, Diagnostic> {
    let params = Parameters::read(ck, system)?;
    let constants: Vec<(String, f64)> = (params.numbers.iter())
        .map(|w| (w.name.clone(), w.value))
        .collect();
    let Some(text) = &system.potential else {
        return Ok(Written {
            potential: None,
            parameters: constants,
        });
    };
    let members: Vec<(String, bool)> = (bodies.iter())
        .map(|b| (b.name.clone(), b.particle))
        .collect();
    let symbols = symbols(ck, inputs(&members), &constants, &params)?;
    let what = "[system] potential";
    let program = (ck.parse_expr(what, text)?.compile(&symbols)).map_err(|e| {
        ck.expr_error(what, text, &e).note(
            "a multibody potential reads `<body>_R11` … `<body>_R33` (bodies), `<name>_x`, \
             `<name>_y`, `<name>_z` (bodies and particles) and the parameters; not `t`",
        )
    })?;
    Ok(Written {
        potential: Some(program),
        parameters: constants,
    })
}
