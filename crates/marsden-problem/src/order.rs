//! Order studies of a problem file (`marsden order`): which methods, which step sizes, which
//! final time — validated into a [`Plan`] before anything runs.
//!
//! A method of order `p` has global error `e(h) ≈ C hᵖ` at a fixed final time `T` until
//! round-off takes over (HLW06 §II.1; reference cases R5 and R6 in
//! the `marsden` crate documentation). The study runs the file's problem with each method at each
//! `h` to `T` with `N = (T − t₀)/h` steps, measures `e(h) = |(q_N, p_N) − (q(T), p(T))|`
//! against one reference solution shared by all methods ([`marsden::studies::order::reference_solution`])
//! and fits the log–log slope ([`marsden::studies::order::empirical_order`]).
//!
//! [`plan`] checks the command-line lists (methods, step sizes, `T`) against the file. The runs
//! are the engine's (`marsden_engine::order_runner`, generic over the Lagrangian and
//! the rule); the table they fill is `marsden_spec::order::table`.

use marsden::Constraint as _;

use crate::error::Diagnostic;
use crate::problem::method::METHOD_NAMES;
use crate::problem::{Method, RunSpec};

/// Relative tolerance for `(T − t₀)/h` to count as a whole number of steps.
pub const WHOLE_STEPS_TOLERANCE: f64 = 1e-9;

/// The default step sizes are the file's `h` times these factors.
pub const DEFAULT_REFINEMENTS: [f64; 4] = [1.0, 0.5, 0.25, 0.125];

/// What the command line asked for (`None`: the file's value).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Request {
    /// `--methods m1,m2,…`.
    pub methods: Option<String>,
    /// `--h h1,h2,…`.
    pub h: Option<String>,
    /// `--t-end T`.
    pub t_end: Option<f64>,
}

/// A validated order study.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    /// The methods, in the order given.
    pub methods: Vec<Method>,
    /// The runs: `(h, steps)`, largest `h` first, no duplicates.
    pub grids: Vec<(f64, usize)>,
    /// Initial time `t₀`.
    pub t0: f64,
    /// Final time `T`.
    pub t_end: f64,
}

impl Plan {
    /// The numbers of steps, increasing (as [`marsden::studies::order::measure_order`] takes them).
    pub fn steps(&self) -> Vec<usize> {
        self.grids.iter().map(|&(_, n)| n).collect()
    }
}

/// Checks the request against the problem file.
///
/// # Errors
/// An unknown method (with the list of names), an empty list, a step size that is not
/// positive or does not divide `T − t₀`, a final time not after `t₀`.
pub fn plan(spec: &RunSpec, request: &Request) -> Result<Plan, Diagnostic> {
    let methods = match &request.methods {
        None => vec![spec.integrator.method.clone()],
        Some(list) => methods(list)?,
    };
    if methods.contains(&Method::Exact) {
        return Err(Diagnostic::new(
            "`exact` has no order to measure: it is the exact flow (by shooting), the reference",
        )
        .help("study a rule, e.g. `--methods midpoint,gauss-2`"));
    }
    if spec.system.constraint.count() > 0 {
        let written = match &request.methods {
            Some(list) => split_top_level(list).into_iter().map(str::trim).collect(),
            None => Vec::new(),
        };
        refuse_unconstrained_only(&methods, &written)?;
    }
    let grid = spec.integrator.grid;
    let t0 = grid.t0;
    let t_end = match request.t_end {
        Some(t) => t,
        None => spec
            .integrator
            .t_end
            .unwrap_or(t0 + grid.h * grid.steps as f64),
    };
    if !(t_end.is_finite() && t_end > t0) {
        return Err(Diagnostic::new(format!(
            "--t-end must be a finite time after t0 = {t0}, got {t_end}"
        )));
    }
    let hs = match &request.h {
        None => DEFAULT_REFINEMENTS.iter().map(|f| grid.h * f).collect(),
        Some(list) => step_sizes(list)?,
    };
    let grids = grids(&hs, t0, t_end)?;
    Ok(Plan {
        methods,
        grids,
        t0,
        t_end,
    })
}

/// The message `marsden run` gives for a method that cannot impose constraints (Gauss rules:
/// no stage at the step's end), for the first such method of a study of a constrained file —
/// before any run, instead of a failure at every step size. `written` holds the names as given
/// in `--methods` (empty for the file's method), so that the message names them.
fn refuse_unconstrained_only(methods: &[Method], written: &[&str]) -> Result<(), Diagnostic> {
    let refusal = methods.iter().enumerate().find_map(|(k, m)| {
        let name = written.get(k).map_or(m.to_string(), |w| (*w).to_owned());
        m.constraint_refusal_as_written(&name)
    });
    match refusal {
        Some(refusal) => Err(Diagnostic::new(refusal.headline).note(refusal.note).help(
            "study constrained rules, e.g. `--methods midpoint,lobatto-3,triple-jump-4(trapezoid)`",
        )),
        None => Ok(()),
    }
}

