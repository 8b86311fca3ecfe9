//! Compositions of second-order variational integrators reach the orders of their schemes
//! (HLW06 §II.4, §V.3; Yoshida 1990; Kahan & Li 1997), measured with the order tool on the
//! pendulum against its exact solution; the explicit (Verlet) path equals the general Newton
//! path; implicit bases compose too; the order tool also works from the flow reference.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::excessive_precision)]

use crate::common::{assert_close, tight};
use marsden::discrete::rules::composition::SCHEMES;
use marsden::discrete::rules::{Composition, CompositionScheme, Galerkin};
use marsden::studies::order::{OrderOptions, measure_order, reference_solution};
use marsden::systems::{Kepler, Pendulum};
use marsden::{Initial, Integrator, Midpoint, Problem, Rule, State, TimeGrid, Trapezoid};

fn pendulum_problem() -> Problem<Pendulum> {
    Problem::new(
        Pendulum::default(),
        Initial::velocity(&[1.5], &[0.0]),
        TimeGrid::new(0.0, 0.1, 50).unwrap(),
    )
    .unwrap()
}

#[test]
fn verlet_compositions_reach_their_orders() {
    let problem = pendulum_problem();
    let (q, p) = Pendulum::default().exact(1.5, 0.0, 5.0).unwrap();
    for scheme in SCHEMES {
        let rule = Composition::new(Trapezoid, scheme);
        let study = measure_order(
            &problem,
            &rule,
            5.0,
            &[5, 10, 20, 40, 80],
            &[q],
            &[p],
            &OrderOptions::default(),
        )
        .unwrap();
        let order = study.order.unwrap();
        println!(
            "{}: errors {:?}, pairwise {:?}, fitted {order:.3} over {} points",
            rule.name(),
            study.points.iter().map(|p| p.error).collect::<Vec<_>>(),
            study.pairwise,
            study.kept
        );
        // The last pair above round-off is within ±0.2 of the scheme's order.
        let last = study.pairwise[study.kept - 2];
        assert!(
            (last - scheme.order() as f64).abs() <= 0.2,
            "{}: asymptotic order {last:.3}",
            rule.name()
        );
    }
}

#[test]
fn explicit_composition_equals_the_general_newton_path() {
    let rule = Composition::new(Trapezoid, CompositionScheme::KahanLi6);
    let ld = rule.discretize(Kepler::default());
    let (q0, p0) = Kepler::pericentre(0.6);
    let run = |fast: bool| {
        let mut integrator = Integrator::new(ld.clone())
            .with_fast_paths(fast)
            .with_options(tight())
            .unwrap();
        integrator.set_velocity_hint(&p0);
        let mut s = State {
            t: 0.0,
            q: q0.to_vec(),
            p: p0.to_vec(),
        };
        for k in 0..200 {
            integrator.step(&mut s, 0.05).unwrap();
            s.t = (k + 1) as f64 * 0.05;
        }
        (s, *integrator.statistics())
    };
    let ((fast, stats), (slow, _)) = (run(true), run(false));
    assert_eq!(stats.explicit_steps, 200);
    // One gradient per substep (9 for Kahan–Li 6) once the first-same-as-last cache is warm:
    // each substep starts where the previous one ended, bit for bit. The time stamps rewritten
    // by the run (`s.t = k h`) may cost a refresh at a step boundary, never more than one.
    let substeps = rule.coefficients().len();
    assert_eq!(substeps, 9);
    println!("{stats:?}");
    assert!(
        stats.potential_gradients <= 200 * (substeps + 1) + 1,
        "{stats:?}: the gradient cache misses inside the composition"
    );
    for a in 0..2 {
        assert_close(fast.q[a], slow.q[a], 1e-12, "q");
        assert_close(fast.p[a], slow.p[a], 1e-12, "p");
    }
}

#[test]
fn implicit_bases_compose() {
    let problem = pendulum_problem();
    let (q, p) = Pendulum::default().exact(1.5, 0.0, 5.0).unwrap();
    let triple = CompositionScheme::TripleJump { order: 4 };
    let midpoint4 = Composition::new(Midpoint, triple);
    let gauss2x = Composition::new(
        Galerkin::gauss(2).unwrap(),
        CompositionScheme::TripleJump { order: 6 },
    );
    for (rule_name, study) in [
        (
            midpoint4.name(),
            measure_order(
                &problem,
                &midpoint4,
                5.0,
                &[10, 20, 40],
                &[q],
                &[p],
                &OrderOptions::default(),
            )
            .unwrap(),
        ),
        (
            gauss2x.name(),
            measure_order(
                &problem,
                &gauss2x,
                5.0,
                &[10, 20, 40],
                &[q],
                &[p],
                &OrderOptions::default(),
            )
            .unwrap(),
        ),
    ] {
        println!("{rule_name}: {:?} {:?}", study.points, study.pairwise);
        let last = study.pairwise[study.kept - 2];
        assert!(
            (last - study.expected as f64).abs() <= 0.25,
            "{rule_name}: {last}"
        );
    }
}

#[test]
fn flow_reference_agrees_with_the_exact_pendulum() {
    let problem = pendulum_problem();
    let (q, p) = reference_solution(&problem, 5.0).unwrap();
    let exact = Pendulum::default().exact(1.5, 0.0, 5.0).unwrap();
    assert_close(q[0], exact.0, 1e-13, "q(5)");
    assert_close(p[0], exact.1, 1e-13, "p(5)");
}
