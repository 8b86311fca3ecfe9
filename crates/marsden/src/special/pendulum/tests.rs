//! Tests of the exact pendulum solution: the project's reference values, values from a
//! 30-digit Taylor integration (mpmath `odefun`), and the equation of motion itself.

use super::*;

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * b.abs().max(1.0)
}

#[test]
fn project_reference_values() {
    // L = ½q̇² + cos q, ω = 1, q₀ = 1.5, p₀ = 0.
    let pendulum = Pendulum::new(1.5, 0.0, 1.0).unwrap();
    assert_eq!(pendulum.motion(), PendulumMotion::Libration);
    let cases = [
        (5.0, -0.6247457443050779, 1.2168604323725019),
        (10.0, -1.054049155450843, -0.920127649125370),
    ];
    for (t, q, p) in cases {
        let (qt, pt) = pendulum.state(t).unwrap();
        assert!(
            (qt - q).abs() < 1e-13 && (pt - p).abs() < 1e-13,
            "t={t}: {qt}, {pt}"
        );
    }
    // Against the 40-digit values (mpmath): q(5) = −0.62474574430507902524…,
    // p(5) = 1.21686043237250187028…, q(10) = −1.05404915545084323288…,
    // p(10) = −0.92012764912536936007…; the solution is within a few ulps.
    let (q5, p5) = pendulum.state(5.0).unwrap();
    let (q10, p10) = pendulum.state(10.0).unwrap();
    assert!((q5 + 0.624_745_744_305_079).abs() < 2e-15);
    assert!((p5 - 1.216_860_432_372_501_9).abs() < 2e-15);
    assert!((q10 + 1.054_049_155_450_843_3).abs() < 2e-15);
    assert!((p10 + 0.920_127_649_125_369_4).abs() < 2e-15);
}

#[test]
fn general_initial_data_against_taylor_integration() {
    // (θ₀, θ̇₀, ω, t, θ(t), θ̇(t)), θ(t) from mpmath odefun at 30 digits.
    #[rustfmt::skip]
    let cases = [
        (-2.0, 0.8, 0.9, 7.3, -0.03794270995523618, -1.7125979969672078),
        (-2.0, 0.8, 0.9, -4.1, -0.3425948604712439, -1.6852339369277074),
        (0.3, 2.5, 1.2, 3.7, 5.57273520923441, 2.383666908887852),
        (0.3, 2.5, 1.2, -2.2, -3.16348225383137, 0.7869694189675858),
        (7.0, -3.1, 1.0, 2.5, -0.12419035257422877, -3.175971042136502),
    ];
    for (theta0, thetadot0, omega, t, theta, thetadot) in cases {
        let pendulum = Pendulum::new(theta0, thetadot0, omega).unwrap();
        let (q, p) = pendulum.state(t).unwrap();
        assert!(
            close(q, theta, 1e-14),
            "{theta0}, {thetadot0}, {omega}, t={t}: {q}"
        );
        assert!(
            close(p, thetadot, 1e-14),
            "{theta0}, {thetadot0}, {omega}, t={t}: {p}"
        );
    }
}

#[test]
fn reproduces_initial_data_and_classifies_motion() {
    let cases = [
        (0.0, 0.0, PendulumMotion::Libration),
        (1.0, -0.5, PendulumMotion::Libration),
        (-3.0, 0.1, PendulumMotion::Libration),
        (12.0, 0.3, PendulumMotion::Libration),
        (0.0, 2.5, PendulumMotion::Rotation),
        (2.0, -2.2, PendulumMotion::Rotation),
        (-20.0, 4.0, PendulumMotion::Rotation),
        (0.0, 2.0, PendulumMotion::Separatrix),
        (0.0, -2.0, PendulumMotion::Separatrix),
    ];
    for (theta0, thetadot0, motion) in cases {
        let pendulum = Pendulum::new(theta0, thetadot0, 1.0).unwrap();
        assert_eq!(pendulum.motion(), motion, "{theta0}, {thetadot0}");
        let (q, p) = pendulum.state(0.0).unwrap();
        assert!(
            close(q, theta0, 1e-15) && close(p, thetadot0, 1e-15),
            "{q}, {p}"
        );
    }
}

