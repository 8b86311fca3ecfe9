//! Reference case R12: the damped oscillator `m q̈ = −k q − c q̇` with the midpoint discrete
//! Lagrangian and midpoint discrete forces (discrete Lagrange–d'Alembert): one-step matrix,
//! exact discrete energy balance, table of states and order 2.
// Tests: helpers unwrap, and reference values keep all their published digits.
#![allow(clippy::unwrap_used, clippy::excessive_precision)]

use crate::common::{assert_close, loglog_slope, tight};
use marsden::analysis::diagnostics::EnergyBalance;
use marsden::forces::{TwoPoint, TwoPointForce};
use marsden::systems::DampedOscillator;
use marsden::{
    Initial, Integrator, Midpoint, Problem, Rule, Scalar, SolveOptions, State, TimeGrid, Trajectory,
};

const H: f64 = 0.1;

fn solve(osc: DampedOscillator, h: f64, steps: usize) -> Trajectory {
    let grid = TimeGrid::new(0.0, h, steps).unwrap();
    let problem = Problem::new(osc, Initial::momentum(&[1.0], &[0.0]), grid)
        .unwrap()
        .with_force(osc);
    let options = SolveOptions {
        newton: tight(),
        ..SolveOptions::default()
    };
    problem.solve(&Midpoint, &options).unwrap()
}

/// One step from `(q, p)` with the integrator built by hand from `L_d` and `f_d^±`.
fn one_step(q: f64, p: f64) -> (f64, f64) {
    let osc = DampedOscillator::default();
    let mut integrator = Integrator::new(Midpoint.discretize(osc))
        .with_force(Midpoint.discretize_force(osc, 1))
        .with_options(tight())
        .unwrap();
    let mut state = State {
        t: 0.0,
        q: vec![q],
        p: vec![p],
    };
    integrator.step(&mut state, H).unwrap();
    (state.q[0], state.p[0])
}

#[test]
fn r12_one_step_matrix_is_401_40_minus40_397_over_403() {
    let (a, b) = (one_step(1.0, 0.0), one_step(0.0, 1.0));
    let m = [[a.0, b.0], [a.1, b.1]];
    let exact = [[401.0, 40.0], [-40.0, 397.0]];
    for i in 0..2 {
        for j in 0..2 {
            assert_close(m[i][j], exact[i][j] / 403.0, 1e-15, &format!("M[{i}][{j}]"));
        }
    }
    // Eigenvalues: Re = trace/2, |λ|² = det = 160797/403².
    let re = 0.5 * (m[0][0] + m[1][1]);
    let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    assert_close(re, 0.99007444168734491315, 1e-15, "Re λ");
    assert_close(det.sqrt(), 0.99502484475883561385, 1e-15, "|λ|");
    assert_close(
        (det - re * re).sqrt(),
        0.099131436007137364346,
        1e-14,
        "Im λ",
    );
}

#[test]
fn r12_table_of_states_to_1e12() {
    let osc = DampedOscillator::default();
    // (N, q_N, p_N, E_N) of the discrete solution, then the exact (q, p).
    let table = [
        (
            1,
            0.99503722084367246,
            -0.099255583126550868,
            0.49997537082304552,
        ),
        (
            10,
            0.55569741018856952,
            -0.80046509553937927,
            0.47477199043357543,
        ),
        (
            100,
            -0.53230291760077280,
            0.32014012028468461,
            0.19291804635109372,
        ),
        (
            1000,
            0.0048158391797281277,
            0.0045974056831669146,
            2.2164223010309965e-5,
        ),
    ];
    let exact = [
        (0.9950207737420776, -0.099335909578646851),
        (0.55499172061789833, -0.80079010735330936),
        (-0.52920881890701978, 0.32397955310035503),
        (0.0051334703750402773, 0.0041152017043413016),
    ];
    let traj = solve(osc, H, 1000);
    let solution = osc.exact(1.0, 0.0).unwrap();
    for ((n, q, p, e), (qx, px)) in table.into_iter().zip(exact) {
        let (qn, pn) = (traj.q(n)[0], traj.p(n)[0]);
        assert_close(qn, q, 1e-12, &format!("q_{n}"));
        assert_close(pn, p, 1e-12, &format!("p_{n}"));
        assert_close(osc.energy(qn, pn), e, 1e-12, &format!("E_{n}"));
        let (qe, pe) = solution.state(n as f64 * H).unwrap();
        assert_close(qe, qx, 1e-14, &format!("exact q({n}h)"));
        assert_close(pe, px, 1e-14, &format!("exact p({n}h)"));
    }
}

