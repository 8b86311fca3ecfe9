//! Reference case R6: Galerkin variational integrators `P_s` with Gauss and Lobatto quadrature
//! have order `2s` (Gauss, `s` points) and `2s − 2` (Lobatto, `s` points); error values,
//! regression values at h = 0.1, and the equivalences with the 2-stage Gauss RK method and the
//! 3-stage Lobatto IIIA–IIIB partitioned RK method.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::excessive_precision)]

use crate::common::{assert_close, run, tight};
use marsden::discrete::rules::{Galerkin, QuadratureFamily};
use marsden::systems::Pendulum;
use marsden::{Initial, Problem, Rule, SolveOptions, TimeGrid};

const EXACT_T5: (f64, f64) = (-0.6247457443050779, 1.2168604323725019);

fn rule(s: usize, family: QuadratureFamily, r: usize) -> Galerkin {
    Galerkin::new(s, family, r).unwrap()
}

/// Error `|(q_N, p_N) − (q(T), p(T))|` (Euclidean) at T = 5 with N steps.
fn error_at_t5(g: &Galerkin, n: usize) -> f64 {
    let s = run(
        g.discretize(Pendulum::default()),
        &[1.5],
        &[0.0],
        5.0 / n as f64,
        n,
    );
    (s.q[0] - EXACT_T5.0).hypot(s.p[0] - EXACT_T5.1)
}

#[test]
fn r6_error_values_and_orders() {
    use QuadratureFamily::{Gauss, Lobatto};
    // (s, family, r, expected order, e(10), e(20), e(40), e(80)); None: round-off.
    #[allow(clippy::type_complexity)]
    let rows: [(usize, QuadratureFamily, usize, f64, [Option<f64>; 4]); 9] = [
        (
            1,
            Gauss,
            1,
            2.0,
            [
                Some(4.914e-2),
                Some(1.225e-2),
                Some(3.059e-3),
                Some(7.647e-4),
            ],
        ),
        (
            1,
            Lobatto,
            2,
            2.0,
            [
                Some(4.293e-2),
                Some(1.051e-2),
                Some(2.615e-3),
                Some(6.529e-4),
            ],
        ),
        (
            2,
            Gauss,
            2,
            4.0,
            [
                Some(2.192e-4),
                Some(1.374e-5),
                Some(8.594e-7),
                Some(5.373e-8),
            ],
        ),
        (
            2,
            Lobatto,
            3,
            4.0,
            [
                Some(1.464e-4),
                Some(8.530e-6),
                Some(5.240e-7),
                Some(3.261e-8),
            ],
        ),
        (
            2,
            Gauss,
            3,
            4.0,
            [
                Some(7.635e-5),
                Some(5.005e-6),
                Some(3.164e-7),
                Some(1.983e-8),
            ],
        ),
        (
            3,
            Gauss,
            3,
            6.0,
            [
                Some(6.746e-7),
                Some(1.143e-8),
                Some(1.824e-10),
                Some(2.9e-12),
            ],
        ),
        (
            3,
            Lobatto,
            4,
            6.0,
            [
                Some(6.681e-7),
                Some(9.400e-9),
                Some(1.430e-10),
                Some(2.3e-12),
            ],
        ),
        (
            4,
            Gauss,
            4,
            8.0,
            [Some(8.602e-9), Some(3.492e-11), None, None],
        ),
        (
            4,
            Lobatto,
            5,
            8.0,
            [Some(3.752e-9), Some(1.386e-11), None, None],
        ),
    ];
    for (s, family, r, order, expected) in rows {
        let g = rule(s, family, r);
        assert_eq!(g.order() as f64, order, "{}", g.name());
        let mut errors = Vec::new();
        for (k, e) in expected.iter().enumerate() {
            let Some(e) = *e else { break };
            let err = error_at_t5(&g, 10 << k);
            // The table gives 4 digits: relative 1e-6 of the table means "to the digits given"
            // (half a unit of the last digit), and absolute 1e-12 for the P3 rows at N = 80.
            let digits = if e < 1e-11 { 0.1e-12 } else { 0.5e-3 * e };
            assert!(
                (err - e).abs() <= digits.max(1e-12),
                "{} N = {}: error {err:.4e}, table {e:.4e}",
                g.name(),
                10 << k
            );
            errors.push(err);
        }
        for pair in errors.windows(2) {
            let observed = (pair[0] / pair[1]).log2();
            // P3 at N = 80 is near round-off: its pair is checked only against ±0.2 as well.
            assert!(
                (observed - order).abs() <= 0.2,
                "{}: observed order {observed:.3}, expected {order}",
                g.name()
            );
        }
    }
}

