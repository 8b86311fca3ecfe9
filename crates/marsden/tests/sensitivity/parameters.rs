//! Parameter sensitivities (parameters as frozen coordinates) against central differences of
//! whole runs at shifted parameter values: Kepler's `mu` (gauss-3), and a damped pendulum's
//! length and damping coefficient (midpoint, forced); the adjoint's parameter gradient against
//! the tangent's.

use super::common::{relative_distance, run_to_end, state};
use crate::common::tight;
use marsden::discrete::rules::Galerkin;
use marsden::sensitivity::{
    AdjointOptions, ParametricIntegrator, ParametricModel, TangentOptions, adjoint, tangent,
};
use marsden::systems::Kepler;
use marsden::{Midpoint, Rule, Scalar, State, TimeGrid};

/// Kepler with the gravitational parameter `mu` as a parameter: `L = ½|v|² + mu/|q|`.
#[derive(Debug, Clone, Copy)]
struct KeplerMu;

impl ParametricModel for KeplerMu {
    fn dof(&self) -> usize {
        2
    }
    fn parameter_names(&self) -> Vec<String> {
        vec!["mu".into()]
    }
    fn lagrangian_with<S: Scalar>(&self, theta: &[S], _t: S, q: &[S], v: &[S]) -> S {
        let r = (q[0] * q[0] + q[1] * q[1]).sqrt();
        (v[0] * v[0] + v[1] * v[1]) * 0.5 + theta[0] / r
    }
}

/// A damped pendulum of unit mass with length `l` and damping `c` as parameters:
/// `L = ½ l² v² + g l cos q`, `f = −c v` (g = 9.81).
#[derive(Debug, Clone, Copy)]
pub struct DampedPendulumLc;

impl ParametricModel for DampedPendulumLc {
    fn dof(&self) -> usize {
        1
    }
    fn parameter_names(&self) -> Vec<String> {
        vec!["l".into(), "c".into()]
    }
    fn lagrangian_with<S: Scalar>(&self, theta: &[S], _t: S, q: &[S], v: &[S]) -> S {
        let l = theta[0];
        l * l * v[0] * v[0] * 0.5 + l * q[0].cos() * 9.81
    }
    fn force_with<S: Scalar>(&self, theta: &[S], _t: S, _q: &[S], v: &[S], out: &mut [S]) {
        out[0] = -(theta[1] * v[0]);
    }
    fn is_forced(&self) -> bool {
        true
    }
}

/// The parameter columns of the final Jacobian against central differences in `θ`.
fn check_parameters<R: Rule, M: ParametricModel + Clone>(
    name: &str,
    rule: &R,
    model: M,
    theta: &[f64],
    start: &State,
    grid: &TimeGrid,
    eps: f64,
) {
    let make =
        |theta: &[f64]| ParametricIntegrator::new(rule, model.clone(), theta, tight()).unwrap();
    let t = tangent(
        &mut make(theta),
        start.clone(),
        grid,
        &TangentOptions::default(),
    )
    .unwrap();
    let m = 2 * t.n;
    for p in 0..theta.len() {
        let shifted = |sign: f64| {
            let mut th = theta.to_vec();
            th[p] += sign * eps * theta[p].abs().max(1.0);
            run_to_end(make(&th), start, grid)
        };
        let (plus, minus) = (shifted(1.0), shifted(-1.0));
        let step = 2.0 * eps * theta[p].abs().max(1.0);
        let fd: Vec<f64> = (0..m).map(|r| (plus[r] - minus[r]) / step).collect();
        let ad: Vec<f64> = (0..m).map(|r| t.get(r, m + p)).collect();
        let d = relative_distance(&ad, &fd);
        println!("{name} / ∂x_K/∂θ_{p}: relative distance to central differences {d:.2e}");
        assert!(d <= 1e-6, "{name}, parameter {p}: relative distance {d:e}");
    }
}

/// Kepler e = 0.6, gauss-3, h = 0.01, 1000 steps: ∂(q, p)/∂mu to 1e-6 of central differences;
/// at `mu = 1` the run is the catalog Kepler's.
#[test]
fn kepler_mu_sensitivity_matches_central_differences() {
    let (q, p) = Kepler::pericentre(0.6);
    let start = state(&q, &p);
    let grid = TimeGrid::new(0.0, 0.01, 1000).unwrap();
    let gauss = Galerkin::gauss(3).unwrap();
    check_parameters(
        "kepler gauss-3",
        &gauss,
        KeplerMu,
        &[1.0],
        &start,
        &grid,
        1e-5,
    );
}

/// A forced model: the damped pendulum's `l` and `c` over 400 midpoint steps of 0.02.
#[test]
fn damped_pendulum_length_and_damping_match_central_differences() {
    let start = state(&[0.8], &[0.0]);
    let grid = TimeGrid::new(0.0, 0.02, 400).unwrap();
    check_parameters(
        "damped pendulum midpoint",
        &Midpoint,
        DampedPendulumLc,
        &[1.3, 0.2],
        &start,
        &grid,
        1e-5,
    );
}

/// The adjoint gradient of `Σ_k q_k²/2` over every 10th sample with respect to `(q₀, p₀, l, c)`
/// equals the tangent run's to 1e-10.
#[test]
fn adjoint_parameter_gradient_equals_forward() {
    let start = state(&[0.8], &[0.0]);
    let grid = TimeGrid::new(0.0, 0.02, 400).unwrap();
    let make =
        || ParametricIntegrator::new(&Midpoint, DampedPendulumLc, &[1.3, 0.2], tight()).unwrap();
    let loss = |k: usize, x: &State, out: &mut [f64]| {
        if k.is_multiple_of(10) {
            out[0] += x.q[0];
        }
    };
    let run = tangent(
        &mut make(),
        start.clone(),
        &grid,
        &TangentOptions { every: 10 },
    )
    .unwrap();
    let mut forward = vec![0.0; run.columns];
    for s in &run.samples {
        forward
            .iter_mut()
            .enumerate()
            .for_each(|(c, g)| *g += s.state.q[0] * s.jacobian[c]);
    }
    let reverse = adjoint(&mut make(), start, &grid, loss, &AdjointOptions::default()).unwrap();
    let d = relative_distance(&reverse.gradient, &forward);
    println!(
        "adjoint vs forward (q₀, p₀, l, c): {:?} vs {forward:?}, {d:.2e}",
        reverse.gradient
    );
    assert_eq!(reverse.gradient.len(), 4);
    assert!(d <= 1e-10, "relative distance {d:e}");
}
