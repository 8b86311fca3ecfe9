//! The N-body catalog system from a file (`systems::nbody::file`): the benchmark data loads
//! into `(system, q₀, p₀)`, and malformed files give typed errors that name the line.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use marsden::error::InputError;
use std::path::PathBuf;

use marsden::systems::NBody;
use marsden::systems::nbody::{NBodyFileError, file};
use marsden::{Error, Integrator, Rule, State, Trapezoid};

fn plummer(n: usize) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join(format!("tests/data/plummer_N{n}_seed20241121.txt"))
}

#[test]
fn the_benchmark_file_loads_into_a_system_and_its_state() {
    let path = plummer(64);
    let (system, q0, p0) = file::load(&path, 1.0, 0.01).unwrap();
    assert_eq!((system.bodies(), q0.len(), p0.len()), (64, 192, 192));
    assert_eq!((system.g, system.softening), (1.0, 0.01));
    // Plummer data: equal masses 1/N, total mass 1, centre-of-mass frame.
    assert!(system.masses.iter().all(|m| *m == 1.0 / 64.0));
    let total = NBody::linear_momentum(&p0);
    assert!(total.iter().all(|c| c.abs() < 1e-12), "{total:?}");
    // The file's first body, `m x y z vx vy vz`, with p = m v.
    assert_eq!(q0[0], -1.5696437631624733);
    assert_eq!(p0[2], 0.015625 * 0.10914160840327063);
    // The loaded system steps: Störmer–Verlet keeps the energy to the softened problem's
    // expected size over 100 steps of h = 1e-3 (verlet.c: max |ΔE/E₀| 6.6e-7 for N = 1024).
    let e0 = system.energy(&q0, &p0);
    let mut integrator = Integrator::new(Trapezoid.discretize(system.clone()));
    let mut state = State {
        t: 0.0,
        q: q0,
        p: p0,
    };
    for _ in 0..100 {
        integrator.step(&mut state, 1e-3).unwrap();
    }
    let drift = ((system.energy(&state.q, &state.p) - e0) / e0).abs();
    assert!(drift < 1e-5, "relative energy error {drift:e}");
    assert_eq!(integrator.statistics().explicit_steps, 100);
}

#[test]
fn a_malformed_line_is_reported_with_its_number() {
    let text = "3\n1 0 0 0 0 0 0\n# a comment\n1 0 0 0 0 0\n1 0 0 0 0 0 0\n";
    let err = file::parse(text).unwrap_err();
    assert_eq!(
        err,
        NBodyFileError::FieldCount {
            line: 4,
            found: 6,
            text: "1 0 0 0 0 0".into()
        }
    );
    assert!(
        err.to_string().starts_with("line 4: expected 7 numbers"),
        "{err}"
    );
}

#[test]
fn a_non_numeric_field_is_reported_with_line_and_field() {
    let err = file::parse("2\n1 0 0 0 0 0 0\n1 0.5 abc 0 0 0 0\n").unwrap_err();
    assert_eq!(
        err,
        NBodyFileError::BadNumber {
            line: 3,
            field: 3,
            name: "y",
            found: "abc".into()
        }
    );
    let err = file::parse("1\n1 0 0 0 NaN 0 0\n").unwrap_err();
    assert!(
        matches!(
            err,
            NBodyFileError::BadNumber {
                line: 2,
                field: 5,
                name: "vx",
                ..
            }
        ),
        "{err:?}"
    );
    let err = file::parse("N=2\n").unwrap_err();
    assert_eq!(
        err,
        NBodyFileError::BadCount {
            line: 1,
            found: "N=2".into()
        }
    );
}

#[test]
fn a_wrong_body_count_is_reported() {
    let err = file::parse("3\n1 0 0 0 0 0 0\n1 1 0 0 0 0 0\n").unwrap_err();
    assert_eq!(
        err,
        NBodyFileError::MissingBodies {
            expected: 3,
            found: 2
        }
    );
    let err = file::parse("1\n1 0 0 0 0 0 0\n\n1 1 0 0 0 0 0\n").unwrap_err();
    assert_eq!(
        err,
        NBodyFileError::ExtraBodies {
            line: 4,
            expected: 1
        }
    );
    assert!(matches!(
        file::parse("0\n").unwrap_err(),
        NBodyFileError::BadCount { line: 1, .. }
    ));
}

#[test]
fn a_missing_file_and_bad_parameters_are_typed_errors() {
    let err = file::load("/nonexistent/bodies.txt", 1.0, 0.0).unwrap_err();
    assert!(matches!(err, NBodyFileError::Io { .. }), "{err:?}");
    let data = file::parse("1\n1 0 0 0 0 0 0\n").unwrap();
    let err = data.clone().into_system(1.0, -0.1).unwrap_err();
    assert!(
        matches!(
            err,
            NBodyFileError::InvalidParameter {
                name: "softening",
                ..
            }
        ),
        "{err:?}"
    );
    let err = data.into_system(f64::NAN, 0.0).unwrap_err();
    assert!(matches!(
        err,
        NBodyFileError::InvalidParameter { name: "G", .. }
    ));
    assert!(matches!(
        NBody::with_parameters(vec![], 1.0, 0.0),
        Err(Error::Input(InputError::InvalidOption {
            name: "masses",
            ..
        }))
    ));
    let ok = NBody::with_parameters(vec![2.0, 3.0], 0.5, 0.1).unwrap();
    assert_eq!(
        ok,
        NBody {
            masses: vec![2.0, 3.0],
            g: 0.5,
            softening: 0.1
        }
    );
}
