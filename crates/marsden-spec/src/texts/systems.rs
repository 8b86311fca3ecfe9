//! The text of `marsden systems [NAME]`: the catalog with coordinates, parameters and
//! defaults, and each Lagrangian as a formula one can copy into `lagrangian = "…"`.

use std::fmt::Write as _;

use marsden_expr::closest;

use crate::catalog::{Builtin, MASSES};
use crate::error::Diagnostic;
use crate::problem::rigid_catalog::{RIGID_BUILTINS, RigidBuiltin, rigid_builtin};

/// The catalog (or the entry `name`).
///
/// # Errors
/// An unknown name, with the closest one and the list.
pub fn render(name: Option<&str>) -> Result<String, Diagnostic> {
    if let Some(entry) = name.and_then(rigid_builtin) {
        return Ok(describe_rigid(entry));
    }
    let selected: Vec<Builtin> = match name {
        None => Builtin::ALL.to_vec(),
        Some(name) => match Builtin::from_name(name) {
            Some(b) => vec![b],
            None => {
                let rigid = RIGID_BUILTINS.iter().map(|b| b.name);
                let names: Vec<&str> = Builtin::ALL
                    .map(Builtin::name)
                    .into_iter()
                    .chain(rigid)
                    .collect();
                return Err(Diagnostic::new(format!("unknown builtin `{name}`"))
                    .suggest(closest(name, names.iter().copied()))
                    .note(format!("builtins: {}", names.join(", "))));
            }
        },
    };
    let mut out = String::new();
    if name.is_none() {
        out.push_str(
            "Catalog systems: use `builtin = \"<name>\"` in [system]; `parameters` override the \
             defaults.\n",
        );
    }
    for (i, b) in selected.into_iter().enumerate() {
        if i > 0 || name.is_none() {
            out.push('\n');
        }
        out.push_str(&describe(b));
    }
    if name.is_none() {
        out.push_str(
            "\nRigid bodies (configuration R ∈ SO(3), stepped by the Lie group variational \
             integrator): `builtin = \"<name>\"` with `[initial]` `rotation_vector`/`R`/\
             `quaternion` and `Omega`/`Pi`.\n",
        );
        for entry in &RIGID_BUILTINS {
            out.push('\n');
            out.push_str(&describe_rigid(entry));
        }
    }
    Ok(out)
}

/// The catalog entry of a rigid body, as the `rigid_body` file it stands for.
pub fn describe_rigid(entry: &RigidBuiltin) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "{}  —  {}", entry.name, entry.summary);
    let params: Vec<String> = (entry.parameters.iter())
        .map(|p| format!("{} = {} ({})", p.name, p.default, p.doc))
        .collect();
    let _ = writeln!(out, "  parameters   {}", params.join(", "));
    let _ = writeln!(out, "  rigid_body   {{ inertia = [J1, J2, J3] }}");
    let _ = writeln!(
        out,
        "  potential    {}",
        entry.potential.unwrap_or("0 (free body)")
    );
    out
}

/// The catalog entry of `b`.
pub fn describe(b: Builtin) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "{}  —  {}", b.name(), b.summary());
    let coordinates = if b.needs_masses() {
        "x1 y1 z1 x2 y2 z2 … (three per body)".to_owned()
    } else {
        b.coordinates(0).join(" ")
    };
    let _ = writeln!(out, "  coordinates  {coordinates}");
    let mut params: Vec<String> = Vec::new();
    if b.needs_masses() {
        params.push(format!("{MASSES} = [..] (required: one mass per body)"));
    }
    params.extend(
        b.parameters()
            .iter()
            .map(|p| format!("{} = {} ({})", p.name, p.default, p.doc)),
    );
    let _ = writeln!(out, "  parameters   {}", params.join(", "));
    let _ = writeln!(out, "  lagrangian   {}", b.formula());
    out
}