#[test]
fn r6_regression_values_at_h_0_1() {
    use QuadratureFamily::{Gauss, Lobatto};
    let cases = [
        (
            rule(2, Gauss, 2),
            -1.054048751245201,
            -0.920128157454560,
            (1.163e-7, 1e-10),
        ),
        (
            rule(2, Lobatto, 3),
            -1.054049148074836,
            -0.920127505192869,
            (-1.388e-7, 1e-10),
        ),
        (
            rule(3, Gauss, 3),
            -1.054049155334075,
            -0.920127649219868,
            (-1.46e-11, 1e-13),
        ),
        (
            rule(3, Lobatto, 4),
            -1.054049155469696,
            -0.920127649145713,
            (3.5e-11, 1e-12),
        ),
        (
            rule(1, Gauss, 1),
            -1.050881405153385,
            -0.923194845294426,
            (7.526e-5, 1e-8),
        ),
        (
            rule(1, Lobatto, 2),
            -1.056937687332870,
            -0.916909286877726,
            (-4.427e-4, 1e-7),
        ),
    ];
    let pendulum = Pendulum::default();
    // H_100 − H_0 is quoted to 2–4 digits: `unit` is one unit of its last digit.
    for (g, q, p, (de, unit)) in cases {
        let s = run(g.discretize(pendulum), &[1.5], &[0.0], 0.1, 100);
        assert_close(s.q[0], q, 1e-11, &format!("{} q_100", g.name()));
        assert_close(s.p[0], p, 1e-11, &format!("{} p_100", g.name()));
        let energy = pendulum.energy(s.q[0], s.p[0]) - pendulum.energy(1.5, 0.0);
        assert!(
            (energy - de).abs() <= 0.5 * unit,
            "{}: ΔH {energy:.4e} vs {de:.4e}",
            g.name()
        );
    }
}

/// The 2-stage Gauss collocation method (order 4) on `q' = p, p' = −sin q`, by fixed-point
/// iteration of its stage equations to round-off (HLW06 Table II.1.1).
fn gauss2_rk(q0: f64, p0: f64, h: f64, steps: usize) -> (f64, f64) {
    let r = 3.0_f64.sqrt() / 6.0;
    let a = [[0.25, 0.25 - r], [0.25 + r, 0.25]];
    let (mut q, mut p) = (q0, p0);
    let (mut kq, mut kp) = ([p0; 2], [-q0.sin(); 2]);
    for _ in 0..steps {
        for _ in 0..200 {
            let old = (kq, kp);
            for i in 0..2 {
                let qi = q + h * (a[i][0] * kq[0] + a[i][1] * kq[1]);
                let pi = p + h * (a[i][0] * kp[0] + a[i][1] * kp[1]);
                (kq[i], kp[i]) = (pi, -qi.sin());
            }
            if old == (kq, kp) {
                break;
            }
        }
        q += h * 0.5 * (kq[0] + kq[1]);
        p += h * 0.5 * (kp[0] + kp[1]);
    }
    (q, p)
}

