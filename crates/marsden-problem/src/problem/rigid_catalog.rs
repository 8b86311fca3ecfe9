//! The catalog's rigid bodies: `builtin = "heavy_top"` or `"free_rigid_body"` in `[system]`
//! stands for a `rigid_body` with its inertia and potential written out, its parameters
//! overridable in `parameters` like a catalog system's.

use marsden::lie::body::{Inertia, Moments};
use toml::Spanned;

use super::check::Checker;
use super::parameters::Parameters;
use super::raw::RawSystem;
use super::resolved::Resolved;
use super::rigid::{Parts, Potential, assemble, refuse_coordinate_keys};
use crate::catalog::Parameter;
use crate::error::Diagnostic;

/// A rigid body of the catalog.
#[derive(Debug, Clone, Copy)]
pub struct RigidBuiltin {
    /// Its `builtin` name.
    pub name: &'static str,
    /// One line on what it is.
    pub summary: &'static str,
    /// Its parameters: the principal moments `J1`, `J2`, `J3` first, then the potential's.
    pub parameters: &'static [Parameter],
    /// `U` in `R11 … R33` and the parameters (`None`: a free body).
    pub potential: Option<&'static str>,
}

/// The catalog's rigid bodies.
pub const RIGID_BUILTINS: [RigidBuiltin; 2] = [
    RigidBuiltin {
        name: "free_rigid_body",
        summary: "free rigid body, Euler's equations (exact solution known: Jacobi elliptic \
                  functions); defaults: the test body of Hairer, Lubich & Wanner",
        parameters: &[
            Parameter {
                name: "J1",
                default: 2.0,
                doc: "principal moment about e1",
            },
            Parameter {
                name: "J2",
                default: 1.0,
                doc: "principal moment about e2",
            },
            Parameter {
                name: "J3",
                default: 2.0 / 3.0,
                doc: "principal moment about e3",
            },
        ],
        potential: None,
    },
    RigidBuiltin {
        name: "heavy_top",
        summary: "heavy top about a fixed point, centre of mass on the body axis e3 \
                  (defaults: the symmetric top of Simo & Wong)",
        parameters: &[
            Parameter {
                name: "J1",
                default: 5.0,
                doc: "principal moment about e1",
            },
            Parameter {
                name: "J2",
                default: 5.0,
                doc: "principal moment about e2",
            },
            Parameter {
                name: "J3",
                default: 1.0,
                doc: "principal moment about e3",
            },
            Parameter {
                name: "mgl",
                default: 20.0,
                doc: "mass × gravity × distance of the centre of mass",
            },
        ],
        potential: Some("mgl*R33"),
    },
];

/// The catalog's rigid body called `name`.
pub fn rigid_builtin(name: &str) -> Option<&'static RigidBuiltin> {
    RIGID_BUILTINS.iter().find(|b| b.name == name)
}

/// The `[system]` of `builtin = "<rigid body>"`: its parameters (defaults overridden by the
/// file's), its inertia and potential, and the file's torques and symmetries.
///
/// # Errors
/// A parameter the entry does not have, moments that are not an inertia, a `rigid_body` or
/// `potential` written beside the builtin, a key a rigid body does not take.
pub(super) fn system(
    ck: &Checker<'_>,
    system: &RawSystem,
    name: &Spanned<String>,
    entry: &RigidBuiltin,
    params: &Parameters,
) -> Result<Resolved, Diagnostic> {
    refuse_coordinate_keys(ck, system, false)?;
    params.numbers_only(ck, "a rigid body")?;
    let written = [
        ("rigid_body", system.rigid_body.as_ref().map(Spanned::span)),
        ("potential", system.potential.as_ref().map(Spanned::span)),
    ];
    if let Some((key, span)) = written.into_iter().find_map(|(k, s)| s.map(|s| (k, s))) {
        return Err(ck
            .error(
                Some(span),
                format!("`{key}` is given by `builtin = \"{}\"`", entry.name),
            )
            .help("change its parameters in `parameters`, or write the body without `builtin`"));
    }
    let known: Vec<&str> = entry.parameters.iter().map(|p| p.name).collect();
    let mut constants: Vec<(String, f64)> = (entry.parameters.iter())
        .map(|p| (p.name.to_owned(), p.default))
        .collect();
    for w in &params.numbers {
        match constants.iter_mut().find(|(n, _)| *n == w.name) {
            Some(slot) => slot.1 = w.value,
            None => constants.push((w.name.clone(), w.value)),
        }
    }
    let moment = |i: usize| constants[i].1;
    let rows = [
        moment(0),
        0.0,
        0.0,
        0.0,
        moment(1),
        0.0,
        0.0,
        0.0,
        moment(2),
    ];
    let inertia = Inertia::validated(0, &rows, Moments::Any).map_err(|e| {
        let span = (params.numbers.iter())
            .find(|w| known[..3].contains(&w.name.as_str()))
            .map_or(name.span(), |w| w.span.clone());
        ck.error(Some(span), format!("invalid inertia: {e}"))
    })?;
    let parts = Parts {
        inertia,
        mass: None,
        potential: entry.potential.map(Potential::Catalog),
        constants,
    };
    assemble(ck, system, parts, params)
}
