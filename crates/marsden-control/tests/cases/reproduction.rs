//! An optimal trajectory satisfies the core's forced DEL equations and reproduces itself when
//! its controls are fed to the core's integrator ([OJM11] §3: the constraints are the
//! discrete equations of motion).

use marsden::discrete::legendre;
use marsden::systems::Pendulum;
use marsden::{
    DiscreteForce, GeneralizedMidpoint, Initial, Midpoint, Problem, Rule, SolveOptions, TimeGrid,
    Trapezoid,
};
use marsden_control::{
    FrozenControl, InputMap, SampledControl, Solution, SqpOptions, StagedControls, Status,
};

use super::swing_up::swing_up;

const STEPS: usize = 60;

fn solve<R: Rule + StagedControls>(rule: &R) -> Solution {
    let solution = swing_up(STEPS).solve(rule, &SqpOptions::default()).unwrap();
    assert_eq!(solution.status, Status::Converged, "{}", rule.name());
    solution
}

/// `max_k |D₂L_d(q_{k−1}, q_k) + f_d⁺_{k−1} + D₁L_d(q_k, q_{k+1}) + f_d⁻_k|` with the core's
/// `L_d`, derivatives (`discrete::legendre`) and discrete forces of the frozen controls.
fn del_residual<R: Rule>(rule: &R, s: &Solution) -> f64
where
    R::Discrete<Pendulum>: marsden::DiscreteLagrangian,
{
    let ld = rule.discretize(Pendulum::default());
    let h = s.t[1] - s.t[0];
    let forces = |k: usize| {
        let frozen = FrozenControl {
            force: InputMap::full(1),
            u: s.u[k].clone(),
        };
        let fd = rule.discretize_force(frozen, 1);
        let mut out = [0.0; 2];
        let offset = [s.q[k + 1][0] - s.q[k][0]];
        fd.discrete_force(s.t[k], h, &s.q[k], &offset, &mut out);
        out
    };
    let mut worst = 0.0_f64;
    for k in 1..STEPS {
        let (mut d2, mut d1) = ([0.0], [0.0]);
        legendre::d2(&ld, s.t[k - 1], h, &s.q[k - 1], &s.q[k], &mut d2);
        legendre::d1(&ld, s.t[k], h, &s.q[k], &s.q[k + 1], &mut d1);
        let residual = d2[0] + forces(k - 1)[1] + d1[0] + forces(k)[0];
        worst = worst.max(residual.abs());
    }
    worst
}

#[test]
fn midpoint_optimum_satisfies_the_core_forced_del() {
    let s = solve(&Midpoint);
    let residual = del_residual(&Midpoint, &s);
    println!("midpoint forced DEL residual {residual:.2e}");
    assert!(residual <= 1e-10);
}

#[test]
fn trapezoid_optimum_satisfies_the_core_forced_del() {
    let s = solve(&Trapezoid);
    let residual = del_residual(&Trapezoid, &s);
    println!(
        "trapezoid forced DEL residual {residual:.2e}, cost {:.6}",
        s.cost
    );
    assert!(residual <= 1e-10);
}

/// Feeds `u_k` to the core's integrator from `(q_0, p_0)` and compares every `q_k`.
fn reproduction_error<R: Rule>(rule: &R, s: &Solution) -> f64 {
    let grid = TimeGrid::new(0.0, s.t[1] - s.t[0], STEPS).unwrap();
    let control = SampledControl {
        force: InputMap::full(1),
        grid,
        u: s.u.clone(),
    };
    let problem = Problem::new(
        Pendulum::default(),
        Initial::momentum(&s.q[0], &s.p[0]),
        grid,
    )
    .unwrap()
    .with_force(control);
    let run = problem.solve(rule, &SolveOptions::default()).unwrap();
    (0..=STEPS)
        .map(|k| {
            (run.q(k)[0] - s.q[k][0])
                .abs()
                .max((run.p(k)[0] - s.p[k][0]).abs())
        })
        .fold(0.0, f64::max)
}

#[test]
fn midpoint_optimum_reproduces_itself_in_the_core_integrator() {
    let s = solve(&Midpoint);
    let error = reproduction_error(&Midpoint, &s);
    println!("midpoint reproduction error {error:.2e}");
    assert!(error <= 1e-8);
}

#[test]
fn alpha_rule_optimum_reproduces_itself_in_the_core_integrator() {
    let rule = GeneralizedMidpoint::new(0.3).unwrap();
    let s = solve(&rule);
    let error = reproduction_error(&rule, &s);
    println!(
        "alpha 0.3 reproduction error {error:.2e}, cost {:.6}",
        s.cost
    );
    assert!(error <= 1e-8);
}
