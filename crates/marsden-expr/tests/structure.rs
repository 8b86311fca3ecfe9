//! Structure read off a Lagrangian expression ([`Program::separable`]): which Lagrangians are
//! `½ vᵀMv − V(t, q)` with a constant `M` (and which must not be taken for one), the symbolic
//! `∇V` and `∇²V` against automatic differentiation, and the register machine ([`Tape`])
//! against the accumulator interpreter.

use crate::common::assert_close;
use marsden_expr::{Program, SeparableForm, Symbols};
use nalgebra::SVector;
use num_dual::{Dual2SVec64, hessian};

/// Symbols `[q…, q_dot…, t]` for `coordinates`, with parameters.
fn symbols(coordinates: &[&str], params: &[(&str, f64)]) -> Symbols {
    let inputs: Vec<String> = coordinates
        .iter()
        .map(|c| c.to_string())
        .chain(coordinates.iter().map(|c| format!("{c}_dot")))
        .chain(["t".to_owned()])
        .collect();
    let mut s = Symbols::with_inputs(&inputs).unwrap();
    for &(name, value) in params {
        s.add_constant(name, value).unwrap();
    }
    s
}

fn compile(text: &str, coordinates: &[&str], params: &[(&str, f64)]) -> Program {
    Program::compile(text, &symbols(coordinates, params)).unwrap_or_else(|e| panic!("{e}"))
}

fn form(text: &str, coordinates: &[&str], params: &[(&str, f64)]) -> Option<SeparableForm> {
    compile(text, coordinates, params).separable(coordinates.len())
}

const XY: &[&str] = &["x", "y"];

#[test]
fn separable_with_diagonal_mass() {
    let kepler = form(
        "0.5*(x_dot^2 + y_dot^2) + mu/sqrt(x^2 + y^2)",
        XY,
        &[("mu", 2.0)],
    );
    assert_eq!(kepler.unwrap().diagonal_mass(), Some(vec![1.0, 1.0]));
    let pendulum = "0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)";
    let params = [("m", 2.0), ("l", 3.0), ("g", 9.81)];
    let f = form(pendulum, &["theta"], &params).unwrap();
    assert_eq!(f.diagonal_mass(), Some(vec![18.0]));
    let henon = "0.5*(x_dot^2 + y_dot^2) - 0.5*(x^2 + y^2) - x^2*y + y^3/3";
    let f = form(henon, XY, &[]).unwrap();
    assert_eq!(f.diagonal_mass(), Some(vec![1.0, 1.0]));
    assert_eq!(f.bandwidth(), 1);
    // Masses written as a product, a quotient and a difference of squares.
    let f = form(
        "x_dot*x_dot*m/2 - (y_dot/2)^2*(-4) - k*x^2",
        XY,
        &[("m", 3.0), ("k", 1.0)],
    );
    assert_eq!(f.unwrap().diagonal_mass(), Some(vec![3.0, 2.0]));
}

#[test]
fn separable_with_time_dependent_potential() {
    let f = form("0.5*x_dot^2 - 0.5*x^2*(1 + 0.1*cos(t))", &["x"], &[]).unwrap();
    assert_eq!(f.diagonal_mass(), Some(vec![1.0]));
    // The potential reads t, in the slot after q.
    let (mut v, mut regs) = ([0.0], Vec::new());
    f.potential().eval_into(&[2.0, 0.0], &mut regs, &mut v);
    assert_close(v[0], 2.0 * 1.1, 1e-15, "V(0, 2)");
    f.potential()
        .eval_into(&[2.0, std::f64::consts::PI], &mut regs, &mut v);
    assert_close(v[0], 2.0 * 0.9, 1e-15, "V(pi, 2)");
}

#[test]
fn separable_with_dense_mass() {
    // A cart and pendulum linearised: M = [[2, 1], [1, 2]].
    let f = form("x_dot^2 + x_dot*y_dot + y_dot^2 - x^2 - y^2", XY, &[]).unwrap();
    assert_eq!(f.diagonal_mass(), None);
    assert_eq!(f.mass(), [2.0, 1.0, 1.0, 2.0]);
    // (x_dot + y_dot)^2 / 2 + y_dot^2: M = [[1, 1], [1, 3]].
    let f = form("(x_dot + y_dot)^2/2 + y_dot^2 - cos(x - y)", XY, &[]).unwrap();
    assert_eq!(f.mass(), [1.0, 1.0, 1.0, 3.0]);
}

