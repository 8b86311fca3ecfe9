//! Helpers of the end-to-end tests: run the built `marsden` binary on fixture files into
//! temporary directories and read back what it wrote.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use marsden_io::Table;
use serde_json::Value;

/// The crate's directory.
pub fn crate_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The repository root (where `examples/` lives).
pub fn repo_root() -> PathBuf {
    crate_dir().join("../..").canonicalize().unwrap()
}

/// A fixture file.
pub fn fixture(name: &str) -> PathBuf {
    crate_dir().join("tests/fixtures").join(name)
}

/// What one invocation did.
pub struct Run {
    /// Exit code.
    pub code: i32,
    /// Standard output.
    pub stdout: String,
    /// Standard error.
    pub stderr: String,
    /// Keeps the temporary directory alive.
    pub tmp: tempfile::TempDir,
    /// The output directory given with `--out`.
    pub out: PathBuf,
}

impl Run {
    /// The parsed `summary.json`.
    pub fn summary(&self) -> Value {
        let text = std::fs::read_to_string(self.out.join("summary.json")).unwrap_or_else(|e| {
            panic!(
                "no summary.json in {}: {e}\n{}",
                self.out.display(),
                self.stderr
            )
        });
        serde_json::from_str(&text).unwrap()
    }

    /// The trajectory read back from `trajectory.csv`.
    pub fn trajectory(&self) -> Table {
        marsden_io::read_csv(self.out.join("trajectory.csv")).unwrap()
    }
}

/// Runs `marsden` with `args` in `dir`.
pub fn marsden_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_marsden"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the marsden binary runs")
}

/// `marsden <command> <file> --out <tmp>/out <extra…>`.
pub fn marsden(command: &str, file: &Path, extra: &[&str]) -> Run {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let mut args = vec![
        command,
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let output = marsden_in(tmp.path(), &args);
    Run {
        code: output.status.code().unwrap_or(-1),
        stdout: String::from_utf8(output.stdout).unwrap(),
        stderr: String::from_utf8(output.stderr).unwrap(),
        tmp,
        out,
    }
}

/// `marsden run <fixture>`, asserting exit status 0.
pub fn run_ok(name: &str, extra: &[&str]) -> Run {
    let run = marsden("run", &fixture(name), extra);
    assert_eq!(run.code, 0, "{name}: stderr:\n{}", run.stderr);
    run
}

/// A column of a table.
pub fn column<'t>(table: &'t Table, name: &str) -> &'t [f64] {
    table
        .values(name)
        .unwrap_or_else(|| panic!("no column {name}"))
}

/// `|a − b| ≤ tol · max(|a|, |b|, 1)`.
pub fn assert_close(a: f64, b: f64, tol: f64, what: &str) {
    let scale = a.abs().max(b.abs()).max(1.0);
    assert!(
        (a - b).abs() <= tol * scale,
        "{what}: {a} vs {b} (diff {:e})",
        (a - b).abs()
    );
}

/// A number of the summary.
pub fn number(v: &Value, path: &str) -> f64 {
    let mut at = v;
    for key in path.split('.') {
        at = &at[key];
    }
    at.as_f64()
        .unwrap_or_else(|| panic!("summary.{path} is not a number: {at}"))
}

/// Runs `marsden run` on `bad/<name>` and checks status 2, every expected fragment of the
/// message on stderr, and that no output directory was created.
pub fn assert_rejected(name: &str, fragments: &[&str]) -> Run {
    assert_rejected_with(name, &[], fragments)
}

/// [`assert_rejected`] with extra command-line arguments.
pub fn assert_rejected_with(name: &str, extra: &[&str], fragments: &[&str]) -> Run {
    let run = marsden("run", &fixture(&format!("bad/{name}")), extra);
    assert_eq!(run.code, 2, "{name}: exit code; stderr:\n{}", run.stderr);
    for fragment in fragments {
        assert!(
            run.stderr.contains(fragment),
            "{name}: message lacks {fragment:?}:\n{}",
            run.stderr
        );
    }
    assert!(run.stderr.starts_with("error: "), "{}", run.stderr);
    assert!(run.stdout.is_empty(), "{name}: stdout: {}", run.stdout);
    assert!(
        !run.out.exists(),
        "{name}: nothing may be written for a bad file"
    );
    run
}

/// A sweep's CSV table read back: the numeric columns (those before `status`; `error` is last
/// and may hold commas inside its quotes).
pub struct SweepTable {
    pub header: Vec<String>,
    pub rows: Vec<Vec<f64>>,
}

impl SweepTable {
    pub fn read(path: &Path) -> Self {
        let text =
            std::fs::read_to_string(path).unwrap_or_else(|e| panic!("no {}: {e}", path.display()));
        let mut lines = text.lines();
        let header: Vec<String> = lines
            .next()
            .unwrap()
            .split(',')
            .map(str::to_owned)
            .collect();
        let numeric = header.iter().position(|h| h == "status").unwrap();
        let rows = lines
            .map(|l| {
                l.split(',')
                    .take(numeric)
                    .map(|x| x.parse().unwrap())
                    .collect()
            })
            .collect();
        Self {
            header: header[..numeric].to_vec(),
            rows,
        }
    }

    pub fn column(&self, name: &str) -> Vec<f64> {
        let i = self
            .header
            .iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("no column {name} in {:?}", self.header));
        self.rows.iter().map(|r| r[i]).collect()
    }
}
