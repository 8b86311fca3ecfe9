//! Column groups: how flat rows split into arrays (`t`, `q`, `p`, `energy`, `J`, …).
//!
//! CSV output is flat (one header of column names); `.npy` output is one file per group.
//! A [`Layout`] says both at once, so the CLI builds one value and streams the same rows
//! into either format.
//!
//! # Example: what the CLI does with a run
//! ```
//! # fn main() -> marsden_io::Result<()> {
//! # let tmp = tempfile::tempdir().unwrap();
//! # let out = tmp.path();
//! use marsden_io::{
//!     CsvWriter, Group, Layout, NpyDirWriter, PlotOptions, RowSink, plot_run, read_csv,
//!     read_npy_dir,
//! };
//! // Column names are the CLI's choice; this is the `trajectory.csv` convention.
//! let layout = Layout::new(vec![
//!     Group::scalar("t"),
//!     Group::vector("q", ["q_theta"]),
//!     Group::vector("p", ["p_theta"]),
//!     Group::scalar("energy"),
//!     Group::vector("J", Vec::<String>::new()), // no symmetries: the group is dropped
//! ])?;
//! let npy = false; // `format = "npy"` in the problem file
//! let mut sink: Box<dyn RowSink> = if npy {
//!     Box::new(NpyDirWriter::create(out, &layout)?)
//! } else {
//!     Box::new(CsvWriter::create(out.join("trajectory.csv"), &layout.column_names())?)
//! };
//! let stride = 10;
//! let mut row = Vec::with_capacity(layout.width());
//! for step in 0..1000 {
//!     let t = step as f64 * 0.01; // … one integrator step …
//!     if step % stride != 0 {
//!         continue;
//!     }
//!     row.clear();
//!     row.extend([t, t.cos(), -t.sin(), 0.5]);
//!     if let Err(e) = sink.write_row(&row) {
//!         sink.finish()?; // keep what was written, then report
//!         return Err(e);
//!     }
//!     // A failing integrator step would likewise `sink.finish()` and report its error.
//! }
//! sink.finish()?;
//!
//! // Plots (also what `marsden plot DIR` does): read the run back, draw every plot.
//! let table = if npy { read_npy_dir(out, &layout)? } else { read_csv(out.join("trajectory.csv"))? };
//! let reports = plot_run(&table, out, &PlotOptions::default())?;
//! assert_eq!(reports.len(), 3); // phase portrait, time series, energy error (no J, no constraints)
//! for r in &reports {
//!     for note in &r.notes {
//!         eprintln!("{}: {note}", r.path.display());
//!     }
//! }
//! # Ok(()) }
//! ```

use crate::error::{Error, Result};
use crate::table::{Column, Table, check_names};

/// The shape a group takes in `.npy` output.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GroupKind {
    /// One column, saved as a 1-D array of length `rows` (e.g. `t`, `energy`).
    Scalar,
    /// Any number of columns, saved as a 2-D array `rows × columns` (e.g. `q`, `p`, `J`),
    /// even when there is only one column, so the array's rank does not depend on the model.
    Vector,
}

/// A named group of columns: one `.npy` file, several consecutive CSV columns.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Group {
    /// Group name, used as the `.npy` file stem (`q` → `q.npy`).
    pub name: String,
    /// The group's column names as they appear in CSV (e.g. `q_x`, `q_y`).
    pub columns: Vec<String>,
    /// 1-D or 2-D in `.npy`.
    pub kind: GroupKind,
}

impl Group {
    /// A one-column group whose column has the group's name (e.g. `t`, `energy`).
    pub fn scalar(name: impl Into<String>) -> Self {
        let name = name.into();
        Self {
            columns: vec![name.clone()],
            name,
            kind: GroupKind::Scalar,
        }
    }

    /// A group of columns saved as one 2-D array (e.g. `q` with columns `q_x`, `q_y`).
    pub fn vector<S: Into<String>>(
        name: impl Into<String>,
        columns: impl IntoIterator<Item = S>,
    ) -> Self {
        Self {
            name: name.into(),
            columns: columns.into_iter().map(Into::into).collect(),
            kind: GroupKind::Vector,
        }
    }