#[test]
fn satisfies_the_equation_of_motion_and_conserves_energy() {
    let h = 1e-4;
    for (theta0, thetadot0, omega) in [(1.0, 0.4, 1.3), (2.9, 0.0, 0.7), (0.5, 3.1, 1.4)] {
        let pendulum = Pendulum::new(theta0, thetadot0, omega).unwrap();
        let energy = pendulum.energy();
        for t in [-3.0, 0.7, 4.2, 25.0] {
            let at = |s: f64| pendulum.state(s).unwrap();
            let (q, p) = at(t);
            let (qp, pp) = at(t + h);
            let (qm, pm) = at(t - h);
            assert!(close((qp - qm) / (2.0 * h), p, 1e-7), "dθ/dt at t={t}");
            assert!(close((pp - pm) / (2.0 * h), -omega * omega * q.sin(), 1e-7));
            let e = 0.5 * p * p - omega * omega * q.cos();
            assert!(close(e, energy, 1e-14), "energy at t={t}: {e} vs {energy}");
        }
    }
}

#[test]
fn periods() {
    let omega = 1.7;
    // Small amplitude: T → 2π/ω (1 + θ²/16).
    let small = period(1e-4, omega).unwrap();
    assert!(close(small, TAU / omega * (1.0 + 1e-8 / 16.0), 1e-15));
    // Libration returns to its start after one period.
    let pendulum = Pendulum::new(2.0, 0.9, omega).unwrap();
    let big = pendulum.period();
    for t in [0.0, 1.3] {
        let (a, b) = (pendulum.state(t).unwrap(), pendulum.state(t + big).unwrap());
        assert!(close(a.0, b.0, 1e-14) && close(a.1, b.1, 1e-14));
    }
    // Started at the bottom with speed 2kω: the amplitude is 2 arcsin k, reached at T/4.
    let swing = Pendulum::new(0.0, 1.5, omega).unwrap();
    let amplitude = 2.0 * (1.5 / (2.0 * omega)).asin();
    assert!(close(
        period(amplitude, omega).unwrap(),
        swing.period(),
        1e-14
    ));
    let (theta_max, at_rest) = swing.state(0.25 * swing.period()).unwrap();
    assert!(close(theta_max, amplitude, 1e-14) && at_rest.abs() < 1e-14);
    // Rotation advances by 2π per period.
    let rotor = Pendulum::new(0.4, -3.9, omega).unwrap();
    let t = rotor.period();
    let ((q0, p0), (q1, p1)) = (rotor.state(0.3).unwrap(), rotor.state(0.3 + t).unwrap());
    assert!(close(q1, q0 - TAU, 1e-14) && close(p1, p0, 1e-14));
    assert_eq!(
        Pendulum::new(0.0, 2.0, 1.0).unwrap().period(),
        f64::INFINITY
    );
}

#[test]
fn near_the_separatrix() {
    // k'² = 1e-12 from both sides: the motions agree with the separatrix for a while.
    let w = (1.0_f64 - 1e-12).sqrt();
    let below = Pendulum::new(0.0, 2.0 * w, 1.0).unwrap();
    let above = Pendulum::new(0.0, 2.0 / w, 1.0).unwrap();
    let on = Pendulum::new(0.0, 2.0, 1.0).unwrap();
    assert_eq!(below.motion(), PendulumMotion::Libration);
    assert_eq!(above.motion(), PendulumMotion::Rotation);
    for t in [0.5, 2.0, 5.0] {
        let (a, b, c) = (below.state(t), above.state(t), on.state(t));
        let (a, b, c) = (a.unwrap(), b.unwrap(), c.unwrap());
        // θ = 2 gd(t) on the separatrix.
        assert!(close(c.0, 2.0 * t.sinh().atan(), 1e-15));
        assert!(
            close(a.0, c.0, 1e-9) && close(b.0, c.0, 1e-9),
            "{a:?} {b:?} {c:?}"
        );
    }
}

#[test]
fn invalid_input_is_an_error() {
    assert!(Pendulum::new(f64::NAN, 0.0, 1.0).is_err());
    assert!(Pendulum::new(0.0, 0.0, 0.0).is_err());
    assert!(Pendulum::new(0.0, 0.0, -1.0).is_err());
    assert!(
        Pendulum::new(1.0, 0.0, 1.0)
            .unwrap()
            .state(f64::INFINITY)
            .is_err()
    );
    assert!(period(std::f64::consts::PI, 1.0).is_err());
    assert!(period(1.0, 0.0).is_err());
}
