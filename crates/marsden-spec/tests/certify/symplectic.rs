//! `[analysis] certify = true`: the symplecticity defect of the step map and the equivariance
//! defect of `L_d`, in `summary.json`.

use super::{number, summary_json};

/// An unforced problem with `system` lines, `initial` lines and `method`, certified.
fn certified(system: &str, initial: &str, method: &str) -> String {
    format!(
        "[system]\n{system}\n[initial]\n{initial}\n[integrator]\nmethod = \"{method}\"\nh = 0.1\n\
         steps = 200\ntolerance = 1e-14\n[output]\nplots = false\n[analysis]\ncertify = true\n"
    )
}

/// Midpoint on the harmonic oscillator (R1): the step map is symplectic to round-off.
#[test]
fn r1_midpoint_oscillator_step_map_is_symplectic() {
    let text = certified(
        "builtin = \"harmonic_oscillator\"",
        "q = [1.0]\np = [0.0]",
        "midpoint",
    );
    let json = summary_json(&text);
    let s = "/certificate/symplecticity";
    assert!(number(&json, &format!("{s}/start")) <= 1e-14, "{json:#}");
    assert!(number(&json, &format!("{s}/end")) <= 1e-14, "{json:#}");
    assert_eq!(
        json.pointer(&format!("{s}/expected_symplectic")),
        Some(&true.into())
    );
    assert_eq!(
        json.pointer(&format!("{s}/note")),
        Some(&serde_json::Value::Null)
    );
}

/// Without `certify` the summary has no certificate (nothing is computed).
#[test]
fn no_certificate_unless_asked_for() {
    let text = certified(
        "builtin = \"harmonic_oscillator\"",
        "q = [1.0]\np = [0.0]",
        "midpoint",
    )
    .replace("certify = true", "certify = false");
    assert!(summary_json(&text).get("certificate").is_none());
}

/// Kepler (the `marsden` crate documentation, Conventions: rotations are a symmetry of the midpoint
/// and Gauss `L_d`): the equivariance defect is at round-off, and the multi-stage map is symplectic
/// too.
#[test]
fn kepler_rotation_equivariance_defect_is_round_off() {
    for method in ["midpoint", "gauss-2"] {
        let text = certified(
            "builtin = \"kepler\"\n[[system.symmetry]]\nrotation = \"z\"",
            "q = [0.4, 0.0]\np = [0.0, 2.0]",
            method,
        )
        .replace("h = 0.1", "h = 0.01");
        let json = summary_json(&text);
        let e = "/certificate/equivariance/Lz";
        assert!(
            number(&json, &format!("{e}/max_rel_defect")) <= 1e-14,
            "{method}: {json:#}"
        );
        assert_eq!(number(&json, &format!("{e}/samples")), 2.0);
        let s = "/certificate/symplecticity";
        assert!(
            number(&json, &format!("{s}/start")) <= 1e-13,
            "{method}: {json:#}"
        );
        assert!(
            number(&json, &format!("{s}/end")) <= 1e-13,
            "{method}: {json:#}"
        );
    }
}

/// A rotation of the pendulum under gravity is no symmetry: a defect of order one. The run is
/// constrained, so the symplecticity defect is measured on `T*N` (and says so), where the
/// SHAKE + RATTLE step is symplectic: round-off.
#[test]
fn pendulum_under_gravity_rotation_shows_a_large_defect() {
    let text = certified(
        "coordinates = [\"x\", \"y\"]\nlagrangian = \"0.5*(x_dot^2 + y_dot^2) - y\"\n\
         constraints = [\"x^2 + y^2 - 1\"]\n[[system.symmetry]]\nrotation = \"z\"",
        "q = [0.6, -0.8]\nv = [0.0, 0.0]",
        "midpoint",
    );
    let json = summary_json(&text);
    assert!(
        number(&json, "/certificate/equivariance/Lz/max_rel_defect") > 1e-2,
        "{json:#}"
    );
    let s = "/certificate/symplecticity";
    assert!(number(&json, &format!("{s}/start")) <= 1e-12, "{json:#}");
    let on = json
        .pointer(&format!("{s}/restricted_to"))
        .and_then(|v| v.as_str());
    assert!(on.is_some_and(|o| o.starts_with("T*N")), "{json:#}");
}

/// A damped oscillator's map contracts phase-space area: its defect is reported, not hidden,
/// and marked as not expected to be symplectic.
#[test]
fn forced_map_reports_its_defect_as_not_expected_symplectic() {
    let text = certified(
        "coordinates = [\"x\"]\nlagrangian = \"0.5*x_dot^2 - 0.5*x^2\"\nforces = [\"-0.5*x_dot\"]",
        "q = [1.0]\nv = [0.0]",
        "midpoint",
    );
    let json = summary_json(&text);
    let s = "/certificate/symplecticity";
    // det DF = (1 − ch/2)/(1 + ch/2) per step in one dimension: a defect of order c·h.
    assert!(number(&json, &format!("{s}/start")) > 1e-3, "{json:#}");
    assert_eq!(
        json.pointer(&format!("{s}/expected_symplectic")),
        Some(&false.into())
    );
    let note = json.pointer(&format!("{s}/note")).and_then(|v| v.as_str());
    assert_eq!(note, Some("not expected symplectic (forced)"));
}
