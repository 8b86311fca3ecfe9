//! Test models: each Lagrangian (or Hamiltonian) as an expression and as hand-written Rust.

use marsden::Scalar;
use marsden_expr::{Program, Symbols};

/// A model written twice: as expression text and as a generic Rust function.
pub trait Model {
    /// The expression.
    const TEXT: &'static str;
    /// Input names, in slot order.
    const INPUTS: &'static [&'static str];
    /// Parameter values.
    const PARAMS: &'static [(&'static str, f64)];
    /// Range each input is sampled from.
    const RANGE: (f64, f64);
    /// The same function written in Rust.
    fn rust<S: Scalar>(x: &[S]) -> S;
}

/// Compile `M::TEXT` with its inputs and parameters.
pub fn compile<M: Model>() -> Program {
    let mut symbols = Symbols::with_inputs(M::INPUTS).unwrap();
    for &(name, value) in M::PARAMS {
        symbols.add_constant(name, value).unwrap();
    }
    Program::compile(M::TEXT, &symbols).unwrap_or_else(|e| panic!("{e}"))
}

/// `|a - b| <= tol * max(|a|, |b|, 1)`.
pub fn assert_close(a: f64, b: f64, tol: f64, what: &str) {
    let scale = a.abs().max(b.abs()).max(1.0);
    assert!(
        (a - b).abs() <= tol * scale,
        "{what}: {a} vs {b} (diff {:e})",
        (a - b).abs()
    );
}

pub struct Pendulum;
impl Model for Pendulum {
    const TEXT: &'static str = "0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)";
    const INPUTS: &'static [&'static str] = &["theta", "theta_dot"];
    const PARAMS: &'static [(&'static str, f64)] = &[("m", 1.3), ("l", 0.7), ("g", 9.81)];
    const RANGE: (f64, f64) = (-4.0, 4.0);
    fn rust<S: Scalar>(x: &[S]) -> S {
        let (m, l, g) = (1.3, 0.7, 9.81);
        let (theta, theta_dot) = (x[0], x[1]);
        theta_dot * theta_dot * (0.5 * m * l * l) + theta.cos() * (m * g * l)
    }
}

pub struct DoublePendulum;
impl Model for DoublePendulum {
    const TEXT: &'static str = "0.5*(m1+m2)*l1^2*th1_dot^2 + 0.5*m2*l2^2*th2_dot^2 \
        + m2*l1*l2*th1_dot*th2_dot*cos(th1-th2) + (m1+m2)*g*l1*cos(th1) + m2*g*l2*cos(th2)";
    const INPUTS: &'static [&'static str] = &["th1", "th2", "th1_dot", "th2_dot"];
    const PARAMS: &'static [(&'static str, f64)] = &[
        ("m1", 1.0),
        ("m2", 2.5),
        ("l1", 0.8),
        ("l2", 1.1),
        ("g", 9.81),
    ];
    const RANGE: (f64, f64) = (-3.0, 3.0);
    fn rust<S: Scalar>(x: &[S]) -> S {
        let (m1, m2, l1, l2, g) = (1.0, 2.5, 0.8, 1.1, 9.81);
        let (th1, th2, w1, w2) = (x[0], x[1], x[2], x[3]);
        w1 * w1 * (0.5 * (m1 + m2) * l1 * l1)
            + w2 * w2 * (0.5 * m2 * l2 * l2)
            + w1 * w2 * (th1 - th2).cos() * (m2 * l1 * l2)
            + th1.cos() * ((m1 + m2) * g * l1)
            + th2.cos() * (m2 * g * l2)
    }
}

pub struct Kepler;
impl Model for Kepler {
    const TEXT: &'static str = "0.5*(x_dot^2+y_dot^2) + 1/sqrt(x^2+y^2)";
    const INPUTS: &'static [&'static str] = &["x", "y", "x_dot", "y_dot"];
    const PARAMS: &'static [(&'static str, f64)] = &[];
    const RANGE: (f64, f64) = (0.2, 2.0);
    fn rust<S: Scalar>(q: &[S]) -> S {
        let (x, y, vx, vy) = (q[0], q[1], q[2], q[3]);
        (vx * vx + vy * vy) * 0.5 + (x * x + y * y).sqrt().recip()
    }
}

pub struct PendulumHamiltonian;
impl Model for PendulumHamiltonian {
    const TEXT: &'static str = "p_theta^2/(2*m*l^2) - m*g*l*cos(theta)";
    const INPUTS: &'static [&'static str] = &["theta", "p_theta"];
    const PARAMS: &'static [(&'static str, f64)] = &[("m", 0.9), ("l", 1.7), ("g", 9.81)];
    const RANGE: (f64, f64) = (-5.0, 5.0);
    fn rust<S: Scalar>(x: &[S]) -> S {
        let (m, l, g) = (0.9, 1.7, 9.81);
        x[1] * x[1] / (2.0 * m * l * l) - x[0].cos() * (m * g * l)
    }
}

/// Every built-in function, on a domain where all of them are smooth.
pub struct AllFunctions;
impl Model for AllFunctions {
    const TEXT: &'static str = "sin(a)*cos(b) + tan(a/3) + asin(b/4) + acos(b/5) + atan(a) \
        + atan2(a, b) + sinh(a/2) - cosh(b/3) + tanh(a) + exp(-b^2) + log(1 + a^2) \
        + sqrt(2 + b) + abs(b - 2) + pow(2 + a^2, b/3) + (1 + a^2)^1.5 - 3/(1 + b^2) \
        + a^-2 + 2^b - (a*b)^3 + c*pi + (1 - sin(a)*b) - atan2(b^2, 3)";
    const INPUTS: &'static [&'static str] = &["a", "b"];
    const PARAMS: &'static [(&'static str, f64)] = &[("c", 0.25)];
    const RANGE: (f64, f64) = (0.2, 1.9);
    fn rust<S: Scalar>(x: &[S]) -> S {
        let (a, b) = (x[0], x[1]);
        let one = S::from(1.0);
        a.sin() * b.cos()
            + (a / 3.0).tan()
            + (b / 4.0).asin()
            + (b / 5.0).acos()
            + a.atan()
            + a.atan2(b)
            + (a / 2.0).sinh()
            - (b / 3.0).cosh()
            + a.tanh()
            + (-(b * b)).exp()
            + (one + a * a).ln()
            + (b + 2.0).sqrt()
            + (S::from(2.0) - b)
            + (a * a + 2.0).powd(b / 3.0)
            + (one + a * a).powf(1.5)
            - S::from(3.0) / (one + b * b)
            + a.powi(-2)
            + (b * 2.0_f64.ln()).exp()
            - (a * b).powi(3)
            + 0.25 * std::f64::consts::PI
            + (one - a.sin() * b)
            - (b * b).atan2(S::from(3.0))
    }
}