/// Splits a comma-separated list; an empty list or an empty entry is an error.
fn items<'a>(list: &'a str, flag: &str, what: &str) -> Result<Vec<&'a str>, Diagnostic> {
    let items: Vec<&str> = split_top_level(list).into_iter().map(str::trim).collect();
    if items.iter().all(|s| s.is_empty()) {
        return Err(Diagnostic::new(format!("{flag} is empty"))
            .help(format!("give at least one {what}, comma-separated")));
    }
    if let Some(k) = items.iter().position(|s| s.is_empty()) {
        return Err(Diagnostic::new(format!(
            "{flag} has an empty entry (item {} of `{list}`)",
            k + 1
        )));
    }
    Ok(items)
}

/// Splits at the commas outside parentheses (method names such as `kahan-li-6(trapezoid)`).
fn split_top_level(list: &str) -> Vec<&str> {
    let mut parts = Vec::new();
    let (mut depth, mut start) = (0i32, 0);
    for (i, c) in list.char_indices() {
        match c {
            '(' => depth += 1,
            ')' => depth -= 1,
            ',' if depth == 0 => {
                parts.push(&list[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    parts.push(&list[start..]);
    parts
}

/// `--methods`: every name parsed, the first unknown one reported as the `run` command does.
fn methods(list: &str) -> Result<Vec<Method>, Diagnostic> {
    items(list, "--methods", "method name")?
        .into_iter()
        .map(|name| {
            Method::parse(name).map_err(|e| {
                Diagnostic::new(format!("--methods: {}", e.message))
                    .suggest(e.suggestion.as_deref())
                    .note(format!("methods: {METHOD_NAMES}"))
            })
        })
        .collect()
}

/// `--h`: positive, finite numbers.
fn step_sizes(list: &str) -> Result<Vec<f64>, Diagnostic> {
    items(list, "--h", "step size")?
        .into_iter()
        .map(|text| {
            let h: f64 = text
                .parse()
                .map_err(|_| Diagnostic::new(format!("--h: `{text}` is not a number")))?;
            if h.is_finite() && h > 0.0 {
                Ok(h)
            } else {
                Err(Diagnostic::new(format!(
                    "--h: every step size must be positive and finite, got {text}"
                )))
            }
        })
        .collect()
}

/// The runs `(h, N)` with `N = (T − t₀)/h` a whole number (within
/// [`WHOLE_STEPS_TOLERANCE`], relative), sorted by decreasing `h`, duplicates removed.
fn grids(hs: &[f64], t0: f64, t_end: f64) -> Result<Vec<(f64, usize)>, Diagnostic> {
    let span = t_end - t0;
    let mut grids = Vec::with_capacity(hs.len());
    for &h in hs {
        let ratio = span / h;
        let steps = ratio.round();
        if steps < 1.0 || (ratio - steps).abs() > WHOLE_STEPS_TOLERANCE * ratio {
            return Err(Diagnostic::new(format!(
                "h = {h} does not divide the time span T − t0 = {span} into whole steps \
                 ((T − t0)/h = {ratio})"
            ))
            .help("choose step sizes that divide T − t0, or set the final time with --t-end"));
        }
        // `steps` is a whole number ≥ 1 here; the cast is exact below 2⁵³.
        grids.push((h, steps as usize));
    }
    grids.sort_by_key(|&(_, n)| n);
    grids.dedup_by_key(|g| g.1);
    Ok(grids)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_split_outside_parentheses() {
        assert_eq!(
            split_top_level("midpoint, kahan-li-6(trapezoid),gauss-2"),
            ["midpoint", " kahan-li-6(trapezoid)", "gauss-2"]
        );
    }

    #[test]
    fn grids_sort_and_reject_non_divisors() {
        let g = grids(&[0.25, 0.5, 0.25], 0.0, 5.0).unwrap();
        assert_eq!(g, [(0.5, 10), (0.25, 20)]);
        let e = grids(&[0.3], 0.0, 5.0).unwrap_err();
        assert!(e.message.contains("h = 0.3"), "{}", e.message);
        assert!(
            grids(&[0.1], 0.0, 1.0).is_ok(),
            "1/0.1 is 10 within round-off"
        );
    }

    #[test]
    fn empty_lists_and_bad_numbers_are_refused() {
        assert!(step_sizes("").unwrap_err().message.contains("empty"));
        assert!(
            step_sizes("0.1,,0.2")
                .unwrap_err()
                .message
                .contains("item 2")
        );
        assert!(step_sizes("-0.1").unwrap_err().message.contains("positive"));
        assert!(
            step_sizes("abc")
                .unwrap_err()
                .message
                .contains("not a number")
        );
        assert!(methods(" ").unwrap_err().message.contains("empty"));
    }
}
