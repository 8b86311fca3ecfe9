//! [`CompiledTape`] against the tape interpreter ([`Tape::eval_into`] at `f64`): **bit for bit**
//! equal outputs (or both NaN: IEEE 754 leaves a NaN's payload unspecified), on the reference
//! potentials (Kepler of reference case R10, pendulum, double pendulum), every function of the
//! language, special inputs and random expressions.

use marsden_expr::{Program, SeparableForm, Symbols, Tape};
use marsden_jit::CompiledTape;
use proptest::prelude::*;

/// Equal bits, or both NaN.
fn same_bits(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

/// Compiles `tape` (this machine has a Cranelift back end: x86-64 or aarch64 in CI).
fn compile(tape: &Tape) -> CompiledTape {
    CompiledTape::compile(tape).unwrap()
}

/// A tape compiled twice: all inputs in one slice, and split before the last input of `x`.
struct Native {
    whole: CompiledTape,
    split: CompiledTape,
}

/// [`Native`] for inputs of length `len` (the tape may read fewer).
fn compile_both(tape: &Tape, len: usize) -> Native {
    Native {
        whole: compile(tape),
        split: CompiledTape::compile_split(tape, len - 1).unwrap(),
    }
}

/// Asserts the compiled tape and the interpreter give the same bits at `x`, through both
/// entry points (`eval`, and `eval_split` with `x = [head, last]`).
fn assert_same(native: &Native, tape: &Tape, x: &[f64], what: &str) {
    let mut expected = vec![0.0; tape.len()];
    tape.eval_into(x, &mut Vec::new(), &mut expected);
    let mut got = vec![f64::NAN; tape.len()];
    native.whole.eval(x, &mut got);
    let mut split = vec![f64::NAN; tape.len()];
    let n = x.len() - 1;
    native.split.eval_split(&x[..n], x[n], &mut split);
    for (k, ((e, g), s)) in expected.iter().zip(&got).zip(&split).enumerate() {
        assert!(
            same_bits(*e, *g) && same_bits(*e, *s),
            "{what}, output {k} at {x:?}: interpreter {e:e}, native {g:e} / {s:e}"
        );
    }
}

/// Symbols `[coords, coords_dot, t]` with the parameters as constants.
fn symbols(coords: &[&str], params: &[(&str, f64)]) -> Symbols {
    let inputs = coords
        .iter()
        .map(|q| q.to_string())
        .chain(coords.iter().map(|q| format!("{q}_dot")))
        .chain(["t".to_owned()]);
    let mut symbols = Symbols::with_inputs(inputs).unwrap();
    for &(name, value) in params {
        symbols.add_constant(name, value).unwrap();
    }
    symbols
}

/// The separable form of `text` (inputs `[q, q̇, t]`).
pub(crate) fn separable(text: &str, coords: &[&str], params: &[(&str, f64)]) -> SeparableForm {
    let program = Program::compile(text, &symbols(coords, params)).unwrap();
    program.separable(coords.len()).unwrap()
}

/// Kepler (reference case R10, μ = 1), the pendulum and a double-pendulum-like potential
/// (constant mass matrix, coupled through `cos(θ₁ − θ₂)`).
pub(crate) fn reference_forms() -> Vec<(&'static str, SeparableForm)> {
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
            "double pendulum",
            separable(double, &["th1", "th2"], &double_params),
        ),
    ]
}

#[test]
fn reference_potentials_gradient_and_hessian_match_interpreter() {
    for (name, form) in reference_forms() {
        let tapes = [
            ("V", Some(form.potential())),
            ("∇V", form.gradient()),
            ("∇²V", form.hessian()),
        ];
        for (what, tape) in tapes {
            let tape = tape.unwrap();
            let what = format!("{name} {what}");
            for x in [
                [0.4, 0.0, 0.0],
                [0.3, -1.2, 1.5],
                [-2.5, 0.7, -3.0],
                [1.0e-3, 3.0, 0.0],
                [1.0e-300, -1.0e300, 0.0],
            ] {
                // Inputs `[q, t]` (the tape may read fewer: Kepler's none of `t`).
                let x = &x[..form.dof() + 1];
                assert_same(&compile_both(tape, x.len()), tape, x, &what);
            }
        }
    }
}

