//! Springs and dampers between body points (`marsden::lie::multibody::{spring, damper}`): the
//! harmonic oscillator of a body on a spring to the ground (R2: the translation of the LGVI is
//! the trapezoid rule, Störmer–Verlet), the damped oscillator's decay (R12's system, stepped by
//! the trapezoidal Lagrange–d'Alembert forces), two free bodies on a spring (momenta conserved,
//! energy bounded), the closed-form gradient against automatic differentiation.

use marsden::lie::body::{Inertia, RigidBody};
use marsden::lie::invariants;
use marsden::lie::multibody::damper::{Damper, Dampers};
use marsden::lie::multibody::joints::JointSet;
use marsden::lie::multibody::spring::{Spring, Springs};
use marsden::lie::multibody::step::MultibodyLgvi;
use marsden::lie::potential::{Configuration, Loads, NoLoads, RigidPotential};
use marsden::lie::so3::{self, Vec3};
use marsden::lie::state::{BodyInitial, RigidState, RigidSystem};
use marsden::scalar::Scalar;

use super::tight;

/// The 1-D oscillator: mass `M`, stiffness `K` (ω = 2), a spring of rest length `L` from the
/// ground point `(−L, 0, 0)` to the body's centre, which starts at `(X0, 0, 0)` at rest. Along
/// `e_x`, `‖d‖ = L + x > 0`, so `U = ½ K x²` exactly.
const M: f64 = 2.0;
const K: f64 = 8.0;
const L: f64 = 1.0;
const X0: f64 = 0.3;

fn ball() -> RigidBody {
    RigidBody::free(Inertia::principal([0.4, 0.5, 0.6]).unwrap(), M).unwrap()
}

fn tether(stiffness: f64) -> Spring {
    Spring {
        bodies: [None, Some(0)],
        points: [[-L, 0.0, 0.0], [0.0; 3]],
        stiffness,
        rest_length: L,
    }
}

fn oscillator(h: f64, c: f64) -> MultibodyLgvi<Springs, NoLoads> {
    let system = RigidSystem::new(
        vec![ball()],
        Springs {
            springs: vec![tether(K)],
        },
    );
    let start = BodyInitial {
        position: [X0, 0.0, 0.0],
        ..BodyInitial::rotating(&so3::Mat3::identity(), &Vec3::zeros())
    };
    let state = RigidState::new(&system, 0.0, &[start]).unwrap();
    let joints = JointSet::new(Vec::new(), 1).unwrap();
    let damper = Damper {
        bodies: [None, Some(0)],
        points: [[-L, 0.0, 0.0], [0.0; 3]],
        coefficient: c,
    };
    let dampers = Dampers {
        dampers: if c > 0.0 { vec![damper] } else { Vec::new() },
    };
    MultibodyLgvi::new(system, joints, state, h, tight())
        .unwrap()
        .with_dampers(dampers)
}

/// `(x, p)` after `n` steps of `h`.
fn oscillate(h: f64, n: usize, c: f64) -> (f64, f64) {
    let mut lgvi = oscillator(h, c);
    for _ in 0..n {
        lgvi.step().unwrap();
    }
    let state = lgvi.state();
    (state.positions[0], state.linear_momenta[0])
}

