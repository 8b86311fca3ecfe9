//! Free bodies (SO(3) × ℝ³) and several bodies: a body thrown in uniform gravity follows the
//! exact parabola (Störmer–Verlet is exact for a constant force, [HLW06] §I.1.4) while it
//! tumbles; two bodies coupled by a rotation-invariant potential keep the total spatial angular
//! momentum Σ(RΠ + x × p) and linear momentum to round-off (discrete Noether, [LLM07] §3.3); a
//! constant body torque about the axis of a symmetric body spun about it adds `hτ` per step
//! exactly (Lagrange–d'Alembert, trapezoid).

use super::tight;
use marsden::Scalar;
use marsden::lie::body::{Inertia, RigidBody};
use marsden::lie::invariants;
use marsden::lie::lgvi::Lgvi;
use marsden::lie::potential::{ExternalLoads, NoPotential, RigidPotential, UniformGravity};
use marsden::lie::so3::{self, Vec3};
use marsden::lie::state::{BodyInitial, RigidState, RigidSystem};

#[test]
fn thrown_body_follows_the_exact_parabola_while_tumbling() {
    let (mass, g) = (2.5, 9.81);
    let body = RigidBody::free(Inertia::principal([1.0, 2.0, 2.5]).unwrap(), mass).unwrap();
    let gravity = UniformGravity {
        g,
        first_moments: vec![[0.0; 3]],
        masses: vec![mass],
    };
    let system = RigidSystem::new(vec![body], gravity);
    let (x0, v0) = (Vec3::new(1.0, -2.0, 0.5), Vec3::new(0.3, 0.4, 5.0));
    let initial = BodyInitial {
        position: x0.into(),
        linear_momentum: (mass * v0).into(),
        ..BodyInitial::rotating(
            &so3::exp(&Vec3::new(0.2, 0.1, -0.3)),
            &Vec3::new(0.5, 1.0, -0.2),
        )
    };
    let state = RigidState::new(&system, 0.0, &[initial]).unwrap();
    let casimir0 = invariants::casimir(&state, 0);
    let mut lgvi = Lgvi::new(system, state, 0.01, tight()).unwrap();
    for k in 1..=200 {
        lgvi.step().unwrap();
        let t = k as f64 * 0.01;
        let exact = x0 + t * v0 - Vec3::new(0.0, 0.0, 0.5 * g * t * t);
        let x = lgvi.state().position(0);
        assert!(
            (x - exact).amax() <= 1e-13 * exact.amax(),
            "t = {t}: {x} vs {exact}"
        );
        let p = lgvi.state().linear_momentum(0);
        let p_exact = mass * (v0 - Vec3::new(0.0, 0.0, g * t));
        assert!((p - p_exact).amax() <= 1e-13 * p_exact.amax());
        assert!((invariants::casimir(lgvi.state(), 0) - casimir0).abs() <= 1e-14);
    }
}

/// `U = ½k|x₁ − x₂|² + c (R₁e₁)·(R₂e₁) + d ((R₁e₃)·(x₂ − x₁))²`: invariant under rotations of
/// space (left) and translations.
struct Coupling;

impl RigidPotential for Coupling {
    fn value<S: Scalar>(&self, _t: S, r: &[S], x: &[S]) -> S {
        let mut u = S::from(0.0);
        let mut axis = S::from(0.0);
        for k in 0..3 {
            let d = x[3 + k] - x[k];
            u += d * d * 0.5 * 3.0 + r[3 * k] * r[9 + 3 * k] * 0.7;
            axis += r[3 * k + 2] * d;
        }
        u + axis * axis * 0.4
    }
}

#[test]
fn coupled_free_bodies_keep_total_angular_and_linear_momentum() {
    let bodies = vec![
        RigidBody::free(Inertia::principal([1.0, 1.5, 2.0]).unwrap(), 1.0).unwrap(),
        RigidBody::free(Inertia::principal([0.5, 0.8, 1.1]).unwrap(), 2.0).unwrap(),
    ];
    let system = RigidSystem::new(bodies, Coupling);
    let initial = [
        BodyInitial {
            position: [0.0, 0.0, 0.0],
            linear_momentum: [0.1, 0.3, -0.2],
            ..BodyInitial::rotating(
                &so3::exp(&Vec3::new(0.3, 0.0, 0.2)),
                &Vec3::new(0.4, -0.6, 0.9),
            )
        },
        BodyInitial {
            position: [1.2, -0.4, 0.3],
            linear_momentum: [-0.3, 0.2, 0.5],
            ..BodyInitial::rotating(
                &so3::exp(&Vec3::new(-0.5, 0.7, 0.1)),
                &Vec3::new(-0.2, 0.3, 0.5),
            )
        },
    ];
    let state = RigidState::new(&system, 0.0, &initial).unwrap();
    let (l0, p0) = (
        invariants::spatial_angular_momentum(&state),
        invariants::linear_momentum(&state),
    );
    let e0 = invariants::energy(&system, &state);
    let mut lgvi = Lgvi::new(system, state, 0.01, tight()).unwrap();
    let (mut dl, mut dp, mut de): (f64, f64, f64) = (0.0, 0.0, 0.0);
    for _ in 0..2000 {
        lgvi.step().unwrap();
        let s = lgvi.state();
        dl = dl.max((invariants::spatial_angular_momentum(s) - l0).amax());
        dp = dp.max((invariants::linear_momentum(s) - p0).amax());
        de = de.max((invariants::energy(lgvi.system(), s) - e0).abs());
    }
    assert!(dl <= 1e-13, "spatial angular momentum drift {dl:.2e}");
    assert!(dp <= 1e-14, "linear momentum drift {dp:.2e}");
    assert!(de <= 1e-3 * e0.abs(), "energy error {de:.2e} of {e0}");
    assert!(invariants::orthogonality(lgvi.state()) <= 1e-14);
}

/// A constant body torque `τ e₃`.
struct Spin(f64);

impl ExternalLoads for Spin {
    fn loads(&self, _: f64, _: &[f64], _: &[f64], torques: &mut [f64], _: &mut [f64]) {
        torques[2] = self.0;
    }
}

#[test]
fn constant_torque_about_the_axis_adds_h_tau_per_step() {
    let body = RigidBody::fixed_point(Inertia::principal([2.0, 2.0, 1.0]).unwrap());
    let system = RigidSystem::new(vec![body], NoPotential).with_loads(Spin(0.3));
    let initial = BodyInitial::rotating(
        &so3::exp(&Vec3::new(0.1, 0.2, 0.0)),
        &Vec3::new(0.0, 0.0, 0.5),
    );
    let state = RigidState::new(&system, 0.0, &[initial]).unwrap();
    let mut lgvi = Lgvi::new(system, state, 0.05, tight()).unwrap();
    for k in 1..=400 {
        lgvi.step().unwrap();
        let pi = lgvi.state().momentum(0);
        let expected = 0.5 + 0.3 * 0.05 * k as f64;
        assert!(
            (pi.z - expected).abs() <= 1e-13 * expected,
            "step {k}: {} vs {expected}",
            pi.z
        );
        assert!(pi.x.abs() + pi.y.abs() <= 1e-14);
    }
}