#[test]
fn separable_chain_has_a_banded_hessian() {
    // Five masses, nearest-neighbour springs with a quartic term, fixed ends.
    let q: Vec<String> = (1..=5).map(|i| format!("q{i}")).collect();
    let names: Vec<&str> = q.iter().map(String::as_str).collect();
    let kinetic: Vec<String> = q.iter().map(|c| format!("0.5*{c}_dot^2")).collect();
    let mut springs = vec!["0.5*q1^2".to_owned(), "0.5*q5^2".to_owned()];
    for i in 0..4 {
        let (a, b) = (&q[i], &q[i + 1]);
        springs.push(format!("0.5*({b} - {a})^2 + 0.25*({b} - {a})^4"));
    }
    let text = format!("{} - ({})", kinetic.join(" + "), springs.join(" + "));
    let f = form(&text, &names, &[]).unwrap();
    assert_eq!(f.diagonal_mass(), Some(vec![1.0; 5]));
    assert_eq!(f.bandwidth(), 1);
    assert_eq!(f.hessian_entries().len(), 5 + 4);
    check_derivatives_against_ad(&f, [0.1, -0.3, 0.7, 0.2, -0.5], 0.0);
}

#[test]
fn not_separable_mass_depends_on_position() {
    // The double pendulum: M(q) has cos(θ₁ − θ₂).
    let dp = "0.5*(m1 + m2)*l1^2*a_dot^2 + 0.5*m2*l2^2*b_dot^2 \
              + m2*l1*l2*a_dot*b_dot*cos(a - b) + (m1 + m2)*g*l1*cos(a) + m2*g*l2*cos(b)";
    let params = [
        ("m1", 1.0),
        ("m2", 1.0),
        ("l1", 1.0),
        ("l2", 1.0),
        ("g", 9.81),
    ];
    assert!(form(dp, &["a", "b"], &params).is_none());
    // Polar coordinates: ½(ṙ² + r² θ̇²).
    assert!(form("0.5*(r_dot^2 + r^2*th_dot^2) + 1/r", &["r", "th"], &[]).is_none());
}

#[test]
fn not_separable_position_velocity_cross_term() {
    assert!(form("0.5*x_dot^2 + x*x_dot - x^2", &["x"], &[]).is_none());
    assert!(form("0.5*(x_dot + x)^2", &["x"], &[]).is_none());
    // A constant term linear in the velocity (a total derivative, but not of the form).
    assert!(form("0.5*x_dot^2 + 3*x_dot", &["x"], &[]).is_none());
}

#[test]
fn not_separable_magnetic_term() {
    let text = "0.5*(x_dot^2 + y_dot^2) + 0.5*B*(x*y_dot - y*x_dot) - 0.5*(x^2 + y^2)";
    assert!(form(text, XY, &[("B", 1.0)]).is_none());
}

#[test]
fn not_separable_mass_depends_on_time() {
    assert!(form("0.5*exp(0.1*t)*x_dot^2 - 0.5*x^2", &["x"], &[]).is_none());
    assert!(form("0.5*x_dot^2/(1 + t) - 0.5*x^2", &["x"], &[]).is_none());
}

#[test]
fn not_separable_other_velocity_dependence() {
    // Relativistic particle, quartic kinetic energy, a velocity inside a function.
    assert!(form("-sqrt(1 - x_dot^2) - 0.5*x^2", &["x"], &[]).is_none());
    assert!(form("0.25*x_dot^4 - x^2", &["x"], &[]).is_none());
    assert!(form("0.5*x_dot^2*cos(x_dot) - x^2", &["x"], &[]).is_none());
    assert!(form("(x_dot^2)^1.5 - x^2", &["x"], &[]).is_none());
    // Indefinite or singular mass.
    assert!(form("0.5*x_dot^2 - 0.5*y_dot^2 - x^2 - y^2", XY, &[]).is_none());
    assert!(form("0.5*x_dot^2 - x^2 - y^2", XY, &[]).is_none());
    assert!(form("0.5*(x_dot + y_dot)^2 - x^2 - y^2", XY, &[]).is_none());
}

/// `V = −L(t, q, 0)`, its gradient and Hessian by num-dual (through the potential's tape at
/// second-order duals), against the symbolic tapes.
fn check_derivatives_against_ad<const N: usize>(f: &SeparableForm, q: [f64; N], t: f64) {
    let inputs: Vec<f64> = q.iter().copied().chain([t]).collect();
    let (mut regs, mut grad) = (Vec::new(), vec![0.0; N]);
    f.gradient()
        .unwrap()
        .eval_into(&inputs, &mut regs, &mut grad);
    let mut value = [0.0];
    f.potential().eval_into(&inputs, &mut regs, &mut value);
    let tape = f.potential();
    let (v_ad, g_ad, h_ad) = hessian(
        |x: SVector<Dual2SVec64<N>, N>| {
            let mut x: Vec<Dual2SVec64<N>> = x.iter().copied().collect();
            x.push(Dual2SVec64::from(t));
            let mut out = [Dual2SVec64::from(0.0)];
            tape.eval_into(&x, &mut Vec::new(), &mut out);
            out[0]
        },
        &SVector::from(q),
    );
    assert_close(value[0], v_ad, 1e-14, "V");
    for i in 0..N {
        assert_close(grad[i], g_ad[i], 1e-13, &format!("dV/dq{i}"));
    }
    let mut hess = vec![0.0; f.hessian_entries().len()];
    f.hessian()
        .unwrap()
        .eval_into(&inputs, &mut regs, &mut hess);
    for i in 0..N {
        for j in 0..N {
            let entry = f
                .hessian_entries()
                .iter()
                .position(|&e| e == (i.min(j), i.max(j)));
            let symbolic = entry.map_or(0.0, |k| hess[k]);
            assert_close(symbolic, h_ad[(i, j)], 1e-12, &format!("H[{i},{j}]"));
        }
    }
}

