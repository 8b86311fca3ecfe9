//! `[sensitivity] parameters` of a constrained system: the spherical pendulum in Cartesian
//! coordinates with gravity `g` in the Lagrangian and the rod length `l` in the constraint
//! `x² + y² + z² − l² = 0` (SHAKE + RATTLE, midpoint). The parameter columns of `summary.json`
//! against central differences of whole runs, and their tangency to `T*N(θ)`.

use marsden::analysis::certificate::DifferentiableStep as _;
use marsden::sensitivity::ConstrainedParametricIntegrator;
use marsden::{Midpoint, State};
use marsden_spec::RunSpec;

use super::run;

const G: f64 = 1.3;

/// The file at gravity `g`: unit length, polar angle 1 from the downward vertical, rates
/// θ̇ = 0.3, ϕ̇ = 0.8 (`v` tangent to the sphere), 500 steps of 0.01.
fn pendulum(g: f64) -> String {
    let (st, ct) = 1.0_f64.sin_cos();
    let q = [st, 0.0, -ct];
    let v = [0.3 * ct, 0.8 * st, 0.3 * st];
    format!(
        r#"
[system]
coordinates = ["x", "y", "z"]
parameters = {{ g = {g:?}, l = 1.0 }}
lagrangian = "0.5*(x_dot^2 + y_dot^2 + z_dot^2) - g*z"
constraints = ["x^2 + y^2 + z^2 - l^2"]
[initial]
q = {q:?}
v = {v:?}
[integrator]
method = "midpoint"
h = 0.01
steps = 500
[sensitivity]
initial = true
parameters = ["g", "l"]
"#
    )
}

/// Column `c` of the summary's final Jacobian.
fn column(jacobian: &[Vec<f64>], c: usize) -> Vec<f64> {
    jacobian.iter().map(|row| row[c]).collect()
}

/// `max |a − b| / max |b|`.
fn relative_distance(a: &[f64], b: &[f64]) -> f64 {
    let diff = (a.iter().zip(b)).fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()));
    diff / b.iter().fold(0.0_f64, |m, y| m.max(y.abs()))
}

/// The sensitivity check for a constrained system: `∂(q, p)_final/∂g` equals the central difference
/// of two runs of the file at `g ± δ`, and `∂(q, p)_final/∂l` that of two runs of the file's
/// model (compiled with `g, l` as inputs) at `l ± δ` from the same `(q₀, p₀)` — a file with
/// another `l` would start off its sphere and be refused — each to 1e-6 relative.
#[test]
fn spherical_pendulum_d_final_d_g_and_l_match_central_differences() {
    let dir = tempfile::tempdir().unwrap();
    let outcome = run(&pendulum(G), &dir.path().join("base"));
    let block = outcome.summary.sensitivity.as_ref().unwrap();
    assert_eq!(block.error, None);
    assert_eq!(
        block.columns,
        ["q0_x", "q0_y", "q0_z", "p0_x", "p0_y", "p0_z", "g", "l"]
    );
    let delta = 1e-5;
    let end = |g: f64, name: &str| {
        let s = run(&pendulum(g), &dir.path().join(name))
            .summary
            .final_state;
        [s.q, s.p].concat()
    };
    let (plus, minus) = (end(G + delta, "plus"), end(G - delta, "minus"));
    let fd: Vec<f64> = (plus.iter().zip(&minus))
        .map(|(a, b)| (a - b) / (2.0 * delta))
        .collect();
    let d = relative_distance(&column(&block.final_jacobian, 6), &fd);
    assert!(d <= 1e-6, "∂/∂g: relative distance {d:e}");

    let spec = RunSpec::from_toml_str(&pendulum(G), "pendulum.toml").unwrap();
    let model = (spec.sensitivity.as_ref().and_then(|s| s.model.clone())).unwrap();
    let (q0, v0): (Vec<f64>, Vec<f64>) = {
        let (st, ct) = 1.0_f64.sin_cos();
        (vec![st, 0.0, -ct], vec![0.3 * ct, 0.8 * st, 0.3 * st])
    };
    let grid = spec.integrator.grid;
    let end = |l: f64| {
        let theta = [G, l];
        let newton = spec.integrator.newton;
        let mut vi = ConstrainedParametricIntegrator::new(&Midpoint, model.clone(), &theta, newton)
            .unwrap()
            .with_velocity_hint(&v0);
        // L = ½|v|² − g z: p = v.
        let mut s = State {
            t: 0.0,
            q: q0.clone(),
            p: v0.clone(),
        };
        for k in 0..grid.steps {
            vi.step(&mut s, grid.h).unwrap();
            s.t = grid.time(k + 1);
        }
        [s.q, s.p].concat()
    };
    let (plus, minus) = (end(1.0 + delta), end(1.0 - delta));
    let fd: Vec<f64> = (plus.iter().zip(&minus))
        .map(|(a, b)| (a - b) / (2.0 * delta))
        .collect();
    let d = relative_distance(&column(&block.final_jacobian, 7), &fd);
    assert!(d <= 1e-6, "∂/∂l: relative distance {d:e}");
}

/// The parameter columns are tangent to `T*N(θ)` at the final state: with `φ = |q|² − l²` and
/// the hidden constraint `q·p = 0`, `2 q·δq − 2l ∂l/∂θ = 0` and `δq·p + q·δp = 0`, each
/// relative to its terms' sizes to 1e-10.
#[test]
fn spherical_pendulum_parameter_columns_are_tangent_to_the_cotangent_bundle() {
    let dir = tempfile::tempdir().unwrap();
    let outcome = run(&pendulum(G), dir.path());
    let block = outcome.summary.sensitivity.as_ref().unwrap();
    let f = &outcome.summary.final_state;
    let (q, p) = (&f.q, &f.p);
    let dot = |a: &[f64], b: &[f64]| -> f64 { a.iter().zip(b).map(|(x, y)| x * y).sum() };
    let norm = |a: &[f64]| dot(a, a).sqrt();
    for (c, explicit) in [(6, 0.0), (7, 2.0)] {
        let image = column(&block.final_jacobian, c);
        let (dq, dp) = image.split_at(3);
        let position = 2.0 * dot(q, dq) - explicit;
        let position_scale = 2.0 * norm(q) * norm(dq) + explicit;
        let hidden = dot(dq, p) + dot(q, dp);
        let hidden_scale = norm(dq) * norm(p) + norm(q) * norm(dp);
        assert!(position_scale > 1e-3 && hidden_scale > 1e-3, "{image:?}");
        assert!(
            position.abs() <= 1e-10 * position_scale,
            "column {c}: δφ = {position:e} (scale {position_scale:e})"
        );
        assert!(
            hidden.abs() <= 1e-10 * hidden_scale,
            "column {c}: δ(q·p) = {hidden:e} (scale {hidden_scale:e})"
        );
    }
}
