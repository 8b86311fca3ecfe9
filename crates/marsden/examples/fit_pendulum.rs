//! Recovering a pendulum's length and damping coefficient from noisy samples of its angle, by
//! Gauss–Newton on the sensitivities of the simulation ([`marsden::sensitivity`]).
//!
//! The model: a unit-mass pendulum, `L = ½ l² θ̇² + g l cos θ` (g = 9.81), with viscous damping
//! `f = −c θ̇`, midpoint rule with midpoint forces, h = 0.01, released at rest from θ = 0.8.
//! The data: θ every 10 steps over 10 s from `l = 1.3`, `c = 0.25`, plus Gaussian noise of
//! σ = 0.01 (a fixed-seed generator, so the output is reproducible). The fit: minimise
//! `½ Σ_i (θ(t_i; l, c) − y_i)²` by Gauss–Newton, the residual Jacobian `∂θ(t_i)/∂(l, c)` read
//! from one tangent run per iteration (parameter columns of
//! [`marsden::sensitivity::Tangent`]), halving the step while the cost does not decrease. The
//! gradient `Jᵀr` is checked against the adjoint gradient at the first iterate.
//!
//! `cargo run -p marsden --example fit_pendulum`

use marsden::numerics::dense::solve_in_place;
use marsden::sensitivity::{
    AdjointOptions, ParametricIntegrator, ParametricModel, TangentOptions, adjoint, tangent,
};
use marsden::{Midpoint, NewtonOptions, Scalar, State, TimeGrid};

const G: f64 = 9.81;
const EVERY: usize = 10;
const SIGMA: f64 = 0.01;

/// The damped pendulum with `θ = (l, c)`.
#[derive(Debug, Clone, Copy)]
struct DampedPendulum;

impl ParametricModel for DampedPendulum {
    fn dof(&self) -> usize {
        1
    }
    fn parameter_names(&self) -> Vec<String> {
        vec!["l".into(), "c".into()]
    }
    fn lagrangian_with<S: Scalar>(&self, theta: &[S], _t: S, q: &[S], v: &[S]) -> S {
        let l = theta[0];
        l * l * v[0] * v[0] * 0.5 + l * q[0].cos() * G
    }
    fn force_with<S: Scalar>(&self, theta: &[S], _t: S, _q: &[S], v: &[S], out: &mut [S]) {
        out[0] = -(theta[1] * v[0]);
    }
    fn is_forced(&self) -> bool {
        true
    }
}

fn start() -> State {
    State {
        t: 0.0,
        q: vec![0.8],
        p: vec![0.0],
    }
}

