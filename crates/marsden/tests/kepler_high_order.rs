//! Long runs of the high-order variational integrators on Kepler e = 0.6 (reference case R10's
//! problem): over 10⁵ steps the angular momentum (discrete Noether) is constant to 1e-12, the
//! energy error is bounded with no drift, and its size scales as hᵖ with the method's order p
//! (HLW06 Ch. IX: `H(y_n) − H(y_0) = O(hᵖ)` over exponentially long times).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::excessive_precision)]

mod common;
use common::{loglog_slope, tight};
use marsden::rules::{Method, WithRule};
use marsden::{Integrator, Rule, State, systems::Kepler};

/// Energy and angular-momentum errors of one run.
struct Run {
    /// Steps per period 2π.
    per_period: usize,
    steps: usize,
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
        let mut integrator = Integrator::new(rule.discretize(kepler)).with_options(tight()).unwrap();
        integrator.set_velocity_hint(&p0);
        let mut s = State { t: 0.0, q: q0.to_vec(), p: p0.to_vec() };
        let (e0, l0) = (kepler.energy(&s.q, &s.p), Kepler::angular_momentum(&s.q, &s.p));
        let tenth = self.steps / 10;
        let mut errors = Errors { energy: (0.0, 0.0), angular: 0.0 };
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

/// `(method, steps per period for the long run)`; the energy order is fitted on 4 periods at
/// N, 2N, 4N steps per period.
fn check(name: &str, per_period: usize) {
    let method = Method::parse(name).unwrap();
    let order = method.order() as f64;
    let long = method.dispatch(Run { per_period, steps: 100_000 });
    println!(
        "{name}: h = 2π/{per_period}, 10⁵ steps: max|ΔL| = {:.2e}, max|ΔH| first/last tenth = {:.3e} / {:.3e}",
        long.angular, long.energy.0, long.energy.1
    );
    assert!(long.angular <= 1e-12, "{name}: angular momentum drifts by {:.2e}", long.angular);
    let ratio = long.energy.1 / long.energy.0;
    assert!((0.9..=1.1).contains(&ratio), "{name}: energy error grows, ratio {ratio}");
    let ns = [per_period / 2, per_period, 2 * per_period];
    let hs: Vec<f64> = ns.iter().map(|n| 1.0 / *n as f64).collect();
    let energy: Vec<f64> = ns
        .iter()
        .map(|&n| {
            let e = method.dispatch(Run { per_period: n, steps: 4 * n });
            e.energy.0.max(e.energy.1)
        })
        .collect();
    let slope = loglog_slope(&hs, &energy);
    println!("{name}: energy errors {energy:?} at N = {ns:?}: order {slope:.3}");
    assert!((slope - order).abs() <= 0.3, "{name}: energy error order {slope}, expected {order}");
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
fn lobatto_3_long_run() {
    check("lobatto-3", 400);
}

#[test]
fn kahan_li_6_verlet_long_run() {
    check("kahan-li-6(trapezoid)", 200);
}

#[test]
fn suzuki_umeno_8_verlet_long_run() {
    check("suzuki-umeno-8(trapezoid)", 100);
}
