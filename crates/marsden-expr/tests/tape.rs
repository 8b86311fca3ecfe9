//! The register machine ([`Tape`]) with fused instructions (constant operands inside the
//! instructions, `a·b + c` and `a² + b²` as one instruction) against its plain layout (every
//! constant in a register, one instruction per operation).
//!
//! At `f64` the two are equal **bit for bit**: fusing keeps every rounding (the product of
//! `a·b + c` is rounded before the addition, no fused multiply–add) and only swaps the operands
//! of `+` and `·`, which IEEE 754 makes exact. At dual numbers a constant operand is an `f64`
//! in the fused layout and a dual with zero derivative parts in the plain one, so `ε·c` becomes
//! `ε·c + x·0`: equal as numbers (`==`, a zero may change sign) when every part is finite, which
//! is what is asserted (for a non-finite `x`, `x·0` is NaN: then only the values are compared).

use marsden_expr::{Program, SeparableForm, Symbols, Tape};
use num_dual::HyperDual64;
use proptest::prelude::*;

/// Equal bits, or both NaN (a NaN's payload is not specified by IEEE 754).
fn same_bits(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

/// Evaluates `tape` fused and plain at `x` and asserts the outputs are bit for bit equal.
fn assert_fused_equals_plain(tape: &Tape, x: &[f64], what: &str) {
    let (mut fused, mut plain) = (vec![0.0; tape.len()], vec![0.0; tape.len()]);
    tape.eval_into(x, &mut Vec::new(), &mut fused);
    tape.plain().eval_into(x, &mut Vec::new(), &mut plain);
    for (k, (a, b)) in fused.iter().zip(&plain).enumerate() {
        assert!(
            same_bits(*a, *b),
            "{what}, output {k} at {x:?}: {a:e} vs {b:e}"
        );
    }
}

/// The same at hyper-dual numbers (seeded along the first two inputs): every part equal.
fn assert_fused_equals_plain_dual(tape: &Tape, x: &[f64], what: &str) {
    let mut h: Vec<HyperDual64> = x.iter().map(|&v| HyperDual64::from(v)).collect();
    h[0].eps1 = 1.0;
    if let Some(second) = h.get_mut(1) {
        second.eps2 = 1.0;
    }
    let zero = HyperDual64::from(0.0);
    let (mut fused, mut plain) = (vec![zero; tape.len()], vec![zero; tape.len()]);
    tape.eval_into(&h, &mut Vec::new(), &mut fused);
    tape.plain().eval_into(&h, &mut Vec::new(), &mut plain);
    for (k, (a, b)) in fused.iter().zip(&plain).enumerate() {
        let parts = |d: &HyperDual64| [d.re, d.eps1, d.eps2, d.eps1eps2];
        let equal = if parts(b).iter().all(|p| p.is_finite()) {
            parts(a).iter().zip(parts(b)).all(|(p, q)| *p == q)
        } else {
            // `x·0` in the plain layout is NaN for a non-finite `x`: only the values compare.
            same_bits(a.re, b.re)
        };
        assert!(equal, "{what}, output {k} at {x:?}: {a} vs {b}");
    }
}

/// A separable Lagrangian in `coords` (inputs `[q, q_dot]`) and its symbolic form.
fn separable(text: &str, coords: &[&str], params: &[(&str, f64)]) -> SeparableForm {
    try_separable(text, coords, params).unwrap()
}

/// [`separable`], `None` if the text does not compile (a constant part folds to a non-finite
/// value) or is not separable.
fn try_separable(text: &str, coords: &[&str], params: &[(&str, f64)]) -> Option<SeparableForm> {
    let inputs = coords
        .iter()
        .map(|q| q.to_string())
        .chain(coords.iter().map(|q| format!("{q}_dot")));
    let mut symbols = Symbols::with_inputs(inputs).unwrap();
    for &(name, value) in params {
        symbols.add_constant(name, value).unwrap();
    }
    let program = Program::compile(text, &symbols).ok()?;
    program.separable(coords.len())
}

/// Kepler (reference case R10: e = 0.6, μ = 1), the pendulum, and the double pendulum's potential
/// (with a constant mass matrix, so it is separable): `V`, `∇V`, `∇²V`.
fn reference_forms() -> Vec<(&'static str, SeparableForm)> {
    let double = "0.5*(th1_dot^2 + th2_dot^2) + (m1+m2)*g*l1*cos(th1) + m2*g*l2*cos(th2) \
        - 0.3*m2*g*cos(th1 - th2)";
    let double_params = [
        ("m1", 1.0),
        ("m2", 2.5),
        ("l1", 0.8),
        ("l2", 1.1),
        ("g", 9.81),
    ];
    vec![
        (
            "kepler",
            separable(
                "0.5*(x_dot^2 + y_dot^2) + mu/sqrt(x^2 + y^2)",
                &["x", "y"],
                &[("mu", 1.0)],
            ),
        ),
        (
            "pendulum",
            separable(
                "0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)",
                &["theta"],
                &[("m", 1.3), ("l", 0.7), ("g", 9.81)],
            ),
        ),
        (
            "double pendulum potential",
            separable(double, &["th1", "th2"], &double_params),
        ),
    ]
}

fn tapes(form: &SeparableForm) -> Vec<(&'static str, &Tape)> {
    let mut all = vec![("V", form.potential())];
    all.extend(form.gradient().map(|g| ("∇V", g)));
    all.extend(form.hessian().map(|h| ("∇²V", h)));
    all
}

#[test]
fn reference_gradients_and_hessians_fused_equal_plain() {
    for (name, form) in reference_forms() {
        let all = tapes(&form);
        assert_eq!(all.len(), 3, "{name}: V, ∇V and ∇²V are symbolic");
        for (what, tape) in all {
            let what = format!("{name} {what}");
            for x in [[0.4, 0.0], [0.3, -1.2], [-2.5, 0.7], [1.0e-3, 3.0]] {
                assert_fused_equals_plain(tape, &x, &what);
                assert_fused_equals_plain_dual(tape, &x, &what);
            }
        }
    }
}

/// One expression per superinstruction: each takes fewer instructions fused, same values.
#[test]
fn every_superinstruction_fuses() {
    let symbols = Symbols::with_inputs(["x", "y"]).unwrap();
    let texts = [
        "sin(x)^2 + cos(y)^2",     // a² + b²
        "sin(x)*cos(y) + y",       // a·b + c
        "sin(x)*cos(y) - y",       // a·b − c
        "y - sin(x)*cos(y)",       // c − a·b
        "sin(x)*cos(y)*(x + y)",   // (a·b)·c
        "sin(x)*cos(y)/(x + y)",   // (a·b)/c
        "(x + y)*(sin(x)*cos(y))", // c·(a·b)
    ];
    for text in texts {
        let tape = Program::compile(text, &symbols).unwrap().tape();
        assert!(
            tape.op_count() < tape.plain().op_count(),
            "{text}: fused {} instructions, plain {}",
            tape.op_count(),
            tape.plain().op_count()
        );
        for x in [[0.3, 1.7], [-1.1, 0.4]] {
            assert_fused_equals_plain(&tape, &x, text);
            assert_fused_equals_plain_dual(&tape, &x, text);
        }
    }
}

#[test]
fn kepler_gradient_is_fused() {
    let (_, kepler) = &reference_forms()[0];
    let gradient = kepler.gradient().unwrap();
    assert!(
        gradient.op_count() < gradient.plain().op_count(),
        "fused {} instructions, plain {}",
        gradient.op_count(),
        gradient.plain().op_count()
    );
}

/// `sin cos tan exp log sqrt ^`, non-integer and variable powers, `atan2`, parameters.
#[test]
fn every_function_fused_equals_plain() {
    let mut symbols = Symbols::with_inputs(["x", "y"]).unwrap();
    symbols.add_constant("a", 0.7).unwrap();
    symbols.add_constant("b", -1.3).unwrap();
    let texts = [
        "sin(x)*cos(y) + tan(x*y) - exp(-x^2) + log(1 + y^2) + sqrt(x^2 + y^2)",
        "x^2.5 + y^-1.5 + x^y + pow(y, 0.3) + 2^x + a*x^3 - b/y + 3 - x + a/x",
        "atan2(y, x) + atan2(2, x) + atan2(y, 0.5) + abs(x - y)*sinh(y) + tanh(x) + cosh(y)",
        "(x*y + a)^2/(x*y + a) - (x*y + a)*(x*y + a) + acos(0.2*x) + asin(0.1*y) + atan(x)",
        "a*x*y + b*x^2 + x^2 + y^2 + (x^2 + y^2)^1.5 - b",
    ];
    for text in texts {
        let tape = Program::compile(text, &symbols).unwrap().tape();
        for x in [[0.3, 1.7], [1.1, 0.4], [2.5, 3.0], [-0.6, 0.2]] {
            assert_fused_equals_plain(&tape, &x, text);
            assert_fused_equals_plain_dual(&tape, &x, text);
        }
    }
}

/// Random expressions over `x`, `y` and the parameters `a`, `b`.
fn expression() -> impl Strategy<Value = String> {
    let leaf = prop_oneof![
        Just("x".to_owned()),
        Just("y".to_owned()),
        Just("a".to_owned()),
        Just("b".to_owned()),
        (-3.0..3.0_f64).prop_map(|c| format!("({c})")),
        (1..4_i32).prop_map(|n| n.to_string()),
    ];
    leaf.prop_recursive(5, 48, 2, |inner| {
        let unary = prop_oneof![
            Just("sin"),
            Just("cos"),
            Just("tan"),
            Just("exp"),
            Just("log"),
            Just("sqrt"),
            Just("atan"),
            Just("-")
        ];
        let binary = prop_oneof![Just("+"), Just("-"), Just("*"), Just("/")];
        prop_oneof![
            (unary, inner.clone()).prop_map(|(f, a)| format!("{f}({a})")),
            (inner.clone(), binary, inner.clone()).prop_map(|(a, op, b)| format!("({a} {op} {b})")),
            (inner.clone(), -3..4_i32).prop_map(|(a, n)| format!("({a})^{n}")),
            (inner.clone(), 0.1..2.5_f64).prop_map(|(a, e)| format!("({a})^{e}")),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| format!("({a})^({b})")),
            (inner.clone(), inner).prop_map(|(a, b)| format!("atan2({a}, {b})")),
        ]
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    /// Fused and plain tapes of a random expression (one output): bit for bit at `f64`.
    #[test]
    fn random_expressions_fused_equal_plain(
        text in expression(),
        x in -3.0..3.0_f64,
        y in -3.0..3.0_f64,
    ) {
        let mut symbols = Symbols::with_inputs(["x", "y"]).unwrap();
        symbols.add_constant("a", 0.7).unwrap();
        symbols.add_constant("b", -1.3).unwrap();
        // Constant parts that fold to a non-finite value are a compile error: skipped.
        let program = Program::compile(&text, &symbols);
        prop_assume!(program.is_ok());
        let tape = program.unwrap().tape();
        assert_fused_equals_plain(&tape, &[x, y], &text);
        assert_fused_equals_plain_dual(&tape, &[x, y], &text);
    }

    /// Symbolic `∇V`, `∇²V` of a random potential: fused and plain bit for bit at `f64`.
    #[test]
    fn random_potential_derivatives_fused_equal_plain(
        text in expression(),
        x in -3.0..3.0_f64,
        y in -3.0..3.0_f64,
    ) {
        let form = try_separable(
            &format!("0.5*(x_dot^2 + y_dot^2) - ({text})"),
            &["x", "y"],
            &[("a", 0.7), ("b", -1.3)],
        );
        prop_assume!(form.is_some());
        let form = form.unwrap();
        for (what, tape) in tapes(&form) {
            assert_fused_equals_plain(tape, &[x, y], &format!("{what} of {text}"));
        }
    }
}
