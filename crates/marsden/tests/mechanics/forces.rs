//! Forces through the discrete Lagrange–d'Alembert principle: Hamiltonian forces, sums,
//! controls, constant and periodic driving, the energy balance for nonlinear potentials, the
//! momentum balance of Noether's theorem with forces, and forces combined with constraints.
// Tests: helpers unwrap, and reference values keep all their published digits.
#![allow(clippy::unwrap_used, clippy::excessive_precision)]

use crate::common::{assert_close, tight};
use marsden::analysis::diagnostics::{ConstraintReport, EnergyBalance, energy_series};
use marsden::forces::{
    ConstantForce, Control, ForceExt, FromHamiltonian, HamiltonianForce, LinearDamping,
    PeriodicForce, hamiltonian_form,
};
use marsden::systems::{
    DampedDrivenPendulum, FreeFall, Pendulum, PendulumOnCart, SphericalPendulum,
};
use marsden::{
    DiscreteForce, Force, Initial, Lagrangian, Midpoint, Problem, Rule, Scalar, SolveOptions,
    TimeGrid, Trajectory, Trapezoid,
};

fn options() -> SolveOptions {
    SolveOptions {
        newton: tight(),
        ..SolveOptions::default()
    }
}

fn solve<L: Lagrangian, F: Force, R: Rule>(
    l: L,
    f: F,
    initial: Initial,
    h: f64,
    steps: usize,
    rule: &R,
) -> Trajectory {
    Problem::new(l, initial, TimeGrid::new(0.0, h, steps).unwrap())
        .unwrap()
        .with_force(f)
        .solve(rule, &options())
        .unwrap()
}