/// Expressions over `x`, `y` covering every built-in function, `^` with integer, negative,
/// non-integer and symbolic exponents, `atan2`, parameters and constants (`pi`).
const EVERY_FUNCTION: [&str; 7] = [
    "sin(x)*cos(y) + tan(x*y) - exp(-x^2) + log(1 + y^2) + sqrt(x^2 + y^2)",
    "x^2.5 + y^-1.5 + x^y + pow(y, 0.3) + 2^x + a*x^3 - b/y + 3 - x + a/x + x^-3 + y^7",
    "atan2(y, x) + atan2(2, x) + atan2(y, 0.5) + abs(x - y)*sinh(y) + tanh(x) + cosh(y)",
    "(x*y + a)^2/(x*y + a) - (x*y + a)*(x*y + a) + acos(0.2*x) + asin(0.1*y) + atan(x)",
    "a*x*y + b*x^2 + x^2 + y^2 + (x^2 + y^2)^1.5 - b + pi*x",
    "log(x) + sqrt(x) + asin(x) + acos(y) + x^0.5 + (-x)^y + abs(x) + abs(-y)",
    "sin(x)*cos(y) + y - sin(x)*cos(y)*(x + y) + sin(x)*cos(y)/(x + y) - (y - sin(x)*cos(y))",
];

/// Inputs including zero of both signs, negatives (NaN from `log`, `sqrt`), infinities, NaN,
/// subnormals and huge values.
const SPECIAL: [f64; 13] = [
    0.0,
    -0.0,
    -1.5,
    0.3,
    1.0,
    2.5,
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::MIN_POSITIVE / 8.0,
    1.0e300,
    -1.0e-300,
    7.0e15,
];

fn xy_symbols() -> Symbols {
    let mut symbols = Symbols::with_inputs(["x", "y"]).unwrap();
    symbols.add_constant("a", 0.7).unwrap();
    symbols.add_constant("b", -1.3).unwrap();
    symbols
}

#[test]
fn every_function_matches_interpreter_at_special_inputs() {
    let symbols = xy_symbols();
    for text in EVERY_FUNCTION {
        let tape = Program::compile(text, &symbols).unwrap().tape();
        for tape in [&tape, tape.plain()] {
            let native = compile_both(tape, 2);
            for x in SPECIAL {
                for y in SPECIAL {
                    assert_same(&native, tape, &[x, y], text);
                }
            }
        }
    }
}

/// Each one-argument function alone (one call instruction) over a sweep of arguments.
#[test]
fn each_unary_function_matches_interpreter() {
    let symbols = xy_symbols();
    let functions = [
        "sin", "cos", "tan", "asin", "acos", "atan", "sinh", "cosh", "tanh", "exp", "log", "sqrt",
        "abs",
    ];
    for f in functions {
        let text = format!("{f}(x)");
        let tape = Program::compile(&text, &symbols).unwrap().tape();
        let native = compile_both(&tape, 2);
        for k in -400..=400 {
            let x = f64::from(k) * 0.0173;
            assert_same(&native, &tape, &[x, 0.0], &text);
        }
        for x in SPECIAL {
            assert_same(&native, &tape, &[x, 0.0], &text);
        }
    }
}

/// A potential's tape reads `[q, t]` only up to its last slot used: Kepler's `∇V` reads `x, y`
/// and not `t`, so the split form must not take `t` for `y` (and more inputs than the split
/// allows are refused).
#[test]
fn split_inputs_follow_the_slots_not_the_tape_length() {
    let (_, kepler) = &reference_forms()[0];
    let gradient = kepler.gradient().unwrap();
    assert_eq!(gradient.input_len(), 2);
    let native = CompiledTape::compile_split(gradient, 2).unwrap();
    let (mut expected, mut got) = (vec![0.0_f64; 2], [0.0; 2]);
    gradient.eval_into(&[0.6, 0.8], &mut Vec::new(), &mut expected);
    native.eval_split(&[0.6, 0.8], 123.0, &mut got);
    assert_eq!(
        got.map(f64::to_bits),
        [expected[0].to_bits(), expected[1].to_bits()]
    );
    assert!(CompiledTape::compile_split(gradient, 0).is_err());
}

#[test]
fn nan_input_gives_nan_output() {
    let (_, kepler) = &reference_forms()[0];
    let native = compile(kepler.gradient().unwrap());
    let mut grad = [0.0; 2];
    native.eval(&[f64::NAN, 1.0, 0.0], &mut grad);
    assert!(grad.iter().all(|g| g.is_nan()), "{grad:?}");
}

/// Tapes without instructions: no outputs at all, an output that is an input, a constant.
#[test]
fn tapes_without_instructions() {
    let empty = Tape::default();
    let native = compile(&empty);
    assert!(native.is_empty());
    native.eval(&[], &mut []);

    let symbols = xy_symbols();
    for text in ["y", "x", "a"] {
        let tape = Program::compile(text, &symbols).unwrap().tape();
        assert_same(&compile_both(&tape, 2), &tape, &[1.25, -0.5], text);
    }
}

