//! Grammar-based fuzzing of problem files: generated files, hostile numbers and generated
//! Lagrangians, each loaded and run (at most 40 steps, into a temporary directory). Asserts
//! for every case: no panic; a refused file writes nothing; the summary's status agrees with
//! its error; every stored energy is counted as a sample or declared non-finite; a completed
//! run has finite energies throughout. The run count and the outcomes by exit class are
//! written to `fuzz-outcomes.txt` in the target's temporary directory, which CI prints.

use std::collections::BTreeMap;
use std::sync::Mutex;

use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};

use marsden_spec::{Controls, Overrides, RunStatus, Store, execute, from_toml_str};

/// Numbers a hostile user types: an ordinary value three times in four, so that most files
/// reach the integrator, else one of the values that break naive code.
fn number() -> impl Strategy<Value = String> {
    prop_oneof![
        3 => (-3.0..3.0_f64).prop_map(|x| format!("{x:?}")),
        1 => hostile(),
    ]
}

/// A step size: an ordinary one four times in five.
fn step_size() -> impl Strategy<Value = String> {
    prop_oneof![
        4 => (1e-3..0.2_f64).prop_map(|x| format!("{x:?}")),
        1 => number(),
    ]
}

/// The values that break naive code.
fn hostile() -> impl Strategy<Value = String> {
    prop_oneof![
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
        4 => (0_i64..40).prop_map(|n| format!("steps = {n}")),
        1 => Just("steps = -1".to_owned()),
        1 => Just("steps = 9223372036854775807".to_owned()),
        1 => number().prop_map(|t| format!("t_end = {t}")),
    ]
}

/// A run of the classes users met later: `exact` with long steps, a translation declared as a
/// symmetry of a generated Lagrangian, a file's own `L_d`, a sweep with options it cannot give.
fn later_classes() -> impl Strategy<Value = String> {
    let exact = (lagrangian(), number(), (0.1..6.0_f64), (1_i64..4)).prop_map(|(l, q, h, n)| {
        format!(
            "[system]\ncoordinates = [\"x\"]\nlagrangian = \"{l}\"\n\
             [initial]\nq = [{q}]\nv = [0.0]\n\
             [integrator]\nmethod = \"exact\"\nh = {h:?}\nsteps = {n}\n\
             [output]\nplots = false\n"
        )
    });
    let symmetry = (lagrangian(), number(), number()).prop_map(|(l, q, v)| {
        format!(
            "[system]\ncoordinates = [\"x\"]\nlagrangian = \"{l}\"\n\
             [[system.symmetry]]\nname = \"P\"\ngenerator = [\"1\"]\n\
             [initial]\nq = [{q}]\nv = [{v}]\n\
             [integrator]\nmethod = \"midpoint\"\nh = 0.05\nsteps = 30\n\
             [output]\nplots = false\n"
        )
    });
    let discrete = (expression(), number()).prop_map(|(e, p)| {
        let ld = (e.replace("x_dot", "Q1").replace("exp", "EXP"))
            .replace('x', "x_0")
            .replace("Q1", "x_1")
            .replace("EXP", "exp");
        format!(
            "[system]\ncoordinates = [\"x\"]\ndiscrete_lagrangian = \"{ld}\"\n\
             [initial]\nq = [0.5]\np = [{p}]\n\
             [integrator]\nh = 0.1\nsteps = 10\n\
             [output]\nplots = false\n"
        )
    });
    let sweep = prop::sample::select(vec![
        "[sensitivity]\ninitial = true\n",
        "[analysis]\ncertify = true\n",
        "[analysis]\nevery_step = true\n",
    ])
    .prop_map(|option| {
        format!(
            "[system]\nbuiltin = \"pendulum\"\n[initial]\nq = [1.0]\nv = [0.0]\n\
             [integrator]\nh = 0.05\nsteps = 20\n[output]\nplots = false\n{option}\
             [sweep]\ninitial = \"q[0]\"\nvalues = [0.5, 1.0]\n"
        )
    });
    prop_oneof![exact, symmetry, discrete, sweep]
}

