//! Long runs of the high-order variational integrators on Kepler e = 0.6 (reference case R10's
//! problem): over 10⁵ steps the angular momentum (discrete Noether) is constant to 1e-12, the
//! energy error is bounded with no drift, and its size scales as hᵖ with the method's order p
//! (HLW06 Ch. IX: `H(y_n) − H(y_0) = O(hᵖ)` over exponentially long times).
//!
//! The full 10⁵ steps run in the default tier: tests are built with opt-level 2 (workspace
//! `[profile.dev]`), and the whole file takes about 10 s.
//!
//! Measured (h = 2π/N, 10⁵ steps, Newton to round-off):
//!
//! | method | N | max\|ΔL\| | max\|ΔH\| first / last tenth | energy order (N, 2N, 4N) |
//! |---|---|---|---|---|
//! | gauss-2 | 400 | 2.2e-13 | 3.910e-8 / 3.910e-8 | 4.0 |
//! | gauss-3 | 200 | 7.2e-13 | 1.074e-9 / 1.073e-9 | 5.9 |
//! | kahan-li-6(trapezoid) | 200 | 8.8e-14 | 1.905e-8 / 1.905e-8 | 6.0 |
//! | suzuki-umeno-8(trapezoid) | 100 | 7.7e-14 | 3.870e-9 / 3.870e-9 | 8.1 |
//! | lobatto-3 | 400 | 1.08e-12 → **1.9e-14** | 7.686e-8 / 7.686e-8 | 4.0 |
//! | gauss-4 | 200 | 1.6e-11 → **1.4e-15** | 2.1e-12 / 2.0e-11 → **2.51e-13 / 2.52e-13** | — |
//!
//! The arrows give the runs with compensated summation of the state update
//! ([`marsden::integrator::compensated`]). Without it, lobatto-3 misses the 1e-12 bound on `L` by 8 %, and
//! gauss-4 (and every rule of degree ≥ 4 tried: gauss-5, lobatto-4, lobatto-5) shows a *linear*
//! round-off drift of `L` (~1e-16 per step) and of `H`, which swamps its 1e-12 truncation
//! error. The drift is round-off, not the Newton tolerance: tightening the residual tolerance
//! to 1e-18 changes lobatto-3's 1.08e-12 only to 7.8e-13. It is coherent rather than a random
//! walk because `h` divides the period and the rounding errors repeat every orbit. Compensated
//! summation of `q + Δ` alone does not help (1.10e-12, 1.61e-11): the momentum `p_{k+1}` comes
//! out of the step as a number of the size of `p`; the cure is to add the increment
//! `p_{k+1} − p_k = ∇_{Q₀} L_d` (offsets fixed) as such, compensated. gauss-4's energy order is
//! not fitted: at N = 400 its error is already round-off.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::excessive_precision)]

use crate::common::tight;
use marsden::discrete::rules::{Method, WithRule};
use marsden::studies::order::empirical_order;
use marsden::systems::Kepler;
use marsden::{Integrator, Rule, State};

/// Energy and angular-momentum errors of one run.
struct Run {
    /// Steps per period 2π.
    per_period: usize,
    steps: usize,
    /// Compensated summation of the state update.
    compensated: bool,
}

struct Errors {
    /// max |ΔH| over the first and the last tenth of the run.
    energy: (f64, f64),
    /// max |L_k − L_0|.
    angular: f64,
}

impl WithRule for Run {
    type Output = Errors;
    fn call<R: Rule>(self, rule: &R) -> Errors {
        let kepler = Kepler::default();
        let (q0, p0) = Kepler::pericentre(0.6);
        let h = 2.0 * std::f64::consts::PI / self.per_period as f64;
        let mut integrator = Integrator::new(rule.discretize(kepler))
            .with_options(tight())
            .unwrap()
            .with_compensated_summation(self.compensated);
        integrator.set_velocity_hint(&p0);
        let mut s = State {
            t: 0.0,
            q: q0.to_vec(),
            p: p0.to_vec(),
        };
        let (e0, l0) = (
            kepler.energy(&s.q, &s.p),
            Kepler::angular_momentum(&s.q, &s.p),
        );
        let tenth = self.steps / 10;
        let mut errors = Errors {
            energy: (0.0, 0.0),
            angular: 0.0,
        };
        for k in 0..self.steps {
            integrator.step(&mut s, h).unwrap();
            s.t = (k + 1) as f64 * h;
            let de = (kepler.energy(&s.q, &s.p) - e0).abs();
            if k < tenth {
                errors.energy.0 = errors.energy.0.max(de);
            }
            if k >= self.steps - tenth {
                errors.energy.1 = errors.energy.1.max(de);
            }
            let dl = (Kepler::angular_momentum(&s.q, &s.p) - l0).abs();
            errors.angular = errors.angular.max(dl);
        }
        errors
    }
}

