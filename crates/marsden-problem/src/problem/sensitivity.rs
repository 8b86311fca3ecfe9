//! `[sensitivity]`: which derivatives of the run to compute — with respect to the initial state
//! (`initial = true`) and to named scalar parameters (`parameters = ["mu"]`, of the Lagrangian,
//! the forces or the constraints) — checked against the system, with the parametric model
//! compiled when parameters are named.

use std::ops::Range;

use toml::Spanned;

use super::check::Checker;
use super::raw::RawSensitivity;
use super::spec::{LagrangianSpec, SystemSpec};
use crate::error::Diagnostic;
use crate::model::{ExprParametric, ParametricTexts};
use marsden_expr::closest;

/// `[sensitivity]`, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct SensitivitySpec {
    /// Report the columns `∂/∂(q₀, p₀)`.
    pub initial: bool,
    /// The parameters differentiated with respect to, in the file's order.
    pub parameters: Vec<String>,
    /// The Lagrangian and forces with those parameters as inputs (`None` without parameters).
    pub model: Option<ExprParametric>,
}

/// Validates `[sensitivity]` against the system.
pub fn sensitivity(
    ck: &Checker<'_>,
    raw: Option<&Spanned<RawSensitivity>>,
    system: &SystemSpec,
) -> Result<Option<SensitivitySpec>, Diagnostic> {
    let Some(raw) = raw else {
        return Ok(None);
    };
    let table = raw.get_ref();
    let initial = table.initial.as_ref().is_some_and(|b| *b.get_ref());
    let names = parameter_names(ck, table, system)?;
    if !initial && names.is_empty() {
        return Err(ck
            .error(Some(raw.span()), "[sensitivity] asks for no derivative")
            .help("add `initial = true` and/or `parameters = [\"…\"]`"));
    }
    let model = match names.is_empty() {
        true => None,
        false => Some(parametric(ck, raw.span(), system, &names)?),
    };
    Ok(Some(SensitivitySpec {
        initial,
        parameters: names.into_iter().map(|(n, _)| n).collect(),
        model,
    }))
}

/// The named parameters, each a scalar parameter of the system, none twice.
fn parameter_names(
    ck: &Checker<'_>,
    table: &RawSensitivity,
    system: &SystemSpec,
) -> Result<Vec<(String, Range<usize>)>, Diagnostic> {
    let Some(list) = &table.parameters else {
        return Ok(Vec::new());
    };
    let known: Vec<&str> = system.parameters.iter().map(|(n, _)| n.as_str()).collect();
    let mut names: Vec<(String, Range<usize>)> = Vec::new();
    for name in list.get_ref() {
        let text = name.get_ref();
        if !known.contains(&text.as_str()) {
            let listed = match known.is_empty() {
                true => "the system has no scalar parameters".to_owned(),
                false => format!("scalar parameters: {}", known.join(", ")),
            };
            return Err(ck
                .error(
                    Some(name.span()),
                    format!("[sensitivity] names `{text}`, which is not a parameter"),
                )
                .suggest(closest(text, known.iter().copied()))
                .note(listed));
        }
        if names.iter().any(|(n, _)| n == text) {
            return Err(ck.error(
                Some(name.span()),
                format!("parameter `{text}` is named twice in [sensitivity]"),
            ));
        }
        names.push((text.clone(), name.span()));
    }
    Ok(names)
}

/// The Lagrangian and forces recompiled with `names` as inputs.
fn parametric(
    ck: &Checker<'_>,
    span: Range<usize>,
    system: &SystemSpec,
    names: &[(String, Range<usize>)],
) -> Result<ExprParametric, Diagnostic> {
    let refuse = |what: &str| {
        ck.error(
            Some(span.clone()),
            format!("parameter sensitivities are not supported for {what}"),
        )
        .help("use `initial = true` alone, or write the Lagrangian as `lagrangian = \"…\"`")
    };
    let catalog_coordinates;
    let (text, coordinates) = match &system.lagrangian {
        LagrangianSpec::Expression(l) => (l.program().text(), &system.coordinates),
        LagrangianSpec::Builtin { builtin, .. } if !builtin.needs_masses() => {
            catalog_coordinates = builtin.coordinates(0);
            (builtin.formula(), &catalog_coordinates)
        }
        LagrangianSpec::Builtin { .. } => return Err(refuse("the N-body builtin")),
        LagrangianSpec::Hamiltonian(_) => return Err(refuse("a `hamiltonian` system")),
        LagrangianSpec::Discrete(_) => return Err(refuse("a `discrete_lagrangian` system")),
        LagrangianSpec::Rigid(_) => return Err(refuse("a rigid body")),
        LagrangianSpec::Multibody(_) => return Err(refuse("a multibody system")),
    };
    let forces: Vec<&str> = (system.force.components().programs().iter())
        .map(|p| p.text())
        .collect();
    let constraints: Vec<&str> = (system.constraint.components().programs().iter())
        .map(|p| p.text())
        .collect();
    let texts = ParametricTexts {
        lagrangian: (text, coordinates),
        forces: (&forces, &system.coordinates),
        force_inputs: system.force.inputs(),
        constraints: &constraints,
        constants: &system.parameters,
    };
    let names: Vec<String> = names.iter().map(|(n, _)| n.clone()).collect();
    ExprParametric::compile(texts, &names).map_err(|e| {
        ck.error(
            Some(span.clone()),
            format!("the model could not be compiled with its parameters as inputs: {e}"),
        )
    })
}