/// Standard normal deviates from a fixed-seed xorshift generator (Box–Muller).
fn noise(count: usize) -> Vec<f64> {
    let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut uniform = || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        ((x >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    };
    (0..count)
        .map(|_| {
            let (u, v) = (uniform(), uniform());
            (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
        })
        .collect()
}

/// θ at the samples and `∂θ/∂(l, c)` there, from one tangent run.
fn simulate(theta: [f64; 2], grid: &TimeGrid) -> Result<(Vec<f64>, Vec<[f64; 2]>), marsden::Error> {
    let mut vi =
        ParametricIntegrator::new(&Midpoint, DampedPendulum, &theta, NewtonOptions::default())?;
    let run = tangent(&mut vi, start(), grid, &TangentOptions { every: EVERY })?;
    // Row 0 of each 2 × 4 Jacobian is θ's: columns (θ₀, p₀, l, c).
    Ok(run
        .samples
        .iter()
        .skip(1)
        .map(|s| (s.state.q[0], [s.jacobian[2], s.jacobian[3]]))
        .unzip())
}

fn cost(model: &[f64], data: &[f64]) -> f64 {
    0.5 * model
        .iter()
        .zip(data)
        .map(|(m, y)| (m - y).powi(2))
        .sum::<f64>()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let grid = TimeGrid::new(0.0, 0.01, 1000)?;
    let truth = [1.3, 0.25];
    let (clean, _) = simulate(truth, &grid)?;
    let data: Vec<f64> = clean
        .iter()
        .zip(noise(clean.len()))
        .map(|(q, e)| q + SIGMA * e)
        .collect();
    println!(
        "data: {} samples of θ (every {EVERY} steps, h = {}), σ = {SIGMA}; truth l = {}, c = {}",
        data.len(),
        grid.h,
        truth[0],
        truth[1]
    );

    let mut theta = [1.0, 0.05];
    println!("iter        l            c          cost        |grad|     step");
    for iter in 0..30 {
        let (model, jac) = simulate(theta, &grid)?;
        let r: Vec<f64> = model.iter().zip(&data).map(|(m, y)| m - y).collect();
        let c0 = cost(&model, &data);
        let mut jtj = [0.0; 4];
        let mut grad = [0.0; 2];
        for (ri, ji) in r.iter().zip(&jac) {
            for a in 0..2 {
                grad[a] += ji[a] * ri;
                for b in 0..2 {
                    jtj[a * 2 + b] += ji[a] * ji[b];
                }
            }
        }
        if iter == 0 {
            check_with_adjoint(theta, &grid, &data, grad)?;
        }
        let gnorm = grad[0].hypot(grad[1]);
        let mut delta = [-grad[0], -grad[1]];
        solve_in_place(&mut jtj, &mut delta, 2).map_err(|e| format!("singular JᵀJ: {e:?}"))?;
        let mut step = 1.0;
        let next = loop {
            let trial = [theta[0] + step * delta[0], theta[1] + step * delta[1]];
            if trial[0] > 0.0 && cost(&simulate(trial, &grid)?.0, &data) < c0 {
                break Some(trial);
            }
            step *= 0.5;
            if step < 1e-6 {
                break None;
            }
        };
        println!(
            "{iter:>4} {:>12.8} {:>12.8} {c0:>12.6e} {gnorm:>10.3e} {step:>8.2e}",
            theta[0], theta[1]
        );
        match next {
            Some(t) if (t[0] - theta[0]).abs() + (t[1] - theta[1]).abs() > 1e-12 => theta = t,
            _ => break,
        }
    }
    let (model, jac) = simulate(theta, &grid)?;
    let dof = (data.len() - 2) as f64;
    let s2 = 2.0 * cost(&model, &data) / dof;
    let mut jtj = [0.0; 4];
    for ji in &jac {
        for a in 0..2 {
            for b in 0..2 {
                jtj[a * 2 + b] += ji[a] * ji[b];
            }
        }
    }
    let det = jtj[0] * jtj[3] - jtj[1] * jtj[2];
    let (se_l, se_c) = ((s2 * jtj[3] / det).sqrt(), (s2 * jtj[0] / det).sqrt());
    println!(
        "recovered l = {:.5} ± {se_l:.5} (truth {}), c = {:.5} ± {se_c:.5} (truth {}); residual σ = {:.4}",
        theta[0],
        truth[0],
        theta[1],
        truth[1],
        s2.sqrt()
    );
    Ok(())
}

/// The gradient `Jᵀr` of the tangent run against the adjoint gradient of the same cost.
fn check_with_adjoint(
    theta: [f64; 2],
    grid: &TimeGrid,
    data: &[f64],
    grad: [f64; 2],
) -> Result<(), marsden::Error> {
    let mut vi =
        ParametricIntegrator::new(&Midpoint, DampedPendulum, &theta, NewtonOptions::default())?;
    let loss = |k: usize, x: &State, out: &mut [f64]| {
        if k > 0 && k.is_multiple_of(EVERY) {
            out[0] += x.q[0] - data[k / EVERY - 1];
        }
    };
    let g = adjoint(&mut vi, start(), grid, loss, &AdjointOptions::default())?;
    println!(
        "gradient at the start: tangent ({:.10e}, {:.10e}), adjoint ({:.10e}, {:.10e}) ({} checkpoints)",
        grad[0], grad[1], g.gradient[2], g.gradient[3], g.checkpoints
    );
    Ok(())
}