#[test]
fn r12_exact_discrete_energy_balance_per_step_to_1e14() {
    let osc = DampedOscillator::default();
    let traj = solve(osc, H, 1000);
    let mut worst: f64 = 0.0;
    for k in 0..1000 {
        let (q0, p0, q1, p1) = (
            traj.q(k)[0],
            traj.p(k)[0],
            traj.q(k + 1)[0],
            traj.p(k + 1)[0],
        );
        let de = osc.energy(q1, p1) - osc.energy(q0, p0);
        let balance = de + osc.c * (q1 - q0) * (q1 - q0) / H;
        worst = worst.max(balance.abs());
        assert!(de <= 0.0, "energy increased in step {k}: {de:e}");
    }
    eprintln!("R12: max |E_k+1 − E_k + c Δq²/h| = {worst:.1e} over 1000 steps");
    assert!(worst <= 1e-14, "max |E_k+1 − E_k + c Δq²/h| = {worst:e}");
    // The same through the diagnostic: the discrete work is −c Δq²/h and the defect vanishes.
    let balance = EnergyBalance::of(&osc, &Midpoint, &osc, &traj).unwrap();
    assert_eq!(balance.defect.len(), 1000);
    assert!(balance.max_defect <= 1e-14, "{:e}", balance.max_defect);
    for k in [0, 10, 999] {
        let dq = traj.q(k + 1)[0] - traj.q(k)[0];
        assert_close(balance.work[k], -osc.c * dq * dq / H, 1e-16, "W_k");
    }
    let e_end = osc.energy(traj.q(1000)[0], traj.p(1000)[0]);
    assert_close(e_end - 0.5, balance.total_work, 1e-13, "E_N − E_0 = Σ W_k");
}

#[test]
fn r12_order_two_from_errors_at_t10() {
    let osc = DampedOscillator::default();
    let solution = osc.exact(1.0, 0.0).unwrap();
    let (qe, pe) = solution.state(10.0).unwrap();
    let steps = [50, 100, 200, 400];
    let table = [1.967e-2, 4.931e-3, 1.234e-3, 3.084e-4];
    let mut hs = Vec::new();
    let mut errors = Vec::new();
    for (n, expected) in steps.into_iter().zip(table) {
        let h = 10.0 / n as f64;
        let traj = solve(osc, h, n);
        let e = (traj.q(n)[0] - qe).hypot(traj.p(n)[0] - pe);
        // Four significant digits in the table.
        assert!(
            (e / expected - 1.0).abs() < 1e-3,
            "h = {h}: {e:.4e} vs {expected:.3e}"
        );
        hs.push(h);
        errors.push(e);
    }
    let slope = loglog_slope(&hs, &errors);
    eprintln!("R12: errors at t = 10 {errors:?}, order {slope:.4}");
    assert!((slope - 2.0).abs() < 0.01, "order {slope}");
}

/// R12's discrete forces written by hand, `f_d^± = −(c/2)(q₁ − q₀)`, as a user-supplied
/// discrete force: the same map as the rule's quadrature of `f = −c v`.
struct HandWrittenDamping(f64);

impl TwoPointForce for HandWrittenDamping {
    fn two_point_force<S: Scalar>(
        &self,
        _t0: f64,
        _h: f64,
        q0: &[S],
        q1: &[S],
        minus: &mut [S],
        plus: &mut [S],
    ) {
        minus[0] = (q1[0] - q0[0]) * (-0.5 * self.0);
        plus[0] = minus[0];
    }
}

#[test]
fn r12_user_supplied_discrete_forces_give_the_same_map() {
    let osc = DampedOscillator::default();
    let mut integrator = Integrator::new(Midpoint.discretize(osc))
        .with_force(TwoPoint(HandWrittenDamping(osc.c)))
        .with_options(tight())
        .unwrap();
    let mut state = State {
        t: 0.0,
        q: vec![1.0],
        p: vec![0.0],
    };
    for _ in 0..10 {
        integrator.step(&mut state, H).unwrap();
    }
    assert_close(state.q[0], 0.55569741018856952, 1e-12, "q_10");
    assert_close(state.p[0], -0.80046509553937927, 1e-12, "p_10");
}
