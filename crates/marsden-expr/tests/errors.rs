//! Every error class: the message text and where the caret points.

use marsden_expr::{ErrorKind, EvalError, Expr, ExprError, Program, ProgramSet, Span, Symbols};

fn pendulum() -> Symbols {
    let mut s = Symbols::with_inputs(["theta", "theta_dot"]).unwrap();
    s.add_constant("m", 1.0)
        .unwrap()
        .add_constant("l", 1.0)
        .unwrap();
    s.add_constant("g", 9.81).unwrap();
    s
}

fn error(text: &str) -> ExprError {
    match Program::compile(text, &pendulum()) {
        Ok(p) => panic!("`{text}` compiled to\n{p}"),
        Err(e) => e,
    }
}

/// The column of the first caret in the rendered report, relative to the expression text.
fn caret_column(err: &ExprError) -> usize {
    let rendered = err.to_string();
    let caret_line = rendered.lines().nth(2).unwrap();
    caret_line.find('^').unwrap() - 2
}

/// Assert the first line of the report, the caret column and the caret count.
fn check(text: &str, message: &str, column: usize, width: usize) -> ExprError {
    let err = error(text);
    let rendered = err.to_string();
    let lines: Vec<&str> = rendered.lines().collect();
    assert_eq!(lines[0], format!("error: {message}"), "{rendered}");
    assert_eq!(lines[1], format!("  {text}"), "{rendered}");
    assert_eq!(caret_column(&err), column, "{rendered}");
    assert_eq!(err.line_column(), (0, column));
    assert_eq!(lines[2].trim().len(), width, "caret width in\n{rendered}");
    err
}

#[test]
fn missing_operand_after_an_operator() {
    let err = check(
        "0.5*m*l^2*theta_dot^2 + * cos(theta)",
        "expected an operand after '+', found '*'",
        24,
        1,
    );
    assert_eq!(
        err.to_string(),
        "error: expected an operand after '+', found '*'\n  \
         0.5*m*l^2*theta_dot^2 + * cos(theta)\n                          ^"
    );
    check(
        "theta *",
        "expected an operand after '*', found the end of the expression",
        7,
        1,
    );
    // trailing whitespace does not push the caret away from the operator
    let err = error("theta *   ");
    assert_eq!(err.line_column(), (0, 7));
    check("2 ^ )", "expected an operand after '^', found ')'", 4, 1);
    check(
        "-",
        "expected an operand after '-', found the end of the expression",
        1,
        1,
    );
    check(
        "atan2(theta, )",
        "expected an operand after ',', found ')'",
        13,
        1,
    );
}

#[test]
fn missing_operand_at_the_start() {
    check("* theta", "expected an operand, found '*'", 0, 1);
    check(", 1", "expected an operand, found ','", 0, 1);
}

#[test]
fn double_star_suggests_caret() {
    check("theta**2", "use '^' for powers, not '**'", 5, 2);
}

#[test]
fn empty_expression() {
    check("", "empty expression", 0, 1);
    let err = check("   ", "empty expression", 0, 1);
    assert_eq!(err.kind(), &ErrorKind::Empty);
}

#[test]
fn unbalanced_parentheses() {
    check(
        "cos(theta",
        "unclosed '(': the expression ends before its ')'",
        3,
        1,
    );
    check(
        "2*((theta+1)",
        "unclosed '(': the expression ends before its ')'",
        2,
        1,
    );
    check("(theta+1))", "unmatched ')'", 9, 1);
    check("(theta 1)", "expected an operator or ')', found '1'", 7, 1);
    check("atan2(theta; 1)", "unexpected character ';'", 11, 1);
    check("atan2(theta 1)", "expected ',' or ')', found '1'", 12, 1);
}

#[test]
fn trailing_input() {
    let err = check(
        "2 theta",
        "unexpected 'theta' after the end of the expression",
        2,
        5,
    );
    assert!(
        err.to_string()
            .ends_with("= help: there is no implicit multiplication: write '*' between factors")
    );
    let err = check(
        "theta, 1",
        "unexpected ',' after the end of the expression",
        5,
        1,
    );
    assert!(!err.to_string().contains("help"));
}

