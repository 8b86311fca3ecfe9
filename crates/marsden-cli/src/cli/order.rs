//! `marsden order FILE [--methods m1,m2,…] [--h h1,h2,…] [--t-end T] [--csv PATH]`: the
//! empirical order of convergence of one or more methods on the problem of a file.
//!
//! Each method (default: the file's `[integrator] method`) runs the file's problem — its
//! Lagrangian, forces and initial data, as `marsden run` builds them — from `t₀` to `T`
//! (default: the file's `t_end = t₀ + h·steps`) at each step size `h` (default: the file's `h`
//! times 1, ½, ¼, ⅛) with `N = (T − t₀)/h` steps; `(T − t₀)/h` must be a whole number to a
//! relative 1e-9. The error `e(h) = |(q_N, p_N) − (q(T), p(T))|` is measured against one
//! reference solution shared by all methods (the extrapolation integrator converged to
//! round-off, [`marsden::studies::order::reference_solution`]); the table on stdout gives per method its
//! expected order, `e(h)` per step size, the pairwise slopes, and the least-squares slope of
//! `log e` against `log h` over the points before round-off ([`marsden::studies::order::empirical_order`];
//! HLW06 §II.1, reference cases R5 and R6). No files are written unless `--csv PATH` is given.
//!
//! ```text
//! $ marsden order examples/pendulum.toml --methods midpoint,gauss-2 --h 0.5,0.25,0.125,0.0625 --t-end 5
//! ```
//!
//! Exit statuses: 0 every run completed; 1 some run failed (its cell reads `failed`, the table
//! is still printed) or the reference could not be computed; 2 bad input (unknown method, empty
//! list, a step size that is not positive or does not divide `T − t₀`, a constrained problem).

use marsden_spec::order::{self, Request, table};
use marsden_spec::{Diagnostic, Overrides};

use super::OrderArgs;
use crate::error::{CliError, Status};

/// Runs the study and prints the table.
pub fn order(args: &OrderArgs) -> Result<Status, CliError> {
    let spec = marsden_spec::load(&args.file, &Overrides::default())?;
    let request = Request {
        methods: args.methods.clone(),
        h: args.h.clone(),
        t_end: args.t_end,
    };
    let plan = order::plan(&spec, &request)?;
    let results = order::measure(&spec, &plan)?;
    print!("{}", table::render(&plan, &results));
    if let Some(path) = &args.csv {
        std::fs::write(path, table::csv(&plan, &results)).map_err(|e| {
            CliError::failed(Diagnostic::new(format!(
                "cannot write {}: {e}",
                path.display()
            )))
        })?;
    }
    let failed = results
        .studies
        .iter()
        .flat_map(|s| &s.points)
        .filter(|pt| pt.error.is_nan())
        .count();
    if failed == 0 {
        return Ok(Status::Completed);
    }
    eprintln!(
        "error: {failed} of the runs failed (shown as `failed`)\n  = help: a Newton failure \
         usually means h is too large for the method, or [integrator] max_iterations too small"
    );
    Ok(Status::Failed)
}
