//! High-order rules with forces and holonomic constraints.
//!
//! * Forces: the Galerkin rules discretise `f_L` by the same quadrature as `L`
//!   (`f_j = h Σ_i b_i ℓ_j(c_i) f(c_i)`, [MW01] §3.2), compositions sum their substeps' forces.
//!   On the damped oscillator (R12's system, exact solution in the catalog) the order of the
//!   forced Lagrange–d'Alembert step is that of the rule.
//! * Constraints: the Lobatto rules impose `φ = 0` at every interior node (constrained Lobatto
//!   IIIA–IIIB, Jay 1996) and compositions at every substep (each a SHAKE + RATTLE step, Reich
//!   1996), followed by the RATTLE projection of `p_{k+1}` onto `T*N`. On the spherical pendulum
//!   in Cartesian coordinates `L = ½ m|v|² − m g z` is quadratic, so every rule's unconstrained
//!   step is exact and the whole error is the constraint's: with the constraint at the step ends
//!   only, every rule gave the midpoint rule's trajectory (errors 3.322e-2 … 1.281e-4 at
//!   h = 5/25 … 5/400, order 2.00); with stage constraints lobatto-3 and suzuki-4(midpoint) are
//!   order 4. The Gauss rules have no stage constraints and are refused (their runs fail).
//!
//! [MW01]: Marsden & West, Acta Numerica 10 (2001).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::excessive_precision)]

use crate::common::tight;
use marsden::discrete::exact::EulerLagrangeFlow;
use marsden::discrete::rules::{Method, WithRule};
use marsden::studies::order::{OrderOptions, OrderStudy, measure_order};
use marsden::systems::{DampedOscillator, SphericalPendulum};
use marsden::{Initial, Lagrangian, Problem, Rule, Scalar, TimeGrid};

/// `[1.234e-5, …]`.
fn fmt(xs: &[f64]) -> String {
    let items: Vec<String> = xs.iter().map(|x| format!("{x:.3e}")).collect();
    format!("[{}]", items.join(", "))
}

/// Order study of one method on the damped oscillator over `[0, 10]` against the exact
/// solution.
struct Damped<'a>(&'a [usize]);

impl WithRule for Damped<'_> {
    type Output = OrderStudy;
    fn call<R: Rule>(self, rule: &R) -> OrderStudy {
        let osc = DampedOscillator::default();
        let t_end = 10.0;
        let problem = Problem::new(
            osc,
            Initial::momentum(&[1.0], &[0.0]),
            TimeGrid::new(0.0, 1.0, 1).unwrap(),
        )
        .unwrap()
        .with_force(osc);
        let (q, p) = osc.exact(1.0, 0.0).unwrap().state(t_end).unwrap();
        let options = OrderOptions {
            newton: tight(),
            ..OrderOptions::default()
        };
        measure_order(&problem, rule, t_end, self.0, &[q], &[p], &options).unwrap()
    }
}

fn check_damped(name: &str, steps: &[usize], expected: f64) {
    let study = Method::parse(name).unwrap().dispatch(Damped(steps));
    let errors: Vec<f64> = study.points.iter().map(|p| p.error).collect();
    println!(
        "{name}: damped oscillator errors {}, pairwise orders {:.3?}",
        fmt(&errors),
        study.pairwise
    );
    assert_eq!(study.expected as f64, expected);
    for order in &study.pairwise[..study.kept - 1] {
        assert!(
            (order - expected).abs() <= 0.2,
            "{name}: pairwise order {order:.3}, expected {expected}"
        );
    }
}

/// R12's system at order 4 with Galerkin forces: measured 4.00 (gauss-2), 4.00 (lobatto-3).
#[test]
fn r12_damped_oscillator_gauss_2_and_lobatto_3_forces_are_order_4() {
    check_damped("gauss-2", &[20, 40, 80, 160], 4.0);
    check_damped("lobatto-3", &[20, 40, 80, 160], 4.0);
}

/// Order 6 and 8 with forces: gauss-3 and gauss-4.
#[test]
fn r12_damped_oscillator_gauss_3_and_4_forces_keep_their_order() {
    check_damped("gauss-3", &[10, 20, 40], 6.0);
    check_damped("gauss-4", &[5, 10, 20], 8.0);
}

/// Compositions of the midpoint rule with forces in every substep.
#[test]
fn r12_damped_oscillator_compositions_with_forces_keep_their_order() {
    check_damped("suzuki-4(midpoint)", &[20, 40, 80, 160], 4.0);
    // Measured 5.75 from N = 10 to 20 (pre-asymptotic), then 5.94, 5.98, 6.00.
    check_damped("kahan-li-6(midpoint)", &[20, 40, 80, 160], 6.0);
}

