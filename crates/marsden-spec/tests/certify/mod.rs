//! Certificates and symmetries from a problem file: named symmetries, the
//! symplecticity and equivariance certificates (`[analysis] certify = true`) and the forced
//! Noether balance, each read back from `summary.json`.

mod constrained;
mod named;
mod noether;
mod symplectic;

use marsden_spec::{Controls, RunSpec, RunStatus, Store, execute};

/// Runs `text` in memory and returns `summary.json` as JSON.
pub fn summary_json(text: &str) -> serde_json::Value {
    let spec = RunSpec::from_toml_str(text, "p.toml").unwrap_or_else(|d| panic!("{d}"));
    let outcome = execute(&spec, Store::Memory, &Controls::none()).unwrap();
    assert_eq!(
        outcome.summary.status,
        RunStatus::Completed,
        "{:?}",
        outcome.summary.error
    );
    serde_json::from_str(&outcome.summary.to_json().unwrap()).unwrap()
}

/// The diagnostic of a refused problem text.
pub fn refused(text: &str) -> String {
    match RunSpec::from_toml_str(text, "p.toml") {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(d) => d.to_string(),
    }
}

/// A number of the JSON at `path` (`/`-separated).
pub fn number(json: &serde_json::Value, path: &str) -> f64 {
    json.pointer(path)
        .and_then(serde_json::Value::as_f64)
        .unwrap_or_else(|| panic!("no number at {path} in {json:#}"))
}
