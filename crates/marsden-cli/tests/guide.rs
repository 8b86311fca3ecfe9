//! The guide's problem files (`docs/guide/examples/`), run by the `marsden` command: every file
//! runs, and its summary.json still gives the numbers the guide's pages quote. Those numbers
//! live in one place, `docs/guide/examples/expected.toml`, each with the independent reason it
//! is right (a closed form, a reference case R1 … R20, a published value or a theory's bound).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde_json::{Map, Value};

use crate::util::{marsden, marsden_in, repo_root};

/// The guide's examples folder.
fn examples_dir() -> PathBuf {
    repo_root().join("docs/guide/examples")
}

/// One entry of expected.toml's `[[check]]` list.
#[derive(Debug, Clone)]
struct Check {
    file: String,
    command: String,
    args: Vec<String>,
    key: String,
    expect: Expect,
    reason: String,
}

/// What a check asserts of the number (or string) at its key.
#[derive(Debug, Clone)]
enum Expect {
    /// |x − value| ≤ tol.
    Within { value: f64, tol: f64 },
    /// |x| ≤ bound.
    AtMost(f64),
    /// A string equal to this one.
    Equals(String),
}

fn text(t: &toml::Value, key: &str) -> Option<String> {
    t.get(key).and_then(toml::Value::as_str).map(str::to_owned)
}

fn float(t: &toml::Value, key: &str) -> Option<f64> {
    t.get(key)
        .and_then(|v| v.as_float().or_else(|| v.as_integer().map(|i| i as f64)))
}

impl Check {
    fn parse(t: &toml::Value) -> Self {
        let key = text(t, "key").expect("a check has a key");
        let expect = if let Some(s) = text(t, "equals") {
            Expect::Equals(s)
        } else if let Some(bound) = float(t, "max") {
            Expect::AtMost(bound)
        } else {
            let value = float(t, "value").unwrap_or_else(|| panic!("{key}: no value"));
            let tol = match (float(t, "abs"), float(t, "rel")) {
                (Some(abs), None) => abs,
                (None, Some(rel)) => rel * value.abs(),
                _ => panic!("{key}: give exactly one of abs, rel"),
            };
            Expect::Within { value, tol }
        };
        let reason = text(t, "reason").unwrap_or_default();
        assert!(!reason.is_empty(), "{key}: every expected value says why");
        Self {
            file: text(t, "file").expect("a check names its file"),
            command: text(t, "command").unwrap_or_else(|| "run".into()),
            args: t
                .get("args")
                .and_then(toml::Value::as_array)
                .map(|a| {
                    a.iter()
                        .filter_map(|x| x.as_str().map(str::to_owned))
                        .collect()
                })
                .unwrap_or_default(),
            key,
            expect,
            reason,
        }
    }

    /// The invocation this check reads: the same one is run once for all its checks.
    fn invocation(&self) -> (String, String, Vec<String>) {
        (self.file.clone(), self.command.clone(), self.args.clone())
    }

    /// Compares `found` (the value at the key) with the expectation; an error message if not.
    fn verify(&self, found: &Value) -> Result<(), String> {
        let what = format!(
            "{} {} {}: {}",
            self.command, self.file, self.key, self.reason
        );
        match &self.expect {
            Expect::Equals(s) => (found.as_str() == Some(s.as_str()))
                .then_some(())
                .ok_or_else(|| format!("{what}: found {found}, expected {s:?}")),
            Expect::AtMost(bound) => {
                let x = found.as_f64().ok_or_else(|| format!("{what}: {found}"))?;
                (x.abs() <= *bound)
                    .then_some(())
                    .ok_or_else(|| format!("{what}: |{x:e}| > {bound:e}"))
            }
            Expect::Within { value, tol } => {
                let x = found.as_f64().ok_or_else(|| format!("{what}: {found}"))?;
                ((x - value).abs() <= *tol)
                    .then_some(())
                    .ok_or_else(|| format!("{what}: found {x:e}, expected {value:e} ± {tol:e}"))
            }
        }
    }
}

/// expected.toml's `[[check]]` list.
fn checks() -> Vec<Check> {
    let path = examples_dir().join("expected.toml");
    let doc: toml::Value = toml::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    doc["check"]
        .as_array()
        .unwrap()
        .iter()
        .map(Check::parse)
        .collect()
}