/// A chain of 60 coupled pendulums: ∇V has 60 outputs, the banded ∇²V 119.
#[test]
fn many_outputs_chain() {
    let n = 60;
    let coords: Vec<String> = (0..n).map(|i| format!("q{i}")).collect();
    let kinetic: Vec<String> = coords.iter().map(|q| format!("0.5*{q}_dot^2")).collect();
    let mut potential: Vec<String> = coords.iter().map(|q| format!("cos({q})")).collect();
    potential.extend((1..n).map(|i| format!("0.5*k*(q{i} - q{})^2", i - 1)));
    let text = format!("{} + {} - t*q0", kinetic.join(" + "), potential.join(" - "));
    let names: Vec<&str> = coords.iter().map(String::as_str).collect();
    let form = separable(&text, &names, &[("k", 3.5)]);
    let gradient = form.gradient().unwrap();
    let hessian = form.hessian().unwrap();
    assert_eq!((gradient.len(), hessian.len()), (n, 2 * n - 1));
    for tape in [gradient, hessian] {
        let native = compile_both(tape, n + 1);
        let x: Vec<f64> = (0..=n).map(|i| (i as f64 * 0.37).sin()).collect();
        assert_same(&native, tape, &x, "chain");
    }
}

/// A seeded loop of random inputs over the reference potentials (no proptest shrinking
/// needed: a failure prints the inputs).
#[test]
fn reference_potentials_at_random_inputs() {
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 * 8.0 - 4.0
    };
    for (name, form) in reference_forms() {
        for tape in [form.gradient().unwrap(), form.hessian().unwrap()] {
            let native = compile_both(tape, form.dof() + 1);
            for _ in 0..2000 {
                let x: Vec<f64> = (0..=form.dof()).map(|_| next()).collect();
                assert_same(&native, tape, &x, name);
            }
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
            Just("abs"),
            Just("tanh"),
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
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// A random expression's tape, and the symbolic ∇V, ∇²V of it as a potential: compiled
    /// equals interpreted, bit for bit.
    #[test]
    fn random_expressions_match_interpreter(
        text in expression(),
        x in -3.0..3.0_f64,
        y in -3.0..3.0_f64,
    ) {
        let program = Program::compile(&text, &xy_symbols());
        // Constant parts that fold to a non-finite value are a compile error: skipped.
        prop_assume!(program.is_ok());
        let tape = program.unwrap().tape();
        assert_same(&compile_both(&tape, 2), &tape, &[x, y], &text);

        let lagrangian = format!("0.5*(x_dot^2 + y_dot^2) - ({text})");
        let potential = Program::compile(&lagrangian, &symbols(&["x", "y"], &[("a", 0.7), ("b", -1.3)]));
        if let Some(form) = potential.ok().and_then(|p| p.separable(2)) {
            for tape in [form.gradient(), form.hessian()].into_iter().flatten() {
                assert_same(&compile_both(tape, 3), tape, &[x, y, 0.25], &text);
            }
        }
    }
}

/// The Taylor data of the double pendulum's `L` ([`Program::jet`]): its tapes take the sine
/// and the cosine of `θ₁ − θ₂`, `θ₁` and `θ₂` each, which compiled code computes in one call
/// per register; the values are the interpreter's bit for bit (a swap of the two would show).
#[test]
fn sine_and_cosine_of_one_register_in_one_call_match_interpreter() {
    let text = "0.5*(m1 + m2)*l1^2*a_dot^2 + 0.5*m2*l2^2*b_dot^2 \
                + m2*l1*l2*a_dot*b_dot*cos(a - b) + (m1 + m2)*g*l1*cos(a) + m2*g*l2*cos(b)";
    let params = [
        ("m1", 1.0),
        ("m2", 1.3),
        ("l1", 1.0),
        ("l2", 0.8),
        ("g", 9.81),
    ];
    let program = Program::compile(text, &symbols(&["a", "b"], &params)).unwrap();
    let jet = program.jet(5).unwrap();
    for tape in [jet.first(), jet.second()] {
        let native = compile_both(tape, 5);
        for x in [
            [1.5, 2.0, 0.3, -0.2, 0.0],
            [-0.7, 0.25, -1.1, 2.5, 3.0],
            [3.0, -3.0, 0.0, 0.0, 0.5],
        ] {
            assert_same(&native, tape, &x, "double pendulum jet");
        }
    }
}