    /// Number of columns in the group.
    pub fn width(&self) -> usize {
        self.columns.len()
    }
}

/// An ordered list of groups; the concatenation of their columns is the CSV header and the
/// layout of every row handed to a writer.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Layout {
    groups: Vec<Group>,
}

impl Layout {
    /// Builds a layout, checking that column names are valid and unique, group names are
    /// usable as file stems and unique, and scalar groups have exactly one column.
    ///
    /// Empty vector groups are dropped (a model with no symmetries has no `J` group).
    ///
    /// # Errors
    /// [`Error::InvalidName`], [`Error::DuplicateName`] or [`Error::NoColumns`].
    pub fn new(groups: Vec<Group>) -> Result<Self> {
        let groups: Vec<Group> = groups.into_iter().filter(|g| g.width() > 0).collect();
        let mut seen = std::collections::HashSet::new();
        for g in &groups {
            check_file_stem(&g.name)?;
            if !seen.insert(g.name.as_str()) {
                return Err(Error::DuplicateName {
                    name: g.name.clone(),
                });
            }
            if g.kind == GroupKind::Scalar && g.width() != 1 {
                return Err(Error::InvalidName {
                    name: g.name.clone(),
                    reason: "a scalar group must have exactly one column",
                });
            }
        }
        check_names(
            groups
                .iter()
                .flat_map(|g| g.columns.iter().map(String::as_str)),
        )?;
        Ok(Self { groups })
    }

    /// The groups, in order.
    pub fn groups(&self) -> &[Group] {
        &self.groups
    }

    /// All column names in row order: the CSV header.
    pub fn column_names(&self) -> Vec<&str> {
        self.groups
            .iter()
            .flat_map(|g| g.columns.iter().map(String::as_str))
            .collect()
    }

    /// Number of values in one row.
    pub fn width(&self) -> usize {
        self.groups.iter().map(Group::width).sum()
    }

    /// Splits a table into this layout's groups: for each group, its columns in order.
    ///
    /// # Errors
    /// [`Error::MissingColumn`] if the table lacks one of the layout's columns.
    pub(crate) fn select<'t>(&self, table: &'t Table) -> Result<Vec<Vec<&'t Column>>> {
        self.groups
            .iter()
            .map(|g| {
                g.columns
                    .iter()
                    .map(|name| {
                        table
                            .column(name)
                            .ok_or_else(|| Error::MissingColumn { name: name.clone() })
                    })
                    .collect()
            })
            .collect()
    }
}

/// Group names become file names: keep them to a portable, harmless set.
fn check_file_stem(name: &str) -> Result<()> {
    let ok = !name.is_empty()
        && !name.starts_with('.')
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.'));
    if ok {
        Ok(())
    } else {
        Err(Error::InvalidName {
            name: name.to_owned(),
            reason: "a group name must be a file stem: ASCII letters, digits, '_', '-', '.', not starting with '.'",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Layout {
        Layout::new(vec![
            Group::scalar("t"),
            Group::vector("q", ["q_x", "q_y"]),
            Group::vector("p", ["p_x", "p_y"]),
            Group::scalar("energy"),
            Group::vector("J", Vec::<String>::new()),
        ])
        .unwrap()
    }

    #[test]
    fn header_is_concatenation_and_empty_groups_drop() {
        let l = sample();
        assert_eq!(
            l.column_names(),
            ["t", "q_x", "q_y", "p_x", "p_y", "energy"]
        );
        assert_eq!(l.width(), 6);
        assert_eq!(l.groups().len(), 5 - 1);
    }

    #[test]
    fn rejects_bad_groups() {
        assert!(Layout::new(vec![Group::scalar("../t")]).is_err());
        assert!(Layout::new(vec![Group::scalar("t"), Group::scalar("t")]).is_err());
        assert!(Layout::new(vec![Group::scalar("t"), Group::vector("q", ["t"])]).is_err());
        let two = Group {
            name: "e".into(),
            columns: vec!["a".into(), "b".into()],
            kind: GroupKind::Scalar,
        };
        assert!(Layout::new(vec![two]).is_err());
        assert!(matches!(Layout::new(vec![]), Err(Error::NoColumns)));
    }
}