fn max_state_difference(a: &Trajectory, b: &Trajectory) -> f64 {
    a.positions
        .iter()
        .zip(&b.positions)
        .chain(a.momenta.iter().zip(&b.momenta))
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// Momentum damping `f_H = −γ p`.
struct MomentumDamping(f64);

impl HamiltonianForce for MomentumDamping {
    fn hamiltonian_force<S: Scalar>(&self, _t: S, _q: &[S], p: &[S], out: &mut [S]) {
        for (o, &pi) in out.iter_mut().zip(p) {
            *o = pi * (-self.0);
        }
    }
}

#[test]
fn hamiltonian_force_is_the_lagrangian_force_composed_with_fl() {
    // Pendulum with m l² = 2: p = 2θ̇, so f_H = −γ p is f_L = −2γ θ̇.
    let pendulum = Pendulum {
        m: 2.0,
        l: 1.0,
        g: 1.0,
    };
    let gamma = 0.15;
    let initial = Initial::velocity(&[1.0], &[0.0]);
    let via_h = solve(
        pendulum,
        FromHamiltonian::new(pendulum, MomentumDamping(gamma)),
        initial.clone(),
        0.05,
        400,
        &Midpoint,
    );
    let direct = solve(
        pendulum,
        LinearDamping::uniform(2.0 * gamma).unwrap(),
        initial,
        0.05,
        400,
        &Midpoint,
    );
    let diff = max_state_difference(&via_h, &direct);
    assert!(diff < 1e-14, "{diff:e}");
    // The energy above the minimum −m g l = −2 decays like e^{−γ t} (e^{−3} at t = 20), and
    // the same Newton work was needed (the nested-AD Jacobian is exact).
    let (e0, e1) = (
        pendulum.energy(via_h.q(0)[0], via_h.p(0)[0]),
        pendulum.energy(via_h.q(400)[0], via_h.p(400)[0]),
    );
    assert!(e1 + 2.0 < 0.1 * (e0 + 2.0), "{e0} {e1}");
    assert_eq!(
        via_h.statistics.newton_iterations,
        direct.statistics.newton_iterations
    );
    // The reverse direction at a phase-space point: f_H = f_L ∘ FH.
    let mut f_h = [0.0];
    let damping = LinearDamping::uniform(2.0 * gamma).unwrap();
    hamiltonian_form(&pendulum, &damping, 0.0, &[0.3], &[1.0], &mut f_h).unwrap();
    assert_close(f_h[0], -gamma, 1e-15, "f_H(q, p) = −γ p");
}

#[test]
fn sum_of_damping_and_periodic_drive_is_the_damped_driven_pendulum() {
    let sys = DampedDrivenPendulum::default();
    let pendulum = Pendulum {
        m: sys.m,
        l: sys.l,
        g: sys.g,
    };
    let sum = LinearDamping::uniform(sys.c)
        .unwrap()
        .plus(PeriodicForce::on(0, 1, sys.amplitude, sys.omega, sys.phase).unwrap());
    let initial = Initial::velocity(&[0.2], &[0.0]);
    let a = solve(pendulum, sum, initial.clone(), 0.05, 1000, &Midpoint);
    let b = solve(sys, sys, initial.clone(), 0.05, 1000, &Midpoint);
    let diff = max_state_difference(&a, &b);
    assert!(diff < 1e-12, "{diff:e}");
    // The same drive as a control closure u(t).
    let (c, amp, w) = (sys.c, sys.amplitude, sys.omega);
    let control =
        LinearDamping::uniform(c)
            .unwrap()
            .plus(Control::new(move |t: f64, u: &mut [f64]| {
                u[0] = amp * (w * t).cos()
            }));
    let d = solve(pendulum, control, initial, 0.05, 1000, &Midpoint);
    let diff = max_state_difference(&d, &b);
    assert!(diff < 1e-12, "{diff:e}");
}

#[test]
fn constant_force_is_a_linear_potential_and_integrated_exactly() {
    // Free fall as L = ½ m v² with the force −m g (R9: variational integrators are exact).
    let fall = FreeFall::default();
    struct Free;
    impl Lagrangian for Free {
        fn dof(&self) -> usize {
            1
        }
        fn lagrangian<S: Scalar>(&self, _t: S, _q: &[S], v: &[S]) -> S {
            v[0] * v[0] * 0.5
        }
    }
    let weight = ConstantForce::new(&[-fall.m * fall.g]).unwrap();
    for rule_is_midpoint in [true, false] {
        let initial = Initial::velocity(&[10.0], &[2.0]);
        let traj = if rule_is_midpoint {
            solve(Free, weight.clone(), initial, 0.1, 50, &Midpoint)
        } else {
            solve(Free, weight.clone(), initial, 0.1, 50, &Trapezoid)
        };
        let t = traj.t(50);
        assert_close(
            traj.q(50)[0],
            10.0 + 2.0 * t - 0.5 * fall.g * t * t,
            1e-12,
            "q(5)",
        );
        assert_close(traj.p(50)[0], 2.0 - fall.g * t, 1e-12, "p(5)");
    }
}

#[test]
fn energy_balance_defect_is_the_midpoint_potential_error_and_third_order() {
    let sys = DampedDrivenPendulum::default();
    let initial = Initial::velocity(&[0.5], &[0.0]);
    let mut max_defects = Vec::new();
    for (h, steps) in [(0.04, 250), (0.02, 500)] {
        let traj = solve(sys, sys, initial.clone(), h, steps, &Midpoint);
        let balance = EnergyBalance::of(&sys, &Midpoint, &sys, &traj).unwrap();
        // Exactly: D_k = V(q₁) − V(q₀) − V'(q̄)(q₁ − q₀) with V = −cos θ.
        for k in 0..steps {
            let (q0, q1) = (traj.q(k)[0], traj.q(k + 1)[0]);
            let bracket = -q1.cos() + q0.cos() - (0.5 * (q0 + q1)).sin() * (q1 - q0);
            // Equal up to the round-off of energies of size 1 (and the Newton residual).
            assert_close(balance.defect[k], bracket, 1e-14, &format!("D_{k}"));
        }
        // Energy change = work + defect, summed: E_N − E_0.
        let e = energy_series(&sys, &traj).unwrap();
        assert_close(
            e[steps] - e[0],
            balance.total_work + balance.total_defect,
            1e-13,
            "E_N − E_0",
        );
        max_defects.push(balance.max_defect);
    }
    let ratio = max_defects[0] / max_defects[1];
    eprintln!("max |D_k|: {max_defects:?}, ratio {ratio:.3} (h³: 8)");
    assert!((7.0..=9.0).contains(&ratio), "{ratio}");
}

#[test]
fn trapezoid_energy_balance_is_approximate_with_third_order_defect() {
    let sys = DampedDrivenPendulum::default();
    let initial = Initial::velocity(&[0.5], &[0.0]);
    let mut max_defects = Vec::new();
    for (h, steps) in [(0.04, 250), (0.02, 500)] {
        let traj = solve(sys, sys, initial.clone(), h, steps, &Trapezoid);
        max_defects.push(
            EnergyBalance::of(&sys, &Trapezoid, &sys, &traj)
                .unwrap()
                .max_defect,
        );
    }
    let ratio = max_defects[0] / max_defects[1];
    eprintln!("trapezoid max |D_k|: {max_defects:?}, ratio {ratio:.3}");
    assert!((7.0..=9.0).contains(&ratio), "{ratio}");
}

#[test]
fn driven_cart_keeps_the_discrete_momentum_balance_exactly() {
    // L does not depend on the cart position x: p_x changes only by the drive, and the forced
    // discrete Noether theorem gives p_x,k+1 − p_x,k = (f_d⁻ + f_d⁺)_x = h A cos(ω(t_k + h/2)).
    let cart = PendulumOnCart::default();
    let (h, steps) = (0.01, 2000);
    let traj = solve(
        cart,
        cart,
        Initial::velocity(&[0.0, 0.3], &[0.0, 0.0]),
        h,
        steps,
        &Midpoint,
    );
    let mut worst: f64 = 0.0;
    for k in 0..steps {
        let dp = traj.p(k + 1)[0] - traj.p(k)[0];
        let impulse = h * cart.drive(traj.t(k) + 0.5 * h);
        worst = worst.max((dp - impulse).abs());
    }
    eprintln!("cart: max |Δp_x − impulse| = {worst:.1e}");
    // To the Newton residual (1e-15 relative) and the round-off of p_x.
    assert!(worst < 1e-14, "{worst:e}");
    // The pendulum swings and the cart moves.
    assert!(traj.q(steps)[0].abs() > 1e-3);
}

#[test]
fn damped_spherical_pendulum_loses_energy_keeps_its_constraint_and_momentum_balance() {
    let sphere = SphericalPendulum::default();
    let damping = LinearDamping::uniform(0.05).unwrap();
    let (h, steps) = (0.01, 20_000);
    let problem = Problem::new(
        sphere,
        sphere.initial(1.2, 0.0, 0.0, 0.9),
        TimeGrid::new(0.0, h, steps).unwrap(),
    )
    .unwrap()
    .with_force(damping.clone())
    .with_constraint(sphere)
    .unwrap();
    let traj = problem.solve(&Midpoint, &options()).unwrap();
    // Constraint and hidden constraint still held.
    let report = ConstraintReport::of(&sphere, &sphere, &traj).unwrap();
    assert!(report.max_position < 1e-14, "{:e}", report.max_position);
    assert!(report.max_velocity < 1e-14, "{:e}", report.max_velocity);
    // Energy decays: by t = 200 (ten times the damping time m/c = 20) it is close to the
    // minimum −m g l = −1, and no step raises it by more than the O(h³) defect of the
    // conservative part (measured: it falls in every step).
    let e = energy_series(&sphere, &traj).unwrap();
    let rises = e
        .windows(2)
        .map(|w| w[1] - w[0])
        .fold(f64::NEG_INFINITY, f64::max);
    eprintln!(
        "damped sphere: E_0 = {:.6}, E_N = {:.6}, largest one-step rise {rises:.1e}",
        e[0], e[steps]
    );
    assert!(e[steps] < -0.999 && e[0] > -0.4, "{} {}", e[0], e[steps]);
    assert!(rises < 1e-6, "{rises:e}");
    // Noether with forces: J_z,k+1 − J_z,k = ⟨f_d⁺, ẑ × q_{k+1}⟩ + ⟨f_d⁻, ẑ × q_k⟩ exactly
    // (constraint and projection forces are radial and do not enter).
    let fd = Midpoint.discretize_force(&damping, 3);
    let j = |i: usize| sphere.vertical_angular_momentum(traj.q(i), traj.p(i));
    let mut worst: f64 = 0.0;
    for k in 0..steps {
        let (q0, q1) = (traj.q(k), traj.q(k + 1));
        let delta: Vec<f64> = q1.iter().zip(q0).map(|(a, b)| a - b).collect();
        let mut f = [0.0; 6];
        fd.discrete_force(traj.t(k), h, q0, &delta, &mut f);
        let torque = |f: &[f64], q: &[f64]| q[0] * f[1] - q[1] * f[0];
        let expected = torque(&f[..3], q0) + torque(&f[3..], q1);
        worst = worst.max((j(k + 1) - j(k) - expected).abs());
    }
    eprintln!("damped sphere: max |ΔJ_z − discrete torque impulse| = {worst:.1e}");
    assert!(worst < 1e-14, "{worst:e}");
}
