//! The results of an order study as an aligned text table (stdout) and as a CSV file.
//!
//! One row per method: the expected order `p`, the error `e(h)` at each step size (`failed`
//! if the run failed), the pairwise slopes `log(e₁/e₂)/log(h₁/h₂)`, how many leading points
//! the fit kept (the rest are round-off), and the fitted least-squares slope — last, so that
//! scripts can take the last field of a row.

use std::fmt::Write as _;

use marsden::studies::order::OrderStudy;

use super::Plan;
use super::runner::Results;

/// The text table, with a headline giving `T`, `t₀` and the reference.
pub fn render(plan: &Plan, results: &Results) -> String {
    let mut rows = vec![header(plan)];
    rows.extend(results.studies.iter().map(row));
    let mut out = format!(
        "order study: T = {}, t0 = {}, {} step sizes; error |(q_N, p_N) − (q(T), p(T))| \
         against {}\n",
        plan.t_end,
        plan.t0,
        plan.grids.len(),
        results.reference_source
    );
    out.push_str(&align(&rows));
    out
}

fn header(plan: &Plan) -> Vec<String> {
    let mut cells = vec!["method".to_owned(), "order".to_owned()];
    cells.extend(plan.grids.iter().map(|(h, _)| format!("e(h={h})")));
    cells.extend(["slopes", "kept", "fitted"].map(str::to_owned));
    cells
}

fn row(study: &OrderStudy) -> Vec<String> {
    let mut cells = vec![study.method.clone(), study.expected.to_string()];
    cells.extend(study.points.iter().map(|pt| error_cell(pt.error)));
    let slopes: Vec<String> = study.pairwise.iter().map(|s| number(*s, 2)).collect();
    cells.push(slopes.join(" "));
    cells.push(format!("{}/{}", study.kept, study.points.len()));
    cells.push(study.order.map_or("-".to_owned(), |p| format!("{p:.3}")));
    cells
}

fn error_cell(error: f64) -> String {
    if error.is_nan() {
        "failed".to_owned()
    } else {
        format!("{error:.3e}")
    }
}

fn number(x: f64, digits: usize) -> String {
    if x.is_finite() {
        format!("{x:.digits$}")
    } else {
        "-".to_owned()
    }
}

/// Columns padded to their widest cell: the first left-aligned, the others right-aligned,
/// two spaces apart.
fn align(rows: &[Vec<String>]) -> String {
    let columns = rows.iter().map(Vec::len).max().unwrap_or(0);
    let widths: Vec<usize> = (0..columns)
        .map(|c| {
            rows.iter()
                .filter_map(|r| r.get(c))
                .map(|s| s.chars().count())
                .max()
                .unwrap_or(0)
        })
        .collect();
    let mut out = String::new();
    for row in rows {
        let mut line = String::new();
        for (c, (cell, width)) in row.iter().zip(&widths).enumerate() {
            match c {
                0 => {
                    let _ = write!(line, "{cell:<width$}");
                }
                _ => {
                    let _ = write!(line, "  {cell:>width$}");
                }
            }
        }
        out.push_str(line.trim_end());
        out.push('\n');
    }
    out
}

/// The CSV file: one line per run, `method,expected_order,h,steps,error,fitted_order`
/// (`error` empty for a failed run, `fitted_order` empty if no fit).
pub fn csv(plan: &Plan, results: &Results) -> String {
    let mut out = String::from("method,expected_order,h,steps,error,fitted_order\n");
    for study in &results.studies {
        let fitted = study.order.map_or(String::new(), |p| p.to_string());
        for (pt, (h, _)) in study.points.iter().zip(&plan.grids) {
            let error = if pt.error.is_nan() {
                String::new()
            } else {
                pt.error.to_string()
            };
            let _ = writeln!(
                out,
                "\"{}\",{},{h},{},{error},{fitted}",
                study.method, study.expected, pt.steps
            );
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_align_and_the_fit_is_last() {
        let rows = vec![
            vec!["method".to_owned(), "fitted".to_owned()],
            vec!["gauss-2".to_owned(), "4.000".to_owned()],
        ];
        assert_eq!(align(&rows), "method   fitted\ngauss-2   4.000\n");
        assert_eq!(error_cell(f64::NAN), "failed");
        assert_eq!(error_cell(4.914e-2), "4.914e-2");
        assert_eq!(number(f64::NAN, 2), "-");
    }
}