/// A dotted path into a JSON value; numbers index arrays.
fn at<'v>(v: &'v Value, path: &str) -> &'v Value {
    path.split('.')
        .fold(v, |at, key| match key.parse::<usize>() {
            Ok(i) if at.is_array() => &at[i],
            _ => &at[key],
        })
}

/// `marsden order FILE ARGS --csv` as JSON: `{method: {fitted_order, error: [per h]}}`.
fn order_table(file: &Path, args: &[String]) -> Value {
    let tmp = tempfile::tempdir().unwrap();
    let csv = tmp.path().join("order.csv");
    let mut all: Vec<&str> = vec!["order", file.to_str().unwrap()];
    all.extend(args.iter().map(String::as_str));
    all.extend(["--csv", csv.to_str().unwrap()]);
    let output = marsden_in(tmp.path(), &all);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        output.status.success(),
        "order {}: {stderr}",
        file.display()
    );
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut methods = Map::new();
    // method,expected_order,h,steps,error,fitted_order
    for line in text.lines().skip(1) {
        let cells: Vec<&str> = line.split(',').collect();
        let method = cells[0].trim_matches('"');
        let entry = methods
            .entry(method)
            .or_insert_with(|| serde_json::json!({"error": []}));
        entry["error"]
            .as_array_mut()
            .unwrap()
            .push(cells[4].parse::<f64>().unwrap().into());
        entry["fitted_order"] = cells[5].parse::<f64>().unwrap().into();
    }
    Value::Object(methods)
}

/// Runs one invocation; returns what its checks read (summary.json, or the order table).
fn outcome(file: &str, command: &str, args: &[String]) -> Value {
    let path = examples_dir().join(file);
    if command == "order" {
        return order_table(&path, args);
    }
    let extra: Vec<&str> = args.iter().map(String::as_str).collect();
    let run = marsden(command, &path, &extra);
    assert_eq!(run.code, 0, "{command} {file}: {}", run.stderr);
    if file == "henon_heiles_section.toml" {
        events_lie_on_the_section(&run.out.join("events.csv"), &run.summary());
    }
    run.summary()
}

/// Every row of events.csv is an upward crossing of x = 0: x at round-off of the root finder,
/// p_x > 0, and as many rows as the summary counts.
fn events_lie_on_the_section(csv: &Path, summary: &Value) {
    let text = std::fs::read_to_string(csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let ix = header.iter().position(|h| *h == "q_x").unwrap();
    let ip = header.iter().position(|h| *h == "p_x").unwrap();
    let mut rows = 0;
    for line in lines {
        let cells: Vec<&str> = line.split(',').collect();
        let x: f64 = cells[ix].parse().unwrap();
        let p: f64 = cells[ip].parse().unwrap();
        assert!(x.abs() <= 1e-10, "an event off the section: x = {x:e}");
        assert!(p > 0.0, "a downward crossing recorded: p_x = {p}");
        rows += 1;
    }
    assert!(rows > 0);
    assert_eq!(Some(rows), summary["events"]["x_up"].as_u64());
}

/// Every number the guide quotes from a problem file (expected.toml) is what the file gives.
#[test]
fn guide_numbers_match_reference_cases_r1_to_r20() {
    let checks = checks();
    let mut by_run: BTreeMap<(String, String, Vec<String>), Vec<Check>> = BTreeMap::new();
    for check in checks {
        by_run.entry(check.invocation()).or_default().push(check);
    }
    let mut failures = Vec::new();
    for ((file, command, args), checks) in &by_run {
        let value = outcome(file, command, args);
        for check in checks {
            let found = at(&value, &check.key);
            match check.verify(found) {
                Ok(()) => println!("ok  {} {} {} = {found}", command, file, check.key),
                Err(e) => failures.push(e),
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Every problem file in the guide's folder is checked by at least one expected number, so
/// no page shows a file that CI does not run.
#[test]
fn every_guide_problem_file_is_checked() {
    let checked: Vec<String> = checks().into_iter().map(|c| c.file).collect();
    for entry in std::fs::read_dir(examples_dir()).unwrap() {
        let name = entry.unwrap().file_name().into_string().unwrap();
        if name.ends_with(".toml") && name != "expected.toml" {
            assert!(
                checked.contains(&name),
                "{name} has no check in expected.toml"
            );
        }
    }
}