#[test]
fn invalid_numbers() {
    check(
        "1e",
        "invalid number `1e`: the exponent after 'e' has no digits",
        0,
        2,
    );
    check(
        "2*1e+ + 1",
        "invalid number `1e+`: the exponent after 'e' has no digits",
        2,
        3,
    );
    check(
        "1.2.3*theta",
        "invalid number `1.2.3`: more than one decimal point",
        0,
        5,
    );
    check(
        "theta + 1e400",
        "invalid number `1e400`: too large for a 64-bit float",
        8,
        5,
    );
    check(
        "3 + .",
        "invalid number `.`: a '.' must be followed by digits",
        4,
        1,
    );
}

#[test]
fn unexpected_character() {
    check("theta # 2", "unexpected character '#'", 6, 1);
    check("θ + 1", "unknown name `θ`", 0, 1);
}

#[test]
fn unknown_name_lists_known_names_and_suggests() {
    let err = check("0.5*m*l^2*thetadot^2", "unknown name `thetadot`", 10, 8);
    let rendered = err.to_string();
    let lines: Vec<&str> = rendered.lines().collect();
    assert_eq!(lines[3], "  = help: did you mean `theta_dot`?");
    assert_eq!(
        lines[4],
        "  = note: known names: g, l, m, pi, theta, theta_dot"
    );
    match err.kind() {
        ErrorKind::UnknownName {
            name,
            known,
            suggestion,
        } => {
            assert_eq!(name, "thetadot");
            assert_eq!(known, &["g", "l", "m", "pi", "theta", "theta_dot"]);
            assert_eq!(suggestion.as_deref(), Some("theta_dot"));
        }
        other => panic!("wrong kind {other:?}"),
    }
    let err = check("omega^2", "unknown name `omega`", 0, 5);
    assert!(!err.to_string().contains("did you mean"));
    assert!(
        err.to_string()
            .contains("known names: g, l, m, pi, theta, theta_dot")
    );
}

#[test]
fn unknown_function_lists_functions() {
    let err = check("m*g*l*cso(theta)", "unknown function `cso`", 6, 3);
    let rendered = err.to_string();
    assert!(
        rendered.contains("= help: did you mean `cos`?"),
        "{rendered}"
    );
    assert!(rendered.ends_with(
        "= note: functions: abs, acos, asin, atan, atan2, cos, cosh, exp, log, pow, sin, \
         sinh, sqrt, tan, tanh"
    ));
    let err = check("ln(theta)", "unknown function `ln`", 0, 2);
    assert!(err.to_string().contains("= help: did you mean `log`?"));
    let err = check("foo(theta)", "unknown function `foo`", 0, 3);
    assert!(!err.to_string().contains("did you mean"));
}

#[test]
fn wrong_number_of_arguments() {
    check(
        "atan2(theta)",
        "function `atan2` takes 2 arguments, found 1",
        0,
        5,
    );
    check(
        "1 + sin(theta, 2)",
        "function `sin` takes 1 argument, found 2",
        4,
        3,
    );
    check("cos()", "function `cos` takes 1 argument, found 0", 0, 3);
    check(
        "pow(theta, 2, 3)",
        "function `pow` takes 2 arguments, found 3",
        0,
        3,
    );
}

#[test]
fn names_and_functions_used_in_the_wrong_role() {
    check("theta(2)", "`theta` is not a function", 0, 5);
    check("2*pi(1)", "`pi` is not a function", 2, 2);
    check(
        "sin + 1",
        "function `sin` must be called with arguments, as in `sin(x)`",
        0,
        3,
    );
}

#[test]
fn non_finite_constants() {
    check(
        "theta + 1/(m - l)",
        "this constant subexpression evaluates to inf, which is not a finite number",
        8,
        9,
    );
    check(
        "theta*sqrt(-g)",
        "this constant subexpression evaluates to NaN, which is not a finite number",
        6,
        8,
    );
}

#[test]
fn nesting_limit() {
    let deep = format!("{}theta{}", "(".repeat(300), ")".repeat(300));
    assert!(matches!(
        error(&deep).kind(),
        ErrorKind::TooDeep { limit: 256 }
    ));
    let too_long_chain = vec!["theta"; 3000].join("+");
    assert!(matches!(
        error(&too_long_chain).kind(),
        ErrorKind::TooTall { limit: 2048 }
    ));
    let minus = format!("{}theta", "-".repeat(300));
    assert!(matches!(error(&minus).kind(), ErrorKind::TooDeep { .. }));
}

