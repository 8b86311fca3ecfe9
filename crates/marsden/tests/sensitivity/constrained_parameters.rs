//! Parameter sensitivities of a constrained run: the spherical pendulum as a Cartesian particle
//! with gravity `g` in the Lagrangian and the rod length `l` in the constraint,
//!
//! ```text
//!     L = ½|v|² − g z,      φ(q; l) = x² + y² + z² − l² = 0      (SHAKE + RATTLE),
//! ```
//!
//! with the midpoint rule and constrained Lobatto IIIA–IIIB (`lobatto-3`). The parameter
//! columns of the tangent run are checked against central differences of whole runs at
//! `θ ± ε` from the same `(q₀, p₀)`, for tangency to `T*N(θ)` (the derivatives of both
//! constraints, explicit `θ`-dependence included), and the adjoint's parameter gradient
//! against the tangent's.

use super::common::{relative_distance, run_to_end};
use crate::common::tight;
use marsden::discrete::rules::Galerkin;
use marsden::sensitivity::{
    AdjointOptions, ConstrainedParametricIntegrator, ParametricModel, TangentOptions, adjoint,
    tangent,
};
use marsden::{Midpoint, Rule, Scalar, State, TimeGrid};

/// The spherical pendulum with `θ = (g, l)`.
#[derive(Debug, Clone, Copy)]
struct PendulumGl;

impl ParametricModel for PendulumGl {
    fn dof(&self) -> usize {
        3
    }
    fn parameter_names(&self) -> Vec<String> {
        vec!["g".into(), "l".into()]
    }
    fn lagrangian_with<S: Scalar>(&self, theta: &[S], _t: S, q: &[S], v: &[S]) -> S {
        (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) * 0.5 - theta[0] * q[2]
    }
    fn constraints(&self) -> usize {
        1
    }
    fn constraint_with<S: Scalar>(&self, theta: &[S], q: &[S], out: &mut [S]) {
        out[0] = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] - theta[1] * theta[1];
    }
}

const THETA: [f64; 2] = [1.3, 1.2];

/// Polar angle 1 from the downward vertical, azimuth 0, rates θ̇ = 0.3, ϕ̇ = 0.8, on the sphere
/// of radius `l = THETA[1]` (`p = v`, tangent up to rounding).
fn start() -> State {
    let l = THETA[1];
    let (st, ct) = 1.0_f64.sin_cos();
    State {
        t: 0.0,
        q: vec![l * st, 0.0, -l * ct],
        p: vec![l * 0.3 * ct, l * 0.8 * st, l * 0.3 * st],
    }
}

fn integrator<R: Rule>(rule: &R, theta: &[f64]) -> ConstrainedParametricIntegrator<R, PendulumGl> {
    ConstrainedParametricIntegrator::new(rule, PendulumGl, theta, tight()).unwrap()
}

fn check_parameter_columns<R: Rule>(name: &str, rule: &R) {
    let grid = TimeGrid::new(0.0, 0.01, 1000).unwrap();
    let run = tangent(
        &mut integrator(rule, &THETA),
        start(),
        &grid,
        &TangentOptions::default(),
    )
    .unwrap();
    assert_eq!(run.columns, 8);
    for (j, parameter) in ["g", "l"].into_iter().enumerate() {
        let eps = 1e-5 * THETA[j];
        let shifted = |sign: f64| {
            let mut theta = THETA;
            theta[j] += sign * eps;
            run_to_end(integrator(rule, &theta), &start(), &grid)
        };
        let (plus, minus) = (shifted(1.0), shifted(-1.0));
        let fd: Vec<f64> = (plus.iter().zip(&minus))
            .map(|(a, b)| (a - b) / (2.0 * eps))
            .collect();
        let exact: Vec<f64> = (0..6).map(|r| run.get(r, 6 + j)).collect();
        let d = relative_distance(&exact, &fd);
        println!("{name}: ∂x_1000/∂{parameter} vs central differences: {d:.2e}");
        assert!(d <= 1e-6, "{name}, {parameter}: relative distance {d:e}");
    }
}

