//! A discrete Lagrangian written as an expression ([`ExprDiscreteLagrangian`]) stepped by the
//! core's integrator: the midpoint rule's `L_d` written by hand gives the midpoint map.

use marsden::{Integrator, Lagrangian, Midpoint, NewtonOptions, Rule, State};
use marsden_expr::{Program, Symbols};
use marsden_spec::model::ExprDiscreteLagrangian;
use marsden_spec::model::ExprLagrangian;
use marsden_spec::model::discrete_lagrangian::endpoint_inputs;
use marsden_spec::model::slots::tangent_inputs;

const STEPS: usize = 2000;
const H: f64 = 0.05;

/// Steps `integrator` `STEPS` times from the pendulum's (θ, p) = (1.5, 0); the final state.
fn run<D: marsden::DiscreteAction>(integrator: &mut Integrator<D>) -> (f64, f64) {
    let mut s = State {
        t: 0.0,
        q: vec![1.5],
        p: vec![0.0],
    };
    for k in 0..STEPS {
        integrator.step(&mut s, H).unwrap();
        s.t = (k + 1) as f64 * H;
    }
    (s.q[0], s.p[0])
}

/// R4's pendulum (w2 = 1): `L_d = h L((θ₀+θ₁)/2, (θ₁−θ₀)/h)` typed as an expression and the
/// midpoint rule applied to `L = ½θ̇² + cos θ` are the same function of `(θ₀, θ₁)` in exact
/// arithmetic, so the two maps agree after 2000 steps of h = 0.05 up to round-off: the
/// expression forms `θ₁ − θ₀` from rounded positions (an error `ε|θ|` per step, `ε|θ|/h` in the
/// momenta) where the rule uses the step's offset, a random walk of ~√N · 1e-14 growing at most
/// linearly along the integrable pendulum: bounded here by 1e-10.
#[test]
fn r4_hand_written_midpoint_discrete_lagrangian_gives_the_midpoint_map() {
    let coordinates = vec!["theta".to_owned()];
    let text = "h*(0.5*((theta_1 - theta_0)/h)^2 + cos((theta_0 + theta_1)/2))";
    let symbols = Symbols::with_inputs(endpoint_inputs(&coordinates)).unwrap();
    let ld = ExprDiscreteLagrangian::new(Program::compile(text, &symbols).unwrap(), 1);
    let symbols = Symbols::with_inputs(tangent_inputs(&coordinates)).unwrap();
    let program = Program::compile("0.5*theta_dot^2 + cos(theta)", &symbols).unwrap();
    let l = ExprLagrangian::new(program, 1).without_structure();
    assert_eq!(l.dof(), 1);
    let newton = NewtonOptions::default();
    let mut user = Integrator::new(ld).with_options(newton).unwrap();
    let mut rule = Integrator::new(Midpoint.discretize(l))
        .with_options(newton)
        .unwrap()
        .with_fast_paths(false);
    let (a, b) = (run(&mut user), run(&mut rule));
    println!(
        "user L_d: ({:.17e}, {:.17e}); midpoint: ({:.17e}, {:.17e}); differences {:.2e}, {:.2e}",
        a.0,
        a.1,
        b.0,
        b.1,
        (a.0 - b.0).abs(),
        (a.1 - b.1).abs()
    );
    assert!((a.0 - b.0).abs() <= 1e-10 && (a.1 - b.1).abs() <= 1e-10);
}
