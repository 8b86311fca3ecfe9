//! `[system] discrete_lagrangian = "…"`: a researcher's own `L_d(q₀, q₁, h, t)` written with
//! `<q>_0`, `<q>_1`, `h` and `t`, compiled into [`ExprDiscreteLagrangian`] and stepped through
//! the discrete Legendre transforms `p_k = −D₁L_d(q_k, q_{k+1})`,
//! `p_{k+1} = D₂L_d(q_k, q_{k+1})` ([MW01] §1.3).
//!
//! The file's `L_d` is the method, and there is no continuous `L` behind it: no rule to choose,
//! no velocity to turn into a momentum, no energy, no continuous forces or constraints to
//! discretize. Every key that would need one is refused here, naming the key.
//!
//! [MW01]: marsden#references

use std::ops::Range;

use toml::Spanned;

use super::check::Checker;
use super::parameters::{self, Parameters};
use super::raw::{RawProblem, RawSystem};
use super::resolved::{Resolved, symbols};
use super::spec::LagrangianSpec;
use crate::error::Diagnostic;
use crate::model::ExprDiscreteLagrangian;
use crate::model::discrete_lagrangian::endpoint_inputs;
use marsden_expr::Program;

/// The key, as the messages name it.
pub use super::spec::DISCRETE_KEY as KEY;

/// Validates and compiles `discrete_lagrangian = "…"` (with `coordinates` and number
/// parameters).
///
/// # Errors
/// No `coordinates`, list parameters, a syntax error or an unknown name (with a suggestion).
pub(super) fn expression(
    ck: &Checker<'_>,
    text: &Spanned<String>,
    system: &RawSystem,
    params: &Parameters,
) -> Result<Resolved, Diagnostic> {
    let help = "e.g. `coordinates = [\"x\"]`; the expression then reads `x_0`, `x_1`, `h`, `t`";
    let coordinates =
        parameters::expression_coordinates(ck, "discrete_lagrangian", text, system, help)?;
    params.numbers_only(ck, "a discrete Lagrangian")?;
    let constants: Vec<(String, f64)> = params
        .numbers
        .iter()
        .map(|w| (w.name.clone(), w.value))
        .collect();
    let context = "[system] discrete_lagrangian";
    let expr = ck.parse_expr(context, text)?;
    let symbols = symbols(ck, endpoint_inputs(&coordinates), &constants, params)?;
    let program: Program = expr
        .compile(&symbols)
        .map_err(|e| ck.expr_error(context, text, &e))?;
    let ld = ExprDiscreteLagrangian::new(program, coordinates.len());
    let ld = LagrangianSpec::Discrete(ld);
    Ok(Resolved::expression(ld, coordinates, constants))
}

/// The keys a `discrete_lagrangian` file cannot have, refused with the key named; `Ok` for any
/// other file.
///
/// # Errors
/// `method`, `v`, `forces`, `constraints`, `[sensitivity]` or `certify` beside a
/// `discrete_lagrangian`.
pub fn refuse_unsupported(ck: &Checker<'_>, raw: &RawProblem) -> Result<(), Diagnostic> {
    let Some(system) = raw.system.as_ref().map(Spanned::get_ref) else {
        return Ok(());
    };
    if system.discrete_lagrangian.is_none() {
        return Ok(());
    }
    let refuse = |span: Range<usize>, key: &str, why: &str| {
        ck.error(Some(span), format!("`{key}` cannot be used with `{KEY}`"))
            .note(why.to_owned())
    };
    if let Some(m) = raw
        .integrator
        .as_ref()
        .and_then(|i| i.get_ref().method.as_ref())
    {
        return Err(refuse(m.span(), "method", "the file's L_d is the method")
            .help("remove `method` from [integrator]"));
    }
    if let Some(v) = raw.initial.as_ref().and_then(|i| i.get_ref().v.as_ref()) {
        return Err(refuse(
            v.span(),
            "v",
            "there is no continuous Lagrangian to turn a velocity into a momentum",
        )
        .help("give the initial momenta `p = [...]` (p₀ = −D₁L_d(q₀, q₁))"));
    }
    let without_l = "there is no continuous L to discretize them with";
    if let Some(f) = &system.forces {
        return Err(refuse(f.span(), "forces", without_l)
            .help("write the forcing into L_d, or use `lagrangian` with a method"));
    }
    if let Some(c) = &system.constraints {
        return Err(refuse(c.span(), "constraints", without_l)
            .help("use coordinates of the constrained configuration space in L_d"));
    }
    if let Some(s) = &raw.sensitivity {
        return Err(refuse(
            s.span(),
            "[sensitivity]",
            "the tangent runs are built from a continuous L and a rule",
        ));
    }
    let certify = raw
        .analysis
        .as_ref()
        .and_then(|a| a.get_ref().certify.as_ref());
    if let Some(c) = certify.filter(|c| *c.get_ref()) {
        return Err(refuse(
            c.span(),
            "certify",
            "the certificates are computed from a continuous L and a rule",
        )
        .help("remove `certify` from [analysis]"));
    }
    Ok(())
}
