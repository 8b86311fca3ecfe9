//! The multipliers of the DEL constraints are the discrete adjoint of the forced step.
//!
//! Kicking the DEL constraint at node `k` by `ε` (`c_k = ε`) is a momentum kick `δp_k = −ε`
//! of the forward run with the controls fixed. At the optimum `∇_z ℒ = 0`, so along that run
//! `d/dε [J + λ_Nᵀ e(x_N)] = −λ_k` (`e`: the end conditions, `λ_N` their multipliers), while
//! the same derivative is `−∂Λ/∂p_k` for the loss `Λ = J + λ_Nᵀ e(x_N)` of the run from node
//! `k` ([GW08] §3, [Sanz-Serna 2016] §5: the multipliers of the discrete equations are the
//! adjoint of the discrete map). The swing-up's cost does not depend on the state, so
//! `λ_k = ∂Λ/∂p_k = ν^p_k`, the momentum part of the core's adjoint run from `(q_k, p_k)`
//! with terminal cotangent `λ_N` — an independent computation (the step's Jacobian by the
//! implicit function theorem, transposed, backwards).

use marsden::sensitivity::{AdjointOptions, adjoint};
use marsden::systems::Pendulum;
use marsden::{Integrator, Midpoint, Rule, State, TimeGrid};
use marsden_control::{InputMap, SampledControl, SqpOptions, Status};

use super::swing_up::swing_up;

#[test]
fn del_multipliers_equal_the_discrete_adjoint_of_the_forced_step() {
    let steps = 60;
    let s = swing_up(steps)
        .solve(&Midpoint, &SqpOptions::default())
        .unwrap();
    assert_eq!(s.status, Status::Converged);
    let h = s.t[1] - s.t[0];
    let control = SampledControl {
        force: InputMap::full(1),
        grid: TimeGrid::new(0.0, h, steps).unwrap(),
        u: s.u.clone(),
    };
    let integrator = Integrator::new(Midpoint.discretize(Pendulum::default()))
        .with_force(Midpoint.discretize_force(control, 1));
    // End rows: q_N − π, then p_N − ∂L/∂v(q_N, 0) = p_N.
    let (lambda_q, lambda_p) = (s.end_multipliers[0], s.end_multipliers[1]);
    let mut worst = 0.0_f64;
    for k in [1, 2, 15, 30, 45, steps - 1] {
        let grid = TimeGrid::new(s.t[k], h, steps - k).unwrap();
        let start = State {
            t: s.t[k],
            q: s.q[k].clone(),
            p: s.p[k].clone(),
        };
        let last = steps - k;
        let loss = |i: usize, _: &State, out: &mut [f64]| {
            if i == last {
                out[0] += lambda_q;
                out[1] += lambda_p;
            }
        };
        let mut stepper = integrator.clone();
        let g = adjoint(&mut stepper, start, &grid, loss, &AdjointOptions::default()).unwrap();
        let (nu_p, lambda) = (g.gradient[1], s.costates[k - 1][0]);
        println!("k = {k}: DEL multiplier {lambda:.12}, adjoint ν^p {nu_p:.12}");
        worst = worst.max((nu_p - lambda).abs() / lambda.abs().max(1.0));
    }
    println!("largest relative difference {worst:.2e}");
    assert!(worst <= 1e-10);
}
