//! `[analysis] certify = true` on a constrained file: the symplecticity defect of the SHAKE +
//! RATTLE step on `T*N` (R17 restricted to the constraint manifold's cotangent bundle), and
//! checks that the restriction is the right one.

use marsden::holonomic::Rattle;
use marsden::sensitivity::SensitiveStep as _;
use marsden::sensitivity::cotangent::{cotangent_basis, omega, restricted_defect};
use marsden::systems::SphericalPendulum;
use marsden::{Initial, Integrator, Midpoint, NewtonOptions, Rule as _, State};

use super::{number, summary_json};

/// The spherical pendulum in Cartesian coordinates (unit mass, length and gravity), polar
/// angle 1 from the downward vertical, θ̇ = 0.3, ϕ̇ = 0.8 (`v` tangent to the sphere), with
/// `method`, certified.
fn spherical(method: &str) -> String {
    let (st, ct) = 1.0_f64.sin_cos();
    let q = [st, 0.0, -ct];
    let v = [0.3 * ct, 0.8 * st, 0.3 * st];
    format!(
        r#"
[system]
coordinates = ["x", "y", "z"]
lagrangian = "0.5*(x_dot^2 + y_dot^2 + z_dot^2) - z"
constraints = ["x^2 + y^2 + z^2 - 1"]
[initial]
q = {q:?}
v = {v:?}
[integrator]
method = "{method}"
h = 0.05
steps = 400
tolerance = 1e-14
[output]
plots = false
[analysis]
certify = true
"#
    )
}

/// R17 on `T*N`: the spherical pendulum's constrained step preserves `ω` on the tangent space
/// of `T*N`, at the start and at the end of the run, to 1e-12 relative, with the midpoint rule
/// and with Lobatto IIIA–IIIB (3 stages); the summary names the space.
#[test]
fn r17_spherical_pendulum_step_is_symplectic_on_the_cotangent_bundle() {
    for method in ["midpoint", "lobatto-3"] {
        let json = summary_json(&spherical(method));
        let s = "/certificate/symplecticity";
        for end in ["start", "end"] {
            let d = number(&json, &format!("{s}/{end}"));
            assert!(d <= 1e-12, "{method} {end}: {d:e}\n{json:#}");
        }
        assert_eq!(
            json.pointer(&format!("{s}/expected_symplectic")),
            Some(&true.into())
        );
        let on = json
            .pointer(&format!("{s}/restricted_to"))
            .and_then(|v| v.as_str());
        assert!(on.is_some_and(|o| o.starts_with("T*N")), "{json:#}");
    }
}

/// The spherical pendulum of the core (`L = ½|v|² − z`, `φ = ½(|q|² − 1)`) at θ = 1, ϕ = 0,
/// θ̇ = 0.3, ϕ̇ = 0.8, on `T*N`.
fn start() -> State {
    let s = SphericalPendulum::default();
    let (Initial::Velocity { q, v } | Initial::Momentum { q, p: v }) =
        s.initial(1.0, 0.0, 0.3, 0.8);
    State { t: 0.0, q, p: v }
}

/// One tightly converged midpoint SHAKE + RATTLE step from `x` and its Jacobian (6 × 6).
fn step_jacobian(x: &State) -> Vec<f64> {
    let p = SphericalPendulum::default();
    let tight = NewtonOptions {
        residual_tolerance: 1e-15,
        ..NewtonOptions::default()
    };
    let mut integrator = Integrator::new(Midpoint.discretize(p))
        .with_constraint(p)
        .with_projection(Rattle::new(p, p).with_options(tight))
        .with_options(tight)
        .unwrap();
    integrator.set_velocity_hint(&x.p);
    let mut jac = vec![0.0; 36];
    integrator
        .step_with_sensitivity(&mut x.clone(), 0.05, &mut jac)
        .unwrap();
    jac
}

/// The basis is the tangent space of `T*N = {|q| = 1, q·p = 0}` (unit mass: `p = v`): four
/// vectors (`2n − 2d`), each with `q·δq = 0` and `δq·p + q·δp = 0` to round-off, independent.
#[test]
fn cotangent_basis_spans_the_closed_form_tangent_space_of_the_sphere() {
    let x = start();
    let s = SphericalPendulum::default();
    let basis = cotangent_basis(&s, &s, x.t, &x.q, &x.p);
    assert_eq!(basis.len(), 4);
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(u, w)| u * w).sum::<f64>();
    for u in &basis {
        let (dq, dp) = u.split_at(3);
        assert!(dot(&x.q, dq).abs() <= 1e-15, "q·δq = {:e}", dot(&x.q, dq));
        let hidden = dot(dq, &x.p) + dot(&x.q, dp);
        assert!(hidden.abs() <= 1e-15, "δq·p + q·δp = {hidden:e}");
    }
    // ω is non-degenerate on T*N: the 4 × 4 Gram matrix of ω has a pair far from zero.
    let largest = (0..4)
        .flat_map(|i| (0..4).map(move |j| (i, j)))
        .map(|(i, j)| omega(&basis[i], &basis[j]).abs())
        .fold(0.0, f64::max);
    assert!(largest > 0.1, "{largest}");
}

/// The restriction matters: on `T*N` the step's defect is round-off, on all of `T*Q` (the
/// identity basis: the Jacobian of the map's extension off `T*N`) it is not, and a Jacobian
/// scaled by `λ = 1 + 10⁻⁶` (not symplectic) shows the defect `(λ² − 1) max |ω(u, w)|` on
/// `T*N`, to 1 %.
#[test]
fn the_defect_on_the_cotangent_bundle_catches_what_it_should() {
    let x = start();
    let s = SphericalPendulum::default();
    let jac = step_jacobian(&x);
    let basis = cotangent_basis(&s, &s, x.t, &x.q, &x.p);
    let (_, on_n) = restricted_defect(&jac, &basis);
    assert!(on_n <= 1e-13, "on T*N: {on_n:e}");
    let identity: Vec<Vec<f64>> = (0..6)
        .map(|i| (0..6).map(|j| f64::from(u8::from(i == j))).collect())
        .collect();
    let (_, on_q) = restricted_defect(&jac, &identity);
    assert!(on_q > 1e-4, "on T*Q: {on_q:e}");
    // Scaled by λ: ω(λDF u, λDF w) − ω(u, w) = (λ² − 1) ω(u, w) + round-off.
    let lambda: f64 = 1.0 + 1e-6;
    let scaled: Vec<f64> = jac.iter().map(|a| a * lambda).collect();
    let (perturbed, _) = restricted_defect(&scaled, &basis);
    let largest = (0..4)
        .flat_map(|i| (i + 1..4).map(move |j| (i, j)))
        .map(|(i, j)| omega(&basis[i], &basis[j]).abs())
        .fold(0.0, f64::max);
    let expected = (lambda * lambda - 1.0) * largest;
    assert!(
        (perturbed - expected).abs() <= 1e-2 * expected,
        "perturbed: {perturbed:e}, expected (λ² − 1) max|ω(u, w)| = {expected:e}"
    );
}
