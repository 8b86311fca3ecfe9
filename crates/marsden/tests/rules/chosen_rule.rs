//! A method chosen at run time used as a rule itself ([`marsden::discrete::rules::chosen`])
//! computes the same map as the concrete rule [`Method::dispatch`] passes: the same trajectory,
//! bit for bit, for every family of rules, with forces (the damped oscillator of R12), with
//! holonomic constraints (the spherical pendulum) and on the explicit and separable fast paths
//! (Kepler, which is separable).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common::tight;
use marsden::discrete::rules::{Method, WithRule};
use marsden::systems::{DampedOscillator, Kepler, SphericalPendulum};
use marsden::{
    Constraint, Force, Initial, Lagrangian, Problem, Rule, SolveOptions, TimeGrid, Trajectory,
};

const METHODS: [&str; 10] = [
    "midpoint",
    "trapezoid",
    "alpha-0.3",
    "symmetrized-0.2",
    "gauss-2",
    "lobatto-3",
    "galerkin-2-gauss-3",
    "triple-jump-4(trapezoid)",
    "suzuki-4(midpoint)",
    "yoshida-6(lobatto-2)",
];

/// Solves `problem` with the concrete rule.
struct Concrete<'a, L, F, C>(&'a Problem<L, F, C>, &'a SolveOptions);

impl<L: Lagrangian, F: Force, C: Constraint> WithRule for Concrete<'_, L, F, C> {
    type Output = Result<Trajectory, String>;
    fn call<R: Rule>(self, rule: &R) -> Self::Output {
        self.0.solve(rule, self.1).map_err(|f| f.error.to_string())
    }
}

/// Asserts that `method` as a rule and the dispatched concrete rule give identical runs (or
/// the same refusal).
fn same_runs<L: Lagrangian, F: Force, C: Constraint>(
    problem: &Problem<L, F, C>,
    name: &str,
    options: &SolveOptions,
) {
    let method = Method::parse(name).unwrap();
    let concrete = method.dispatch(Concrete(problem, options));
    let chosen = problem
        .solve(&method, options)
        .map_err(|f| f.error.to_string());
    match (concrete, chosen) {
        (Ok(a), Ok(b)) => {
            assert_eq!(a.len(), b.len(), "{name}");
            for i in 0..a.len() {
                assert_eq!(a.q(i), b.q(i), "{name}: q at sample {i}");
                assert_eq!(a.p(i), b.p(i), "{name}: p at sample {i}");
            }
            assert_eq!(a.statistics, b.statistics, "{name}: Newton work");
        }
        (Err(a), Err(b)) => assert_eq!(a, b, "{name}: refusals"),
        (a, b) => panic!("{name}: concrete {:?}, chosen {:?}", a.err(), b.err()),
    }
}

fn options(general_path: bool) -> SolveOptions {
    SolveOptions {
        newton: tight(),
        general_path,
        ..SolveOptions::default()
    }
}

#[test]
fn kepler_runs_are_bit_for_bit_those_of_the_concrete_rules_on_every_path() {
    let kepler = Kepler::default();
    let (q, p) = Kepler::pericentre(0.6);
    let problem = Problem::new(
        kepler,
        Initial::momentum(&q, &p),
        TimeGrid::new(0.0, 0.05, 200).unwrap(),
    )
    .unwrap();
    for name in METHODS {
        same_runs(&problem, name, &options(false));
        same_runs(&problem, name, &options(true));
    }
}

#[test]
fn r12_damped_runs_are_bit_for_bit_those_of_the_concrete_rules() {
    let osc = DampedOscillator::default();
    let problem = Problem::new(
        osc,
        Initial::momentum(&[1.0], &[0.0]),
        TimeGrid::new(0.0, 0.1, 100).unwrap(),
    )
    .unwrap()
    .with_force(osc);
    for name in METHODS {
        same_runs(&problem, name, &options(false));
    }
}

#[test]
fn constrained_runs_are_bit_for_bit_those_of_the_concrete_rules() {
    let p = SphericalPendulum::default();
    let problem = Problem::new(
        p,
        p.initial(1.0, 0.0, 0.0, 0.8),
        TimeGrid::new(0.0, 0.02, 100).unwrap(),
    )
    .unwrap()
    .with_constraint(p)
    .unwrap();
    // The Gauss rules are refused with constraints: the refusal must be the same too.
    for name in METHODS {
        same_runs(&problem, name, &options(false));
    }
}