/// A flat sum counts its terms as one level of nesting each only toward the height limit:
/// generated Lagrangians with hundreds of terms parse, evaluate and differentiate.
#[test]
fn flat_sum_of_many_terms_is_not_too_deep() {
    let sum = vec!["theta*theta_dot"; 1500].join(" + ");
    let p = Program::compile(&sum, &pendulum()).unwrap();
    assert_eq!(p.eval(&[2.0, 0.5]), 1500.0);
}

#[test]
fn over_long_expression_is_refused_before_parsing_with_a_short_snippet() {
    let long = "theta + ".repeat(10_000) + "theta";
    let err = error(&long);
    assert!(matches!(err.kind(), ErrorKind::TooLong { .. }), "{err}");
    assert!(err.to_string().len() < 400, "{err}");
}

#[test]
fn caret_in_a_long_line_shows_a_window() {
    let long = "theta + ".repeat(500) + "* theta";
    let err = error(&long);
    let shown = err.to_string();
    assert!(shown.len() < 400, "{shown}");
    let lines: Vec<&str> = shown.lines().collect();
    let caret = lines[2].chars().position(|c| c == '^').unwrap();
    assert_eq!(lines[1].chars().nth(caret), Some('*'), "{shown}");
    assert!(lines[1].starts_with("  …"), "{shown}");
}

#[test]
fn caret_on_a_later_line_and_after_unicode() {
    let symbols = Symbols::with_inputs(["θ"]).unwrap();
    let err = Program::compile("θ^2\n + 2*θ +\n", &symbols).unwrap_err();
    assert_eq!(err.line_column(), (1, 8));
    assert_eq!(
        err.to_string(),
        "error: expected an operand after '+', found the end of the expression\n   + 2*θ +\n          ^"
    );
}

#[test]
fn context_labels_and_sets() {
    let err = ProgramSet::compile(["theta", "theta_dot +"], &pendulum()).unwrap_err();
    assert!(
        err.to_string()
            .starts_with("error in expression [1]: expected an operand")
    );
    let err = err.with_context("constraints[1]");
    assert_eq!(err.context(), Some("constraints[1]"));
    assert!(err.to_string().starts_with("error in constraints[1]: "));
}

#[test]
fn caller_errors_at_a_name() {
    let expr = Expr::parse("theta^2 + theta_dot").unwrap();
    let id = expr
        .identifiers()
        .into_iter()
        .find(|id| id.name == "theta_dot")
        .unwrap();
    assert_eq!(id.span, Span::new(10, 19));
    let err = expr.error_at(
        id.span,
        "a constraint may only use coordinates",
        Some("remove `theta_dot`".into()),
    );
    assert_eq!(
        err.to_string(),
        "error: a constraint may only use coordinates\n  theta^2 + theta_dot\n            ^^^^^^^^^\n  = help: remove `theta_dot`"
    );
}

#[test]
fn evaluation_length_errors() {
    let p = Program::compile("theta_dot", &pendulum()).unwrap();
    assert_eq!(
        p.try_eval(&[1.0]),
        Err(EvalError::TooFewInputs {
            needed: 2,
            given: 1
        })
    );
    assert_eq!(p.try_eval(&[1.0, 2.0]), Ok(2.0));
    let set = ProgramSet::compile(["theta", "m"], &pendulum()).unwrap();
    let mut out = [0.0; 3];
    assert_eq!(
        set.try_eval_into(&[1.0], &mut out),
        Err(EvalError::OutputLength {
            needed: 2,
            given: 3
        })
    );
    assert_eq!(
        EvalError::TooFewInputs {
            needed: 2,
            given: 1
        }
        .to_string(),
        "the expression needs 2 inputs, but 1 were given"
    );
}

#[test]
#[should_panic(expected = "needs 2 inputs, got 1")]
fn eval_with_too_few_inputs_panics() {
    let p = Program::compile("theta_dot", &pendulum()).unwrap();
    let _ = p.eval(&[1.0]);
}
