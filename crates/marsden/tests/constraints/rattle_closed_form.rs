//! RATTLE's closed form for a constant mass matrix (`Rattle` on a separable Lagrangian) and its
//! Newton form (the reference, `with_closed_form(false)`) give the same projection to
//! round-off: one projection to a few ulps, and a whole SHAKE + RATTLE run of the Cartesian
//! double pendulum (two constraints, unequal masses) no further apart than a one-ulp change of
//! the initial momentum moves the reference run.

// Tests may unwrap.
#![allow(clippy::unwrap_used)]

use marsden::holonomic::{MomentumProjection, Rattle};
use marsden::systems::{CartesianDoublePendulum, DoublePendulum, SphericalPendulum};
use marsden::{Initial, Integrator, Midpoint, Rule, State};

fn max_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

#[test]
fn one_projection_agrees_with_the_newton_form() {
    let pendulum = SphericalPendulum {
        m: 2.5,
        ..SphericalPendulum::default()
    };
    // A point on the sphere |q| = l and a momentum with a radial part.
    let l = pendulum.l;
    let (a, b) = (0.7_f64, 1.9_f64);
    let q = [l * a.sin() * b.cos(), l * a.sin() * b.sin(), -l * a.cos()];
    let p_tilde = [0.3, -1.1, 0.8];
    let mut closed = Rattle::new(pendulum, pendulum);
    let mut newton = Rattle::new(pendulum, pendulum).with_closed_form(false);
    let (mut p1, mut p2) = (p_tilde, p_tilde);
    closed.project_at(0.0, &q, &mut p1).unwrap();
    newton.project_at(0.0, &q, &mut p2).unwrap();
    assert!(
        max_difference(&p1, &p2) <= 4.0 * f64::EPSILON,
        "{p1:?} vs {p2:?}"
    );
    assert!((closed.multipliers()[0] - newton.multipliers()[0]).abs() <= 4.0 * f64::EPSILON);
    // The hidden constraint q · v = 0 holds for the closed form's velocity v = p/m.
    let radial: f64 = q.iter().zip(closed.velocity()).map(|(x, v)| x * v).sum();
    assert!(radial.abs() <= 4.0 * f64::EPSILON, "q·v = {radial:e}");
    assert_eq!(closed.statistics().closed_form, 1);
    assert_eq!(newton.statistics().closed_form, 0);
    assert!(newton.statistics().kkt_evaluations >= 1);
}

/// Unequal masses and rods, so `M⁻¹` is not a multiple of the identity.
fn system() -> CartesianDoublePendulum {
    CartesianDoublePendulum::from(DoublePendulum {
        m1: 1.0,
        m2: 0.4,
        l1: 1.0,
        l2: 0.7,
        g: 9.81,
    })
}

fn run(start: &State, closed_form: bool, steps: usize) -> (Vec<f64>, usize) {
    let sys = system();
    let mut integrator = Integrator::new(Midpoint.discretize(sys))
        .with_constraint(sys)
        .with_projection(Rattle::new(sys, sys).with_closed_form(closed_form));
    let mut s = start.clone();
    let mut out = Vec::new();
    for _ in 0..steps {
        integrator.step(&mut s, 0.005).unwrap();
        out.extend(s.q.iter().chain(&s.p));
    }
    (out, integrator.projection().statistics().closed_form)
}

#[test]
fn a_shake_rattle_run_agrees_with_the_newton_form_to_round_off() {
    let sys = system();
    let Initial::Velocity { q, v } = sys.initial([1.2, -0.4], [0.0, 0.5]) else {
        panic!("the Cartesian double pendulum starts from velocities");
    };
    // p = M v with M = diag(m₁, m₁, m₂, m₂).
    let p = v
        .iter()
        .enumerate()
        .map(|(k, vk)| vk * if k < 2 { 1.0 } else { 0.4 })
        .collect();
    let start = State { t: 0.0, q, p };
    let steps = 1000;
    let (closed, count) = run(&start, true, steps);
    let (newton, none) = run(&start, false, steps);
    assert_eq!((count, none), (steps, 0));
    let mut nudged = start.clone();
    nudged.p[3] = f64::from_bits(nudged.p[3].to_bits() + 1);
    let sensitivity = max_difference(&newton, &run(&nudged, false, steps).0).max(f64::EPSILON);
    let d = max_difference(&closed, &newton);
    assert!(
        d <= 10.0 * sensitivity,
        "closed form and Newton form differ by {d:e}; one ulp of p₀ moves the run by {sensitivity:e}"
    );
}
