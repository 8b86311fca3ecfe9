//! Grammar-based fuzzing of problem files: generated files, hostile numbers and generated
//! Lagrangians, each loaded and run (at most 40 steps, into a temporary directory). Asserts
//! for every case: no panic; a refused file writes nothing; the summary's status agrees with
//! its error; every stored energy is counted as a sample or declared non-finite; a completed
//! run has finite energies throughout.

use proptest::prelude::*;

use marsden_spec::{Controls, Overrides, RunStatus, Store, execute, from_toml_str};

/// Numbers a hostile user types.
fn number() -> impl Strategy<Value = String> {
    prop_oneof![
        (-3.0..3.0_f64).prop_map(|x| format!("{x:?}")),
        Just("0".to_owned()),
        Just("-0.0".to_owned()),
        Just("1e308".to_owned()),
        Just("-1e308".to_owned()),
        Just("1e-308".to_owned()),
        Just("1e17".to_owned()),
        Just("1e150".to_owned()),
        Just("inf".to_owned()),
        Just("nan".to_owned()),
    ]
}

/// An expression over `x`, `x_dot` and `t` from a small grammar.
fn expression() -> impl Strategy<Value = String> {
    let leaf = prop_oneof![
        Just("x".to_owned()),
        Just("x_dot".to_owned()),
        Just("t".to_owned()),
        (0_u32..5).prop_map(|k| k.to_string()),
        Just("1e308".to_owned()),
    ];
    leaf.prop_recursive(4, 16, 2, |inner| {
        prop_oneof![
            (
                inner.clone(),
                inner.clone(),
                prop::sample::select(vec!["+", "-", "*", "/", "^"])
            )
                .prop_map(|(a, b, op)| format!("({a}) {op} ({b})")),
            (
                inner,
                prop::sample::select(vec![
                    "sin", "cos", "exp", "log", "sqrt", "abs", "tanh", "atan"
                ])
            )
                .prop_map(|(a, f)| format!("{f}({a})")),
        ]
    })
}

/// A Lagrangian: regular (`½ẋ²` plus a generated term) most of the time, anything otherwise.
fn lagrangian() -> impl Strategy<Value = String> {
    prop_oneof![
        3 => expression().prop_map(|e| format!("0.5*x_dot^2 + 0.1*({e})")),
        1 => expression(),
    ]
}

/// The length of the run: `steps` or `t_end`.
fn length() -> impl Strategy<Value = String> {
    prop_oneof![
        (0_i64..40).prop_map(|n| format!("steps = {n}")),
        Just("steps = -1".to_owned()),
        Just("steps = 9223372036854775807".to_owned()),
        number().prop_map(|t| format!("t_end = {t}")),
    ]
}

fn problem() -> impl Strategy<Value = String> {
    let methods = prop::sample::select(vec![
        "midpoint",
        "trapezoid",
        "alpha-0",
        "gauss-2",
        "lobatto-3",
        "stormer-verlet",
        "gauss-99999999999999999999",
        "triple-jump-4(midpoint)",
    ]);
    (
        lagrangian(),
        (number(), number(), number()),
        (methods, number(), length()),
    )
        .prop_map(|(l, (t0, q, v), (method, h, length))| {
            format!(
                "[system]\ncoordinates = [\"x\"]\nlagrangian = \"{l}\"\n\
                 [initial]\nt0 = {t0}\nq = [{q}]\nv = [{v}]\n\
                 [integrator]\nmethod = \"{method}\"\nh = {h}\n{length}\n\
                 [output]\nplots = false\n"
            )
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn generated_problem_files_fail_cleanly_or_report_the_truth(text in problem()) {
        let tmp = tempfile::tempdir().unwrap();
        let out = tmp.path().join("out");
        let overrides = Overrides { out: Some(out.clone()), ..Overrides::default() };
        let Ok(spec) = from_toml_str(&text, "fuzz.toml", &overrides) else {
            prop_assert!(!out.exists(), "a refused file wrote {}", out.display());
            return Ok(());
        };
        match execute(&spec, Store::Files, &Controls::none()) {
            Err(e) => {
                prop_assert!(
                    !out.join("summary.json").exists() || e.kind == marsden_spec::ErrorKind::Failed,
                    "refused, yet a summary was written: {e}\n{text}"
                );
            }
            Ok(outcome) => {
                let s = &outcome.summary;
                let rows = usize::try_from(s.output.rows).unwrap();
                prop_assert_eq!(s.status == RunStatus::Failed, s.error.is_some(), "{}", text);
                prop_assert_eq!(s.energy.samples + s.energy.non_finite, rows, "{}", text);
                if s.status == RunStatus::Completed {
                    prop_assert_eq!(s.energy.non_finite, 0);
                    prop_assert_eq!(s.steps, s.steps_requested);
                    prop_assert!(s.t_final.is_finite(), "{}", text);
                }
                prop_assert!(out.join("summary.json").exists());
            }
        }
    }
}