fn problem() -> impl Strategy<Value = String> {
    prop_oneof![4 => first_classes(), 1 => later_classes()]
}

fn first_classes() -> impl Strategy<Value = String> {
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
        (methods, step_size(), length()),
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

/// How a generated case ended, by the exit status `marsden run` gives it.
fn outcome_class(text: &str) -> Result<&'static str, TestCaseError> {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let overrides = Overrides {
        out: Some(out.clone()),
        ..Overrides::default()
    };
    let Ok(spec) = from_toml_str(text, "fuzz.toml", &overrides) else {
        prop_assert!(!out.exists(), "a refused file wrote {}", out.display());
        return Ok("exit 2: refused while reading the file");
    };
    match execute(&spec, Store::Files, &Controls::none()) {
        Err(e) => {
            prop_assert!(
                !out.join("summary.json").exists() || e.kind == marsden_spec::ErrorKind::Failed,
                "refused, yet a summary was written: {e}\n{text}"
            );
            Ok(match e.kind {
                marsden_spec::ErrorKind::Failed => "exit 1: no summary could be written",
                _ => "exit 2: refused at the initial state",
            })
        }
        Ok(outcome) => {
            let s = &outcome.summary;
            let rows = usize::try_from(s.output.rows).unwrap();
            prop_assert_eq!(s.status == RunStatus::Failed, s.error.is_some(), "{}", text);
            // A file's own `L_d` has no energy: its rows count no energy samples.
            if s.energy_not_available.is_none() {
                prop_assert_eq!(s.energy.samples + s.energy.non_finite, rows, "{}", text);
            }
            prop_assert!(out.join("summary.json").exists());
            // A momentum map said to be a symmetry's is conserved (discrete Noether: to the
            // Newton tolerance per step); a map that drifts must not be called one.
            for (name, m) in &s.momenta {
                if m.symmetry && s.status == RunStatus::Completed {
                    let bound = 1e-8 * m.initial.abs().max(1.0) * (s.steps as f64 + 1.0);
                    prop_assert!(
                        m.max_abs_drift <= bound,
                        "{name} is called a symmetry but drifts by {}\n{text}",
                        m.max_abs_drift
                    );
                }
            }
            Ok(match s.status {
                RunStatus::Completed => {
                    prop_assert_eq!(s.energy.non_finite, 0, "{}", text);
                    prop_assert_eq!(s.steps, s.steps_requested);
                    prop_assert!(s.t_final.is_finite(), "{}", text);
                    "exit 0: completed"
                }
                RunStatus::Failed if s.steps == 0 => "exit 1: failed at the first step",
                RunStatus::Failed => "exit 1: failed part-way",
                RunStatus::Interrupted => "exit 1: interrupted",
                RunStatus::Stopped => "exit 0: stopped by an event",
            })
        }
    }
}

/// Cases run by [`generated_problem_files_fail_cleanly_or_report_the_truth`].
const CASES: u32 = 300;

#[test]
fn generated_problem_files_fail_cleanly_or_report_the_truth() {
    let counts = Mutex::new(BTreeMap::<&'static str, usize>::new());
    let config = Config {
        cases: CASES,
        failure_persistence: None,
        ..Config::default()
    };
    let mut runner = TestRunner::new(config);
    let result = runner.run(&problem(), |text| {
        let class = outcome_class(&text)?;
        *counts.lock().unwrap().entry(class).or_default() += 1;
        Ok(())
    });
    if let Err(e) = result {
        panic!("{e}");
    }
    let counts = counts.into_inner().unwrap();
    let total: usize = counts.values().sum();
    let mut report =
        format!("{total} generated problem files run (crates/marsden-spec/tests/robust/fuzz.rs)\n");
    for (class, n) in &counts {
        report.push_str(&format!("{n:>6}  {class}\n"));
    }
    let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("fuzz-outcomes.txt");
    std::fs::write(&path, report).unwrap();
    assert_eq!(total, CASES as usize);
}
