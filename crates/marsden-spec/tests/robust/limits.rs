//! Sizes that would allocate (sweep members, bodies, file sizes, expression length and
//! depth) are checked against limits before anything is allocated; messages quote a short
//! window of a long line.

use std::path::Path;
use std::time::Instant;

use marsden_spec::{Overrides, RunSpec, from_toml_str, load};

const FREE: &str = "[system]\ncoordinates = [\"x\"]\nlagrangian = \"0.5*x_dot^2\"\n\
                    [initial]\nq = [0]\nv = [1]\n[integrator]\nh = 0.1\nsteps = 2\n";

#[test]
fn sweep_member_count_beyond_the_limit_is_refused_before_allocating() {
    let text = format!(
        "{FREE}[sweep]\ninitial = \"q[0]\"\n\
         range = {{ start = 0, stop = 1, count = 1000000000000000000 }}\n"
    );
    let shown = RunSpec::from_toml_str(&text, "p.toml")
        .unwrap_err()
        .to_string();
    assert!(shown.contains("more than the limit"), "{shown}");
    assert!(shown.contains("p.toml:12:"), "{shown}");
}

fn nbody_problem(dir: &Path, bodies: &str) -> std::path::PathBuf {
    std::fs::write(dir.join("bodies.txt"), bodies).unwrap();
    let problem = dir.join("p.toml");
    std::fs::write(
        &problem,
        "[system]\nbuiltin = \"nbody\"\n[initial]\nfile = \"bodies.txt\"\n\
         [integrator]\nh = 0.01\nsteps = 2\n",
    )
    .unwrap();
    problem
}

#[test]
fn nbody_count_beyond_the_limit_or_the_lines_is_refused_before_allocating() {
    let dir = tempfile::tempdir().unwrap();
    let body = "1 0 0 0 0 0 0\n";
    let problem = nbody_problem(dir.path(), &format!("1000000000000\n{body}"));
    let shown = load(&problem, &Overrides::default())
        .unwrap_err()
        .to_string();
    assert!(shown.contains("more than the limit"), "{shown}");
    let problem = nbody_problem(dir.path(), &format!("5000\n{body}"));
    let shown = load(&problem, &Overrides::default())
        .unwrap_err()
        .to_string();
    assert!(
        shown.contains("says 5000 bodies, but 1 line follow"),
        "{shown}"
    );
}

#[test]
fn problem_file_that_is_not_a_regular_file_is_refused_without_reading() {
    let shown = load(Path::new("/dev/zero"), &Overrides::default())
        .unwrap_err()
        .to_string();
    assert!(shown.contains("not a regular file"), "{shown}");
    let text = FREE.replace("q = [0]\nv = [1]", "file = \"/dev/zero\"");
    let shown = from_toml_str(&text, "p.toml", &Overrides::default())
        .unwrap_err()
        .to_string();
    assert!(shown.contains("not a regular file"), "{shown}");
}

#[test]
fn problem_file_of_100_megabytes_is_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("huge.toml");
    let file = std::fs::File::create(&path).unwrap();
    file.set_len(100_000_000).unwrap();
    let clock = Instant::now();
    let shown = load(&path, &Overrides::default()).unwrap_err().to_string();
    assert!(clock.elapsed().as_secs_f64() < 1.0);
    assert!(shown.contains("more than the limit"), "{shown}");
    assert!(shown.len() < 400, "{shown}");
}

#[test]
fn non_utf8_problem_file_gets_the_byte_offset() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("latin1.toml");
    std::fs::write(&path, b"[system]\nname = \"caf\xe9\"\n").unwrap();
    let shown = load(&path, &Overrides::default()).unwrap_err().to_string();
    assert!(shown.contains("offset 20"), "{shown}");
}

#[test]
fn long_line_in_a_diagnostic_shows_a_short_window() {
    let numbers = vec!["1.0"; 200_000].join(", ");
    let text = FREE.replace("q = [0]", &format!("q = [{numbers}]"));
    let shown = RunSpec::from_toml_str(&text, "p.toml")
        .unwrap_err()
        .to_string();
    assert!(shown.contains("has 200000 values"), "{shown}");
    assert!(
        shown.len() < 600,
        "{} bytes:\n{}",
        shown.len(),
        &shown[..600]
    );
}

#[test]
fn flat_sum_of_hundreds_of_terms_runs() {
    let terms = (0..300)
        .map(|k| format!("{}e-3*x^2", k % 7))
        .collect::<Vec<_>>()
        .join(" - ");
    let text = FREE.replace("0.5*x_dot^2", &format!("0.5*x_dot^2 - {terms}"));
    let spec = RunSpec::from_toml_str(&text, "p.toml").unwrap();
    let outcome = marsden_spec::execute(
        &spec,
        marsden_spec::Store::Memory,
        &marsden_spec::Controls::none(),
    )
    .unwrap();
    assert_eq!(outcome.summary.status, marsden_spec::RunStatus::Completed);
}
