//! Parser semantics: precedence, associativity, literals, functions, constants.

use marsden_expr::{Expr, Program, Symbols};

/// Evaluate `text` with `x` bound to input 0.
fn at(text: &str, x: f64) -> f64 {
    let symbols = Symbols::with_inputs(["x"]).unwrap();
    let program = Program::compile(text, &symbols).unwrap_or_else(|e| panic!("{e}"));
    program.eval(&[x])
}

/// Evaluate a closed expression.
fn value(text: &str) -> f64 {
    at(text, f64::NAN)
}

#[test]
fn power_is_right_associative() {
    assert_eq!(value("2^3^2"), 512.0);
    assert_eq!(value("(2^3)^2"), 64.0);
    assert_eq!(at("x^2^3", 2.0), 256.0);
}

#[test]
fn unary_minus_binds_looser_than_power() {
    assert_eq!(value("-2^2"), -4.0);
    assert_eq!(value("(-2)^2"), 4.0);
    assert_eq!(at("-x^2", 3.0), -9.0);
    assert_eq!(at("-x^2", -3.0), -9.0);
    assert_eq!(value("2^-1"), 0.5);
    assert_eq!(at("2^-x^2", 2.0), 1.0 / 16.0);
    assert_eq!(value("--3"), 3.0);
    assert_eq!(value("+3 - -2"), 5.0);
}

#[test]
fn multiplication_before_addition() {
    assert_eq!(value("2*3+4"), 10.0);
    assert_eq!(value("4+2*3"), 10.0);
    assert_eq!(value("(1+2)*3"), 9.0);
    assert_eq!(value("2*-3"), -6.0);
    assert_eq!(at("1 + 2*x^2", 3.0), 19.0);
}

#[test]
fn subtraction_and_division_are_left_associative() {
    assert_eq!(value("10-4-3"), 3.0);
    assert_eq!(value("64/4/2"), 8.0);
    assert_eq!(at("x/2/4", 16.0), 2.0);
    assert_eq!(at("1 - x - 1", 5.0), -5.0);
    assert_eq!(at("12/x/2", 3.0), 2.0);
}

#[test]
fn number_literals() {
    assert_eq!(value("1"), 1.0);
    assert_eq!(value("2.5"), 2.5);
    assert_eq!(value("1e-3"), 1e-3);
    assert_eq!(value(".5"), 0.5);
    assert_eq!(value("6.02E23"), 6.02e23);
    assert_eq!(value("1e+2"), 100.0);
    assert_eq!(value("3."), 3.0);
}

#[test]
fn one_argument_functions() {
    let x: f64 = 0.37;
    let cases: [(&str, f64); 13] = [
        ("sin(x)", x.sin()),
        ("cos(x)", x.cos()),
        ("tan(x)", x.tan()),
        ("asin(x)", x.asin()),
        ("acos(x)", x.acos()),
        ("atan(x)", x.atan()),
        ("sinh(x)", x.sinh()),
        ("cosh(x)", x.cosh()),
        ("tanh(x)", x.tanh()),
        ("exp(x)", x.exp()),
        ("log(x)", x.ln()),
        ("sqrt(x)", x.sqrt()),
        ("abs(-x)", x),
    ];
    for (text, expected) in cases {
        assert_eq!(at(text, x), expected, "{text}");
    }
}

#[test]
fn two_argument_functions() {
    assert_eq!(at("atan2(x, -1)", 1.0), 1.0_f64.atan2(-1.0));
    assert_eq!(at("atan2(-1, x)", -2.0), (-1.0_f64).atan2(-2.0));
    assert_eq!(at("pow(x, 3)", -2.0), -8.0);
    assert_eq!(at("pow(2, x)", 10.0), 1024.0_f64.ln().exp());
    assert_eq!(at("pow(x, x)", 2.5), 2.5_f64.powf(2.5));
    assert_eq!(at("x^1.5", 4.0), 8.0);
    assert_eq!(at("x^0.5", 9.0), 3.0);
}

#[test]
fn pi_and_whitespace() {
    assert_eq!(value("pi"), std::f64::consts::PI);
    assert_eq!(value("  cos( pi )\n * 2 "), -2.0);
    assert_eq!(at("sin(pi/2 + x)", 0.0), 1.0);
}

#[test]
fn integer_powers_of_negative_numbers_are_exact() {
    assert_eq!(at("x^3", -2.0), -8.0);
    assert_eq!(at("x^-2", -2.0), 0.25);
}

#[test]
fn names_lists_the_values_used() {
    let e = Expr::parse("0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta) + pi").unwrap();
    assert_eq!(e.names(), ["g", "l", "m", "theta", "theta_dot"]);
    let ids = e.identifiers();
    assert_eq!(ids.len(), 7);
    assert_eq!(
        (ids[0].name, ids[0].span.start, ids[0].span.end),
        ("m", 4, 5)
    );
}

#[test]
fn unicode_names() {
    let symbols = Symbols::with_inputs(["θ", "θ_dot"]).unwrap();
    let program = Program::compile("θ_dot^2 - cos(θ)", &symbols).unwrap();
    assert_eq!(program.eval(&[0.0, 2.0]), 3.0);
}