/// The spherical pendulum in spherical angles `(θ, ϕ)`, θ from the downward vertical:
/// `L = ½ m l² (θ̇² + sin²θ ϕ̇²) + m g l cos θ` — the same system without a constraint, for the
/// reference solution.
#[derive(Clone, Copy)]
struct Angles(SphericalPendulum);

impl Lagrangian for Angles {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        let SphericalPendulum { m, l, g } = self.0;
        let s = q[0].sin();
        (v[0] * v[0] + s * s * v[1] * v[1]) * (0.5 * m * l * l) + q[0].cos() * (m * g * l)
    }
}

const THETA: (f64, f64) = (1.0, 0.0);
const PHI: (f64, f64) = (0.0, 0.8);

/// `(q(T), p(T))` in Cartesian coordinates from the angle flow (extrapolation to round-off).
fn spherical_reference(t_end: f64) -> (Vec<f64>, Vec<f64>) {
    let pendulum = SphericalPendulum::default();
    let SphericalPendulum { m, l, .. } = pendulum;
    let flow = EulerLagrangeFlow::new(Angles(pendulum));
    let end = flow
        .advance(0.0, t_end, &[THETA.0, PHI.0], &[THETA.1, PHI.1])
        .unwrap();
    let ([th, ph], [dth, dph]) = ([end.q[0], end.q[1]], [end.v[0], end.v[1]]);
    let q = vec![
        l * th.sin() * ph.cos(),
        l * th.sin() * ph.sin(),
        -l * th.cos(),
    ];
    let v = [
        l * (th.cos() * ph.cos() * dth - th.sin() * ph.sin() * dph),
        l * (th.cos() * ph.sin() * dth + th.sin() * ph.cos() * dph),
        l * th.sin() * dth,
    ];
    (q, v.iter().map(|x| m * x).collect())
}

struct Spherical<'a>(&'a [usize], f64);

impl WithRule for Spherical<'_> {
    type Output = OrderStudy;
    fn call<R: Rule>(self, rule: &R) -> OrderStudy {
        let pendulum = SphericalPendulum::default();
        let initial = pendulum.initial(THETA.0, PHI.0, THETA.1, PHI.1);
        let problem = Problem::new(pendulum, initial, TimeGrid::new(0.0, 1.0, 1).unwrap())
            .unwrap()
            .with_constraint(pendulum)
            .unwrap();
        let (q, p) = spherical_reference(self.1);
        let options = OrderOptions {
            newton: tight(),
            ..OrderOptions::default()
        };
        measure_order(&problem, rule, self.1, self.0, &q, &p, &options).unwrap()
    }
}

/// Order of `name` with SHAKE at the step ends and the RATTLE projection, over `[0, 5]`.
fn spherical_study(name: &str) -> OrderStudy {
    let study = Method::parse(name)
        .unwrap()
        .dispatch(Spherical(&[25, 50, 100, 200, 400], 5.0));
    let errors: Vec<f64> = study.points.iter().map(|p| p.error).collect();
    println!(
        "{name} + RATTLE: spherical pendulum errors {}, pairwise orders {:.3?}",
        fmt(&errors),
        study.pairwise
    );
    study
}

/// The check of the reference: the midpoint rule with SHAKE + RATTLE is order 2.
#[test]
fn spherical_pendulum_midpoint_rattle_is_order_2() {
    let study = spherical_study("midpoint");
    for order in &study.pairwise {
        assert!((order - 2.0).abs() <= 0.1, "midpoint order {order}");
    }
}

/// R13: order-4 rules with stage constraints are order 4 on the spherical pendulum, and no
/// longer give the midpoint rule's trajectory; gauss-2 is refused (every run fails).
#[test]
fn r13_spherical_pendulum_order_4_rules_with_stage_constraints_are_order_4() {
    let midpoint = spherical_study("midpoint");
    for name in ["lobatto-3", "suzuki-4(midpoint)"] {
        let study = spherical_study(name);
        let (a, b) = (study.points[2].error, midpoint.points[2].error);
        assert!(
            a < b / 10.0,
            "{name}: error {a:e} vs the midpoint rule's {b:e}"
        );
        assert_eq!(study.expected, 4);
        let last = study.pairwise[study.kept - 2];
        assert!(
            (last - 4.0).abs() <= 0.2,
            "{name}: asymptotic order {last:.3} with stage constraints"
        );
    }
    let gauss = spherical_study("gauss-2");
    assert!(gauss.points.iter().all(|p| p.error.is_nan()), "{gauss:?}");
}