/// The 3-stage Lobatto IIIA–IIIB partitioned RK method (order 4) on `q' = p, p' = −sin q`
/// (HLW06 §II.2.2, Tables II.2.1–2): IIIA for q, IIIB for p, fixed-point iteration.
fn lobatto3_prk(q0: f64, p0: f64, h: f64, steps: usize) -> (f64, f64) {
    let a = [
        [0.0, 0.0, 0.0],
        [5.0 / 24.0, 1.0 / 3.0, -1.0 / 24.0],
        [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0],
    ];
    let ab = [
        [1.0 / 6.0, -1.0 / 6.0, 0.0],
        [1.0 / 6.0, 1.0 / 3.0, 0.0],
        [1.0 / 6.0, 5.0 / 6.0, 0.0],
    ];
    let b = [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0];
    let (mut q, mut p) = (q0, p0);
    let (mut kq, mut kp) = ([p0; 3], [-q0.sin(); 3]);
    for _ in 0..steps {
        for _ in 0..200 {
            let old = (kq, kp);
            let stage = |m: &[[f64; 3]; 3], i: usize, k: &[f64; 3]| {
                m[i][0] * k[0] + m[i][1] * k[1] + m[i][2] * k[2]
            };
            let qs: [f64; 3] = std::array::from_fn(|i| q + h * stage(&a, i, &kq));
            let ps: [f64; 3] = std::array::from_fn(|i| p + h * stage(&ab, i, &kp));
            kq = ps;
            kp = qs.map(|x| -x.sin());
            if old == (kq, kp) {
                break;
            }
        }
        q += h * (b[0] * kq[0] + b[1] * kq[1] + b[2] * kq[2]);
        p += h * (b[0] * kp[0] + b[1] * kp[1] + b[2] * kp[2]);
    }
    (q, p)
}

#[test]
fn r6_gauss_and_lobatto_equivalences() {
    let pendulum = Pendulum::default();
    let vi = run(
        Galerkin::gauss(2).unwrap().discretize(pendulum),
        &[1.5],
        &[0.0],
        0.1,
        100,
    );
    let rk = gauss2_rk(1.5, 0.0, 0.1, 100);
    assert_close(vi.q[0], rk.0, 1e-14, "P2-Gauss2 vs Gauss RK, q");
    assert_close(vi.p[0], rk.1, 1e-14, "P2-Gauss2 vs Gauss RK, p");
    assert_close(rk.0, -1.054048751245201, 1e-11, "Gauss RK, q_100");
    let vi = run(
        Galerkin::lobatto(3).unwrap().discretize(pendulum),
        &[1.5],
        &[0.0],
        0.1,
        100,
    );
    let prk = lobatto3_prk(1.5, 0.0, 0.1, 100);
    assert_close(vi.q[0], prk.0, 1e-14, "P2-Lobatto3 vs Lobatto IIIA–IIIB, q");
    assert_close(vi.p[0], prk.1, 1e-14, "P2-Lobatto3 vs Lobatto IIIA–IIIB, p");
    assert_close(prk.0, -1.054049148074836, 1e-11, "Lobatto IIIA–IIIB, q_100");
}

#[test]
fn high_degree_rules_run_and_converge() {
    // s = 5, 6 with Gauss and Lobatto: order 10, 12 — checked against the exact solution.
    let problem = Problem::new(
        Pendulum::default(),
        Initial::velocity(&[1.5], &[0.0]),
        TimeGrid::new(0.0, 0.5, 10).unwrap(),
    )
    .unwrap();
    let (q5, p5) = Pendulum::default().exact(1.5, 0.0, 5.0).unwrap();
    let options = SolveOptions {
        newton: tight(),
        ..SolveOptions::default()
    };
    for g in [
        Galerkin::gauss(5).unwrap(),
        Galerkin::gauss(6).unwrap(),
        Galerkin::lobatto(6).unwrap(),
        Galerkin::lobatto(7).unwrap(),
    ] {
        let run = problem.solve(&g, &options).unwrap();
        let last = run.len() - 1;
        let err = (run.q(last)[0] - q5).hypot(run.p(last)[0] - p5);
        assert!(err < 1e-6, "{}: {err:e}", g.name());
    }
}
