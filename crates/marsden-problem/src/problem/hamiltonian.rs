//! `[system] hamiltonian = "…"`: `H(t, q, p)` written with the coordinates, their momenta
//! `p_<coordinate>` and `t`, compiled and turned into the Lagrangian the run uses
//! ([`crate::model::hamiltonian`]).

use toml::Spanned;

use super::check::Checker;
use super::parameters::{self, Parameters};
use super::raw::RawSystem;
use super::resolved::{Resolved, symbols};
use super::spec::LagrangianSpec;
use crate::error::Diagnostic;
use crate::model::ExprHamiltonian;
use crate::model::hamiltonian::cotangent_inputs;
use marsden::hamiltonian::HamiltonianLagrangian;
use marsden_expr::Program;

/// Validates and compiles `hamiltonian = "…"` (with `coordinates` and number parameters).
pub(super) fn expression(
    ck: &Checker<'_>,
    text: &Spanned<String>,
    system: &RawSystem,
    params: &Parameters,
) -> Result<Resolved, Diagnostic> {
    let help = "e.g. `coordinates = [\"theta\"]`; momenta are then named `p_theta`";
    let coordinates = parameters::expression_coordinates(ck, ("hamiltonian", text), system, help)?;
    params.numbers_only(ck, "an expression Hamiltonian")?;
    let constants: Vec<(String, f64)> = params
        .numbers
        .iter()
        .map(|w| (w.name.clone(), w.value))
        .collect();
    let expr = ck.parse_expr("[system] hamiltonian", text)?;
    let symbols = symbols(ck, cotangent_inputs(&coordinates), &constants, params)?;
    let program: Program = expr
        .compile(&symbols)
        .map_err(|e| ck.expr_error("[system] hamiltonian", text, &e))?;
    let n = coordinates.len();
    let reads_momenta = (n..2 * n).all(|slot| program.inputs_used().contains(&slot));
    if !reads_momenta {
        return Err(ck
            .error(
                Some(text.span()),
                "the Hamiltonian is not regular: some momentum `p_<coordinate>` does not appear in it",
            )
            .help("∂²H/∂p² must be invertible for the run to go through L = ⟨p, v⟩ − H"));
    }
    let h = HamiltonianLagrangian::new(ExprHamiltonian::new(program, n));
    let h = LagrangianSpec::Hamiltonian(h);
    Ok(Resolved::expression(h, coordinates, constants))
}