/// Energy errors below this are round-off (|H| = 0.5, 4 periods of up to 3200 steps: the
/// energy of the exact-to-round-off runs wanders by ~1e-14) and are left out of the order fit.
const ENERGY_ROUND_OFF: f64 = 1e-13;

/// The long run at `per_period` steps per period, 10⁵ steps.
fn long_run(name: &str, per_period: usize, compensated: bool) -> Errors {
    let method = Method::parse(name).unwrap();
    let long = method.dispatch(Run {
        per_period,
        steps: 100_000,
        compensated,
    });
    println!(
        "{name} (compensated: {compensated}): h = 2π/{per_period}, 10⁵ steps: max|ΔL| = {:.2e}, max|ΔH| first/last tenth = {:.3e} / {:.3e}",
        long.angular, long.energy.0, long.energy.1
    );
    long
}

/// The long run at `per_period` steps per period: angular momentum and energy bounds.
fn check_long_run(name: &str, per_period: usize, compensated: bool) -> Errors {
    let long = long_run(name, per_period, compensated);
    assert!(
        long.angular <= 1e-12,
        "{name}: angular momentum drifts by {:.2e}",
        long.angular
    );
    let ratio = long.energy.1 / long.energy.0;
    assert!(
        (0.9..=1.1).contains(&ratio),
        "{name}: energy error grows, ratio {ratio}"
    );
    long
}

/// The energy error's order, fitted on 4 periods at N, 2N, 4N steps per period (N that of the
/// long run, the asymptotic regime), leaving out points at round-off
/// ([`marsden::studies::order::empirical_order`]).
fn check_energy_order(name: &str, per_period: usize) {
    let method = Method::parse(name).unwrap();
    let order = method.order() as f64;
    let ns = [per_period, 2 * per_period, 4 * per_period];
    let hs: Vec<f64> = ns.iter().map(|n| 1.0 / *n as f64).collect();
    let energy: Vec<f64> = ns
        .iter()
        .map(|&n| {
            let e = method.dispatch(Run {
                per_period: n,
                steps: 4 * n,
                compensated: false,
            });
            e.energy.0.max(e.energy.1)
        })
        .collect();
    let (slope, kept) = empirical_order(&hs, &energy, ENERGY_ROUND_OFF);
    let slope = slope.unwrap();
    println!("{name}: energy errors {energy:?} at N = {ns:?}: order {slope:.3} over {kept} points");
    assert!(
        (slope - order).abs() <= 0.3,
        "{name}: energy error order {slope}, expected {order}"
    );
}

fn check(name: &str, per_period: usize) {
    check_long_run(name, per_period, false);
    check_energy_order(name, per_period);
}

#[test]
fn gauss_2_long_run() {
    check("gauss-2", 400);
}

#[test]
fn gauss_3_long_run() {
    check("gauss-3", 200);
}

#[test]
fn lobatto_3_energy_order() {
    check_energy_order("lobatto-3", 400);
}

/// Compensated: max|ΔL| = 1.9e-14 over 10⁵ steps at h = 2π/400 (1.08e-12 without, module doc).
#[test]
fn lobatto_3_long_run_compensated() {
    check_long_run("lobatto-3", 400, true);
}

/// Compensated: max|ΔL| = 1.4e-15 and the energy error 2.51e-13 / 2.52e-13 (first / last
/// tenth) at h = 2π/200; without compensation the same run drifts (module doc), and this test
/// shows it: `L` at least 100× worse, the energy error growing by more than 2×.
#[test]
fn gauss_4_long_run_compensated() {
    let compensated = check_long_run("gauss-4", 200, true);
    let plain = long_run("gauss-4", 200, false);
    assert!(
        plain.angular > 100.0 * compensated.angular,
        "plain {:.2e}, compensated {:.2e}",
        plain.angular,
        compensated.angular
    );
    assert!(plain.energy.1 > 2.0 * plain.energy.0);
}

#[test]
fn kahan_li_6_verlet_long_run() {
    check("kahan-li-6(trapezoid)", 200);
}

#[test]
fn suzuki_umeno_8_verlet_long_run() {
    check("suzuki-umeno-8(trapezoid)", 100);
}
