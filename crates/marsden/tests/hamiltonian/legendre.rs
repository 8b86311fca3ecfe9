//! The Legendre adapters on a Lagrangian that is not quadratic in the velocities (a
//! relativistic particle in an anharmonic well): H built from L by FH (and L from H by FL) agrees
//! with the closed form in value, gradient and Hessian — the derivatives flow through the inner
//! Newton solve exactly — and a degenerate Lagrangian is reported, not silently integrated.
#![allow(clippy::unwrap_used, clippy::expect_used)] // tests may unwrap

use marsden::error::{SetupError, StepError, StepFailure};
use marsden::hamiltonian::{
    Hamiltonian, HamiltonianIntegrator, HamiltonianLagrangian, ImplicitMidpoint,
    LegendreHamiltonian, PhaseJet,
};
use marsden::mechanics::{self, LagrangianJet};
use marsden::{Error, Lagrangian, NewtonOptions, Scalar, State};

fn potential<S: Scalar>(q: S) -> S {
    q * q * 0.5 + q * q * q * q * 0.1
}

/// L = −√(1 − v²) − V(q) (m = c = 1).
#[derive(Clone, Copy)]
struct RelativisticL;
impl Lagrangian for RelativisticL {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        -(-(v[0] * v[0]) + 1.0).sqrt() - potential(q[0])
    }
}

/// H = √(1 + p²) + V(q), its Legendre transform.
#[derive(Clone, Copy)]
struct RelativisticH;
impl Hamiltonian for RelativisticH {
    fn dof(&self) -> usize {
        1
    }
    fn hamiltonian<S: Scalar>(&self, _t: S, q: &[S], p: &[S]) -> S {
        (p[0] * p[0] + 1.0).sqrt() + potential(q[0])
    }
}

#[test]
fn hamiltonian_from_lagrangian_matches_closed_form_to_second_derivatives() {
    let from_l = LegendreHamiltonian::new(RelativisticL);
    for (q, p) in [(0.3, 0.0), (-1.2, 2.5), (0.7, -8.0)] {
        let exact = PhaseJet::at(&RelativisticH, 0.0, &[q], &[p]);
        let adapted = PhaseJet::at(&from_l, 0.0, &[q], &[p]);
        assert!((exact.value - adapted.value).abs() < 1e-13);
        assert!((from_l.try_value(0.0, &[q], &[p]).unwrap() - exact.value).abs() < 1e-13);
        for (a, b) in exact.grad.iter().zip(&adapted.grad) {
            assert!((a - b).abs() < 1e-13, "gradient {a} vs {b} at ({q}, {p})");
        }
        for (a, b) in exact.hess.iter().zip(&adapted.hess) {
            assert!((a - b).abs() < 1e-12, "Hessian {a} vs {b} at ({q}, {p})");
        }
    }
}

#[test]
fn lagrangian_from_hamiltonian_matches_closed_form() {
    let from_h = HamiltonianLagrangian::new(RelativisticH);
    for (q, v) in [(0.3, 0.0), (-1.2, 0.9), (0.7, -0.99)] {
        let (exact, adapted) = (
            LagrangianJet::at(&RelativisticL, 0.0, &[q], &[v]),
            LagrangianJet::at(&from_h, 0.0, &[q], &[v]),
        );
        assert!((exact.value - adapted.value).abs() < 1e-13);
        assert!((exact.dl_dv[0] - adapted.dl_dv[0]).abs() < 1e-12);
        assert!((exact.dl_dq[0] - adapted.dl_dq[0]).abs() < 1e-13);
        let rel = (exact.d2l_dv2[0] - adapted.d2l_dv2[0]).abs() / exact.d2l_dv2[0];
        assert!(
            rel < 1e-12,
            "mass {} vs {}",
            exact.d2l_dv2[0],
            adapted.d2l_dv2[0]
        );
        // Energy E_L(q, v) = H(q, FL(q, v)).
        let e = mechanics::energy(&RelativisticL, 0.0, &[q], &[v]);
        let h: f64 = RelativisticH.hamiltonian(0.0, &[q], &[exact.dl_dv[0]]);
        assert!((e - h).abs() < 1e-12);
    }
}

#[test]
fn implicit_midpoint_on_the_adapter_follows_the_closed_form() {
    let options = NewtonOptions {
        residual_tolerance: 1e-15,
        ..NewtonOptions::default()
    };
    let mut exact =
        HamiltonianIntegrator::new(RelativisticH, ImplicitMidpoint::new(options).unwrap());
    let mut adapted = HamiltonianIntegrator::new(
        LegendreHamiltonian::new(RelativisticL),
        ImplicitMidpoint::new(options).unwrap(),
    );
    let start = State {
        t: 0.0,
        q: vec![1.0],
        p: vec![3.0],
    };
    let (mut a, mut b) = (start.clone(), start);
    for _ in 0..200 {
        exact.step(&mut a, 0.05).unwrap();
        adapted.step(&mut b, 0.05).unwrap();
    }
    assert!((a.q[0] - b.q[0]).abs() < 1e-12 && (a.p[0] - b.p[0]).abs() < 1e-12);
}

/// L = q v: linear in v, so ∂²L/∂v² = 0 and there is no Hamiltonian.
struct Degenerate;
impl Lagrangian for Degenerate {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        q[0] * v[0]
    }
}

#[test]
fn degenerate_lagrangian_is_reported() {
    let h = LegendreHamiltonian::new(Degenerate);
    assert!(matches!(
        h.try_value(0.0, &[1.0], &[2.0]),
        Err(Error::Setup(SetupError::InverseLegendre { .. }))
    ));
    let value: f64 = h.hamiltonian(0.0, &[1.0], &[2.0]);
    assert!(value.is_nan());
    let mut integrator = HamiltonianIntegrator::new(h, ImplicitMidpoint::default());
    let mut state = State {
        t: 0.0,
        q: vec![1.0],
        p: vec![2.0],
    };
    let err = integrator.step(&mut state, 0.1).unwrap_err();
    assert!(
        matches!(
            err,
            Error::Step(StepFailure {
                step: 0,
                cause: StepError::NonFinite { .. },
                ..
            })
        ),
        "{err:?}"
    );
    assert_eq!(state.q, vec![1.0]);
}
