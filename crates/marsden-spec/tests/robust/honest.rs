//! Runs that would finish but report something untrue are refused at load time (a
//! diagnostic, exit 2) or reported as failed.

use marsden_spec::{Controls, RunSpec, RunStatus, Store, execute};

/// A free particle, `L = ½ẋ²`, with the integrator lines `integrator` and initial lines
/// `initial`.
fn free(initial: &str, integrator: &str) -> String {
    format!(
        "[system]\ncoordinates = [\"x\"]\nlagrangian = \"0.5*x_dot^2\"\n\
         [initial]\n{initial}\n[integrator]\n{integrator}\n[output]\nplots = false\n"
    )
}

fn refused(text: &str) -> String {
    match RunSpec::from_toml_str(text, "p.toml") {
        Ok(spec) => match marsden_spec::prepare(&spec) {
            Ok(_) => panic!("accepted:\n{text}"),
            Err(d) => d.to_string(),
        },
        Err(d) => d.to_string(),
    }
}

#[test]
fn time_overflow_is_refused() {
    let shown = refused(&free("q = [0]\nv = [1]", "h = 1e308\nsteps = 2"));
    assert!(shown.contains("is not a finite number"), "{shown}");
    assert!(shown.contains("p.toml:"), "{shown}");
}

#[test]
fn step_count_beyond_the_limit_is_refused_not_saturated() {
    let shown = refused(&free("q = [0]\nv = [1]", "h = 0.05\nt_end = 1e300"));
    assert!(shown.contains("more than the limit"), "{shown}");
    assert!(!shown.contains("18446744073709551615"), "{shown}");
    let shown = refused(&free(
        "q = [0]\nv = [1]",
        "h = 0.05\nsteps = 9000000000000000000",
    ));
    assert!(shown.contains("more than the limit"), "{shown}");
}

#[test]
fn step_below_the_resolution_of_t_is_refused() {
    let shown = refused(&free("t0 = 1e17\nq = [0]\nv = [1]", "h = 0.05\nsteps = 10"));
    assert!(shown.contains("below the resolution of t"), "{shown}");
}

#[test]
fn t_end_less_than_one_step_is_refused() {
    let shown = refused(&free("q = [0]\nv = [1]", "h = 0.05\nt_end = 1e-12"));
    assert!(shown.contains("less than one step"), "{shown}");
}

#[test]
fn t_end_not_a_multiple_of_h_ends_with_a_shorter_step_there() {
    let spec = RunSpec::from_toml_str(&free("q = [0]\nv = [1]", "h = 0.05\nt_end = 0.07"), "p");
    let grid = spec.unwrap().integrator.grid;
    assert_eq!(grid.steps, 2);
    assert_eq!(grid.time(2), 0.07, "the run stops where it was asked to");
    assert!((grid.last_step().unwrap() - 0.02).abs() < 1e-15);
    let ok = RunSpec::from_toml_str(&free("q = [0]\nv = [1]", "h = 0.1\nt_end = 10"), "p.toml");
    let grid = ok.unwrap().integrator.grid;
    assert_eq!(
        (grid.steps, grid.end),
        (100, None),
        "10/0.1 is a whole number"
    );
}

#[test]
fn non_finite_lagrangian_at_the_start_is_refused() {
    let text = free("q = [1.5]\nv = [0]", "h = 0.05\nsteps = 4")
        .replace("0.5*x_dot^2", "0.5*x_dot^2 + log(-x)");
    let shown = refused(&text);
    assert!(shown.contains("at the initial state is NaN"), "{shown}");
}

#[test]
fn coincident_bodies_without_softening_are_refused() {
    let text = "[system]\nbuiltin = \"nbody\"\nparameters = { masses = [1.0, 1.0] }\n\
                [initial]\nq = [0, 0, 0, 0, 0, 0]\nv = [0, 0, 0, 0, 0, 0]\n[integrator]\nh = 0.01\nsteps = 3\n";
    let shown = refused(text);
    assert!(shown.contains("at the initial state is"), "{shown}");
}

#[test]
fn energy_turning_non_finite_mid_run_fails_the_run() {
    // L = ½ẋ² + log(2 − t): the motion is free (the term has no x-derivative), the energy
    // −log(2 − t) is infinite at t = 2 and NaN after.
    let text = free("q = [0]\nv = [1]", "h = 1\nsteps = 4")
        .replace("0.5*x_dot^2", "0.5*x_dot^2 + log(2 - t)");
    let spec = RunSpec::from_toml_str(&text, "p.toml").unwrap();
    let outcome = execute(&spec, Store::Memory, &Controls::none()).unwrap();
    let s = &outcome.summary;
    assert_eq!(s.status, RunStatus::Failed, "{:?}", s.error);
    assert!(s.energy.non_finite > 0);
    assert_eq!(
        s.energy.samples + s.energy.non_finite,
        usize::try_from(s.output.rows).unwrap()
    );
}