/// `V` itself against `−L(t, q, 0)` through the accumulator interpreter.
fn check_potential_against_lagrangian(p: &Program, f: &SeparableForm, q: &[f64], t: f64) {
    let n = q.len();
    let lx: Vec<f64> = q.iter().copied().chain(vec![0.0; n]).chain([t]).collect();
    let mut v = [0.0];
    let inputs: Vec<f64> = q.iter().copied().chain([t]).collect();
    f.potential().eval_into(&inputs, &mut Vec::new(), &mut v);
    assert_close(v[0], -p.eval(&lx), 1e-14, "V = -L(t, q, 0)");
}

#[test]
fn symbolic_derivatives_equal_automatic_differentiation() {
    let cases: [(&str, &[&str], &[f64]); 7] = [
        (
            "0.5*(x_dot^2 + y_dot^2) + mu/sqrt(x^2 + y^2)",
            XY,
            &[0.8, -0.6],
        ),
        (
            "0.5*x_dot^2 + tan(x) - exp(0.3*x)*log(2 + x)",
            &["x"],
            &[0.4],
        ),
        (
            "0.5*(x_dot^2 + y_dot^2) - x^2.5*y^1.5 + atan2(y, x)",
            XY,
            &[1.3, 0.7],
        ),
        (
            "0.5*(x_dot^2 + y_dot^2) - sin(x*y)*cosh(y) + asin(0.5*x)",
            XY,
            &[0.6, -0.2],
        ),
        (
            "0.5*(x_dot^2 + y_dot^2) - x^y - tanh(x)/y + atan(x - y)",
            XY,
            &[1.4, 0.9],
        ),
        (
            "0.5*(x_dot^2 + y_dot^2) - (x^2 + y^2)^(-1.5) + acos(0.3*y)",
            XY,
            &[0.9, 1.1],
        ),
        ("0.5*x_dot^2 - k*x^2*cos(w*t) - sinh(x)", &["x"], &[0.3]),
    ];
    let params = [("mu", 1.5), ("k", 2.0), ("w", 3.0)];
    for (text, coordinates, q) in cases {
        let p = compile(text, coordinates, &params);
        let f = p
            .separable(coordinates.len())
            .unwrap_or_else(|| panic!("{text}"));
        for t in [0.0, 0.7] {
            match *q {
                [a] => check_derivatives_against_ad(&f, [a], t),
                [a, b] => check_derivatives_against_ad(&f, [a, b], t),
                _ => unreachable!(),
            }
            check_potential_against_lagrangian(&p, &f, q, t);
        }
    }
}

#[test]
fn abs_leaves_the_derivatives_to_automatic_differentiation() {
    let f = form("0.5*x_dot^2 - abs(x)", &["x"], &[]).unwrap();
    assert!(f.gradient().is_none() && f.hessian().is_none());
    assert_eq!(f.diagonal_mass(), Some(vec![1.0]));
}

#[test]
fn common_subexpressions_are_evaluated_once() {
    let f = form(
        "0.5*(x_dot^2 + y_dot^2) + mu/sqrt(x^2 + y^2)",
        XY,
        &[("mu", 1.0)],
    )
    .unwrap();
    // x², y², their sum, the root and its powers are shared by both components.
    let gradient = f.gradient().unwrap();
    assert_eq!(gradient.len(), 2);
    assert!(gradient.op_count() <= 12, "{}", gradient.op_count());
}

#[test]
fn register_machine_equals_the_interpreter() {
    let texts = [
        "sin(x)*cos(y) + tan(x*y) - exp(-x^2) + log(1 + y^2) + sqrt(x^2 + y^2)",
        "x^2.5 + y^-1.5 + x^y + pow(y, 0.3) + 2^x + a*x^3 - b/y",
        "atan2(y, x) + abs(x - y)*sinh(y) + tanh(x) + cosh(y)",
        "(x*y + a)^2/(x*y + a) - (x*y + a)*(x*y + a) + acos(0.2*x) + asin(0.1*y) + atan(x)",
    ];
    let mut s = Symbols::with_inputs(["x", "y"]).unwrap();
    s.add_constant("a", 0.7)
        .unwrap()
        .add_constant("b", -1.3)
        .unwrap();
    for text in texts {
        let p = Program::compile(text, &s).unwrap();
        let tape = p.tape();
        for x in [[0.3, 1.7], [1.1, 0.4], [2.5, 3.0]] {
            let mut out = [0.0];
            tape.eval_into(&x, &mut Vec::new(), &mut out);
            assert_close(out[0], p.eval(&x), 1e-14, text);
        }
    }
}
