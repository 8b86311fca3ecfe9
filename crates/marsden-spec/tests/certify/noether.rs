//! The forced Noether balance (MW01 §3.2, Noether's theorem with forces): the change of the
//! discrete momentum map equals the discrete impulse of the forces along the generator.

use super::{number, summary_json};

/// A planar particle in the rotation-invariant well `V = ½|q|²` with friction `−c v`, the
/// symmetry `rotation = "z"`, and `method`.
fn damped_planar(method: &str) -> String {
    format!(
        "[system]\ncoordinates = [\"x\", \"y\"]\nparameters = {{ c = 0.3 }}\n\
         lagrangian = \"0.5*(x_dot^2 + y_dot^2) - 0.5*(x^2 + y^2)\"\n\
         forces = [\"-c*x_dot\", \"-c*y_dot\"]\n[[system.symmetry]]\nrotation = \"z\"\n\
         [initial]\nq = [1.0, 0.0]\nv = [0.0, 0.8]\n[integrator]\nmethod = \"{method}\"\n\
         h = 0.05\nsteps = 400\ntolerance = 1e-14\n[output]\nplots = false\nevery = 50\n"
    )
}

/// Damped planar particle: `J_N − J_0 − Σ I_k` at round-off (≤ 1e-13 relative), while the
/// angular momentum itself decays by a large fraction.
#[test]
fn damped_planar_particle_angular_momentum_change_equals_impulse() {
    for method in ["midpoint", "trapezoid"] {
        let json = summary_json(&damped_planar(method));
        let b = "/noether_balance/Lz";
        let change = number(&json, &format!("{b}/momentum_change"));
        let impulse = number(&json, &format!("{b}/total_impulse"));
        let j0 = number(&json, "/momenta/Lz/initial");
        assert!((j0 - 0.8).abs() < 1e-15, "{json:#}");
        // e^{−c t} over t = 20: almost all of it is lost to friction.
        assert!(change < -0.9 * j0, "{method}: {json:#}");
        let scale = j0.abs().max(change.abs());
        let total_defect = number(&json, &format!("{b}/total_defect"));
        assert!(total_defect.abs() <= 1e-13 * scale, "{method}: {json:#}");
        assert!(
            (change - impulse - total_defect).abs() <= 1e-15,
            "{method}: {json:#}"
        );
        assert!(
            number(&json, &format!("{b}/max_rel_defect")) <= 1e-13,
            "{method}: {json:#}"
        );
        assert_eq!(number(&json, &format!("{b}/steps")), 400.0);
    }
}

/// Without forces there is no Noether balance in the summary (the momentum map is conserved
/// and reported under `momenta`).
#[test]
fn no_noether_balance_without_forces() {
    let text = damped_planar("midpoint").replace("c = 0.3", "c = 0.0");
    let json = summary_json(&text.replace("forces = [\"-c*x_dot\", \"-c*y_dot\"]\n", ""));
    assert!(json.get("noether_balance").is_none(), "{json:#}");
}