#[test]
fn spherical_pendulum_midpoint_d_final_d_g_and_l_match_central_differences() {
    check_parameter_columns("midpoint", &Midpoint);
}

#[test]
fn spherical_pendulum_lobatto3_d_final_d_g_and_l_match_central_differences() {
    check_parameter_columns("lobatto-3", &Galerkin::lobatto(3).unwrap());
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// After every step `x_k(θ)` lies on `T*N(θ)`, so its parameter derivative satisfies the
/// derivatives of `φ = |q|² − l²` and of the hidden constraint `Dφ·v = 2 q·p`:
/// `2 q·δq − 2l ∂l/∂θ_j = 0` and `δq·p + q·δp = 0`, each relative to its terms' sizes.
fn check_tangency<R: Rule>(name: &str, rule: &R) {
    let grid = TimeGrid::new(0.0, 0.01, 1000).unwrap();
    let options = TangentOptions { every: 1 };
    let run = tangent(&mut integrator(rule, &THETA), start(), &grid, &options).unwrap();
    let norm = |a: &[f64]| dot(a, a).sqrt();
    let (mut position, mut hidden) = (0.0_f64, 0.0_f64);
    for sample in run.samples.iter().filter(|s| s.step > 0) {
        let (q, p) = (&sample.state.q, &sample.state.p);
        for j in 0..2 {
            let column: Vec<f64> = (0..6).map(|r| sample.jacobian[r * 8 + 6 + j]).collect();
            let (dq, dp) = column.split_at(3);
            let explicit = if j == 1 { 2.0 * THETA[1] } else { 0.0 };
            let scale = 2.0 * norm(q) * norm(dq) + explicit;
            if scale > 0.0 {
                position = position.max((2.0 * dot(q, dq) - explicit).abs() / scale);
            }
            let scale = norm(dq) * norm(p) + norm(q) * norm(dp);
            if scale > 0.0 {
                hidden = hidden.max((dot(dq, p) + dot(q, dp)).abs() / scale);
            }
        }
    }
    println!("{name}: parameter columns, max relative δφ = {position:.2e}, δ(q·p) = {hidden:.2e}");
    assert!(position <= 1e-10, "{name}: δφ = {position:e}");
    assert!(hidden <= 1e-10, "{name}: δ(q·p) = {hidden:e}");
}

#[test]
fn spherical_pendulum_parameter_columns_are_tangent_to_the_cotangent_bundle() {
    check_tangency("midpoint", &Midpoint);
    check_tangency("lobatto-3", &Galerkin::lobatto(3).unwrap());
}

/// ℓ_k = Σ_i w_i x_i²/2 on every 5th step.
fn cotangent(k: usize, x: &State, out: &mut [f64]) {
    if k.is_multiple_of(5) {
        for (i, o) in out.iter_mut().enumerate() {
            let xi = if i < 3 { x.q[i] } else { x.p[i - 3] };
            *o += (1.0 + 0.1 * i as f64) * xi;
        }
    }
}

#[test]
fn spherical_pendulum_adjoint_parameter_gradient_matches_forward_to_1e10() {
    let grid = TimeGrid::new(0.0, 0.01, 1000).unwrap();
    let run = tangent(
        &mut integrator(&Midpoint, &THETA),
        start(),
        &grid,
        &TangentOptions { every: 1 },
    )
    .unwrap();
    let mut forward = [0.0; 8];
    let mut cot = [0.0; 6];
    for sample in &run.samples {
        cot.fill(0.0);
        cotangent(sample.step, &sample.state, &mut cot);
        for (c, g) in forward.iter_mut().enumerate() {
            *g += (0..6)
                .map(|r| cot[r] * sample.jacobian[r * 8 + c])
                .sum::<f64>();
        }
    }
    let mut stepper = integrator(&Midpoint, &THETA);
    let options = AdjointOptions::default();
    let reverse = adjoint(&mut stepper, start(), &grid, cotangent, &options).unwrap();
    let d = relative_distance(&reverse.gradient, &forward);
    println!("midpoint: forward vs adjoint gradient (state and g, l): {d:.2e}");
    assert!(d <= 1e-10, "{d:e}");
}