fn slope(hs: &[f64], errors: &[f64]) -> f64 {
    let n = hs.len() as f64;
    let (x, y): (Vec<f64>, Vec<f64>) = hs.iter().zip(errors).map(|(h, e)| (h.ln(), e.ln())).unzip();
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(&y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = x.iter().map(|a| (a - mx) * (a - mx)).sum();
    sxy / sxx
}

/// R2: a body on a spring to the ground is the harmonic oscillator, `ω = √(k/m)`, and the
/// LGVI's translation is the trapezoid rule (Störmer–Verlet): its iterates are R2's discrete
/// closed form `q_n = q₀ cos nθ`, `sin(θ/2) = hω/2` (from rest), to round-off.
#[test]
fn r2_body_on_spring_is_the_discrete_trapezoid_oscillator() {
    let omega = (K / M).sqrt();
    let (h, n) = (0.05, 400);
    let theta = 2.0 * (h * omega / 2.0).asin();
    let mut lgvi = oscillator(h, 0.0);
    let mut worst = 0.0_f64;
    for k in 1..=n {
        lgvi.step().unwrap();
        let exact = X0 * (k as f64 * theta).cos();
        worst = worst.max((lgvi.state().positions[0] - exact).abs());
        assert_eq!(lgvi.state().positions[1], 0.0);
    }
    assert!(worst < 1e-13, "R2 closed form missed by {worst:e}");
}

/// R2: the error against the continuous oscillator `x = x₀ cos ωt` at `t = 2` converges at
/// order 2 (the log–log slope over three step sizes).
#[test]
fn r2_spring_oscillator_converges_at_order_two() {
    let omega = (K / M).sqrt();
    let t = 2.0;
    let (x_exact, p_exact) = (X0 * (omega * t).cos(), -M * X0 * omega * (omega * t).sin());
    let steps = [100, 200, 400];
    let hs: Vec<f64> = steps.iter().map(|&n| t / n as f64).collect();
    let errors: Vec<f64> = (steps.iter().zip(&hs))
        .map(|(&n, &h)| {
            let (x, p) = oscillate(h, n, 0.0);
            (x - x_exact).abs().max((p - p_exact).abs())
        })
        .collect();
    let order = slope(&hs, &errors);
    assert!(
        (order - 2.0).abs() < 0.05,
        "order {order}, errors {errors:?}"
    );
}

/// The damped oscillator `m ẍ = −k x − c ẋ` (R12's system) with the damper between the same
/// points as the spring: `x = e^{−ζωt}(x₀ cos ω_d t + (ζω x₀/ω_d) sin ω_d t)`, `ζ = c/(2√(km))`,
/// `ω_d = ω√(1 − ζ²)`. The trapezoidal Lagrange–d'Alembert forces keep order 2.
#[test]
fn damped_spring_of_r12s_system_decays_as_the_closed_form_at_order_two() {
    let c = 0.8;
    let omega = (K / M).sqrt();
    let zeta = c / (2.0 * (K * M).sqrt());
    let omega_d = omega * (1.0 - zeta * zeta).sqrt();
    let t = 2.0;
    let decay = (-zeta * omega * t).exp();
    let (s, co) = (omega_d * t).sin_cos();
    let x_exact = decay * X0 * (co + zeta * omega / omega_d * s);
    let p_exact = -M * decay * X0 * omega * omega / omega_d * s;
    let steps = [100, 200, 400];
    let hs: Vec<f64> = steps.iter().map(|&n| t / n as f64).collect();
    let errors: Vec<f64> = (steps.iter().zip(&hs))
        .map(|(&n, &h)| {
            let (x, p) = oscillate(h, n, c);
            (x - x_exact).abs().max((p - p_exact).abs())
        })
        .collect();
    let order = slope(&hs, &errors);
    assert!(
        (order - 2.0).abs() < 0.05,
        "order {order}, errors {errors:?}"
    );
    assert!(errors[2] < 1e-3, "errors {errors:?}");
}

/// With a damper the energy decreases at every step (the dissipation `(h/2)c(v_k² + v_{k+1}²)`
/// per step exceeds the trapezoid rule's energy oscillation of R2, `O(h³)` per step, for this
/// damping), and the run loses what the closed form loses over `t = 10` (R12's `E` decays as
/// `e^{−2ζωt}` on average).
#[test]
fn damped_spring_of_r12s_system_loses_energy_every_step() {
    let c = 0.8;
    let mut lgvi = oscillator(0.01, c);
    let mut energy = invariants::energy(lgvi.system(), lgvi.state());
    let e0 = energy;
    for step in 0..1000 {
        lgvi.step().unwrap();
        let next = invariants::energy(lgvi.system(), lgvi.state());
        assert!(
            next < energy,
            "energy rose at step {step}: {energy} → {next}"
        );
        energy = next;
    }
    let zeta = c / (2.0 * (K * M).sqrt());
    let omega = (K / M).sqrt();
    let ratio = energy / e0;
    let envelope = (-2.0 * zeta * omega * 10.0).exp();
    assert!(
        ratio < 2.0 * envelope && ratio > 0.2 * envelope,
        "E/E₀ = {ratio:e}"
    );
}

/// Two free bodies of different inertias joined by a spring at off-centre points, spinning
/// and tumbling with no field: the spring pulls along the line of its points, so the total
/// linear momentum and the angular momentum about the origin (spin included) are conserved by
/// the LGVI (discrete Noether, [MW01] §3.2).
fn dumbbell(h: f64, c: f64) -> MultibodyLgvi<Springs, NoLoads> {
    let a = RigidBody::free(Inertia::principal([0.3, 0.4, 0.5]).unwrap(), 1.5).unwrap();
    let b = RigidBody::free(Inertia::principal([0.2, 0.25, 0.3]).unwrap(), 1.0).unwrap();
    let spring = Spring {
        bodies: [Some(0), Some(1)],
        points: [[0.3, 0.1, 0.0], [-0.2, 0.0, 0.15]],
        stiffness: 20.0,
        rest_length: 1.0,
    };
    let system = RigidSystem::new(
        vec![a, b],
        Springs {
            springs: vec![spring],
        },
    );
    let ra = so3::exp(&Vec3::new(0.1, 0.2, -0.3));
    let rb = so3::exp(&Vec3::new(-0.4, 0.1, 0.2));
    let bodies = [
        BodyInitial {
            position: [-0.6, 0.0, 0.1],
            linear_momentum: [0.1, 0.3, 0.0],
            ..BodyInitial::rotating(&ra, &Vec3::new(0.2, -0.1, 0.4))
        },
        BodyInitial {
            position: [0.7, 0.1, 0.0],
            linear_momentum: [-0.2, -0.1, 0.2],
            ..BodyInitial::rotating(&rb, &Vec3::new(-0.1, 0.3, 0.1))
        },
    ];
    let state = RigidState::new(&system, 0.0, &bodies).unwrap();
    let damper = Damper {
        bodies: [Some(0), Some(1)],
        points: [[0.0, -0.1, 0.2], [0.1, 0.1, 0.0]],
        coefficient: c,
    };
    let dampers = Dampers {
        dampers: if c > 0.0 { vec![damper] } else { Vec::new() },
    };
    let joints = JointSet::new(Vec::new(), 2).unwrap();
    MultibodyLgvi::new(system, joints, state, h, tight())
        .unwrap()
        .with_dampers(dampers)
}

/// What a dumbbell run measured: the largest drifts of the momenta relative to their size, of
/// the energy relative to itself, and of the energy balance `E_n − E₀ − W_n` relative to `E₀`,
/// with `W` the dampers' work by the trapezoid rule, `W_{k+1} = W_k + (h/2)(P_k + P_{k+1})`.
struct Drifts {
    linear: f64,
    angular: f64,
    energy: f64,
    balance: f64,
}

fn dumbbell_drifts(c: f64, n: usize) -> Drifts {
    let h = 0.01;
    let mut lgvi = dumbbell(h, c);
    let power =
        |l: &MultibodyLgvi<Springs, NoLoads>| l.dampers().power(&l.system().bodies, l.state());
    let p0 = invariants::linear_momentum(lgvi.state());
    let l0 = invariants::spatial_angular_momentum(lgvi.state());
    let e0 = invariants::energy(lgvi.system(), lgvi.state());
    let mut drifts = Drifts {
        linear: 0.0,
        angular: 0.0,
        energy: 0.0,
        balance: 0.0,
    };
    let (mut work, mut last_power) = (0.0, power(&lgvi));
    for _ in 0..n {
        lgvi.step().unwrap();
        let state = lgvi.state();
        let dp = (invariants::linear_momentum(state) - p0).amax() / p0.amax();
        let dl = (invariants::spatial_angular_momentum(state) - l0).amax() / l0.amax();
        let e = invariants::energy(lgvi.system(), state);
        let p = power(&lgvi);
        work += 0.5 * h * (last_power + p);
        last_power = p;
        drifts.linear = drifts.linear.max(dp);
        drifts.angular = drifts.angular.max(dl);
        drifts.energy = drifts.energy.max((e - e0).abs() / e0);
        drifts.balance = drifts.balance.max((e - e0 - work).abs() / e0);
    }
    drifts
}

/// [MW01] §3.2 (discrete Noether): momenta to round-off over 1000 steps; the energy error is
/// bounded (no drift: ten times the steps, not ten times the error).
#[test]
fn spring_dumbbell_conserves_momenta_and_bounds_energy() {
    let short = dumbbell_drifts(0.0, 1000);
    assert!(
        short.linear < 1e-12,
        "linear momentum drifted by {:e}",
        short.linear
    );
    assert!(
        short.angular < 1e-12,
        "angular momentum drifted by {:e}",
        short.angular
    );
    let long = dumbbell_drifts(0.0, 10_000);
    let (e1, e2) = (short.energy, long.energy);
    assert!(e1 < 1e-3, "energy error {e1:e}");
    assert!(e2 < 2.0 * e1, "energy error {e1:e} → {e2:e}");
}

/// A damper between the bodies acts along the line of its points: the momenta stay conserved
/// to round-off; the energy lost is the dampers' work (the balance closes to the size of the
/// undamped run's energy error: in 3-D the energy may rise for a step where the damper's line
/// barely stretches, by the trapezoid rule's `O(h²)` energy oscillation, so it is not monotone
/// step by step as the 1-D oscillator's is).
#[test]
fn damped_dumbbell_conserves_momenta_and_balances_energy() {
    let damped = dumbbell_drifts(2.0, 1000);
    let undamped = dumbbell_drifts(0.0, 1000);
    assert!(
        damped.linear < 1e-12,
        "linear momentum drifted by {:e}",
        damped.linear
    );
    assert!(
        damped.angular < 1e-12,
        "angular momentum drifted by {:e}",
        damped.angular
    );
    assert!(
        damped.energy > 0.05,
        "the damper took only {:e} of the energy",
        damped.energy
    );
    let bound = 2.0 * undamped.energy;
    assert!(
        damped.balance < bound,
        "balance {:e}, bound {bound:e}",
        damped.balance
    );
}

/// The springs' potential without its closed-form gradient: the body moment by AD.
struct ByAd(Springs);

impl RigidPotential for ByAd {
    fn value<S: Scalar>(&self, t: S, rotations: &[S], positions: &[S]) -> S {
        self.0.value(t, rotations, positions)
    }
}

/// The closed-form gradient (the chain rule through `p = x + R X`) equals the AD body moment
/// and force, for a spring between bodies and one to the ground.
#[test]
fn spring_gradient_matches_automatic_differentiation() {
    let springs = Springs {
        springs: vec![
            Spring {
                bodies: [Some(0), Some(1)],
                points: [[0.3, 0.1, -0.2], [-0.2, 0.4, 0.15]],
                stiffness: 3.0,
                rest_length: 0.7,
            },
            Spring {
                bodies: [Some(1), None],
                points: [[0.1, 0.0, 0.3], [1.0, -1.0, 0.5]],
                stiffness: 2.0,
                rest_length: 0.0,
            },
        ],
    };
    let mut rotations = so3::rows(&so3::exp(&Vec3::new(0.3, -0.2, 0.5))).to_vec();
    rotations.extend(so3::rows(&so3::exp(&Vec3::new(-0.1, 0.7, 0.2))));
    let positions = [0.1, 0.2, -0.3, 0.9, -0.4, 0.6];
    let config = Configuration {
        t: 0.0,
        rotations: &rotations,
        positions: &positions,
        free: &[0, 1],
    };
    let (mut closed, mut ad) = (Loads::new(2), Loads::new(2));
    closed.evaluate(&springs, &NoLoads, config);
    ad.evaluate(&ByAd(springs), &NoLoads, config);
    for i in 0..2 {
        assert!((closed.moments[i] - ad.moments[i]).amax() < 1e-13);
        assert!((closed.forces[i] - ad.forces[i]).amax() < 1e-13);
        assert!(closed.forces[i].amax() > 0.1);
    }
}

/// At coincident points a zero-length spring is smooth (`U = ½k‖d‖²`: value and gradient 0),
/// and one with `ℓ₀ > 0` gives the finite value `½kℓ₀²` and a zero gradient, never NaN.
#[test]
fn spring_at_coincident_points_is_finite() {
    let rotations = so3::rows(&so3::Mat3::identity());
    let positions = [1.0, 2.0, 3.0];
    for (rest, energy) in [(0.0, 0.0), (0.5, 0.5 * 4.0 * 0.25)] {
        let spring = Spring {
            bodies: [None, Some(0)],
            points: [[1.0, 2.0, 3.0], [0.0; 3]],
            stiffness: 4.0,
            rest_length: rest,
        };
        let springs = Springs {
            springs: vec![spring],
        };
        assert_eq!(springs.value(0.0, &rotations, &positions), energy);
        let (mut dr, mut dx) = ([0.0; 9], [0.0; 3]);
        assert!(springs.gradient(0.0, &rotations, &positions, &mut dr, &mut dx));
        assert!(dr.iter().chain(&dx).all(|g| *g == 0.0));
    }
}

/// The dampers' end loads are implicit in the end momenta; the step settles them by extra
/// projections, a fixed-point iteration contracting by about `h c/m` per pass: for the
/// dumbbell (`h = 0.01`, `c = 2`, smallest mass 1) `hc/m = 0.02`, so reaching round-off
/// (`4ε` of the momenta) from an `O(1)` change takes at most `ln(4ε)/ln(0.02) ≈ 9` passes.
#[test]
fn damper_settles_in_few_projections() {
    let mut lgvi = dumbbell(0.01, 2.0);
    for _ in 0..1000 {
        lgvi.step().unwrap();
    }
    let s = lgvi.statistics();
    let per_step = s.damper_iterations as f64 / s.steps as f64;
    println!("damper projections per step: {per_step:.2}");
    assert!(
        per_step >= 1.0,
        "the damper's load was never settled: {per_step}"
    );
    let bound = (4.0 * f64::EPSILON).ln() / (0.01_f64 * 2.0 / 1.0).ln();
    assert!(
        per_step <= bound,
        "{per_step} projections per step, bound {bound:.1}"
    );
}
