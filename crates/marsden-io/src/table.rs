//! A plain column table: the in-memory form of a trajectory, independent of the core crate.

use crate::error::{Error, Result};

/// One named column of `f64` values, e.g. `q_x` over all output steps.
#[derive(Debug, Clone, PartialEq)]
pub struct Column {
    /// The column's name, as written in a CSV header.
    pub name: String,
    /// The column's values, one per row.
    pub values: Vec<f64>,
}

impl Column {
    /// A column from a name and its values.
    pub fn new(name: impl Into<String>, values: Vec<f64>) -> Self {
        Self {
            name: name.into(),
            values,
        }
    }
}

/// Columns of equal length with unique, writable names (see [`check_column_name`]).
///
/// The invariants are checked by [`Table::new`], so every `Table` can be written as CSV.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    columns: Vec<Column>,
}

impl Table {
    /// Builds a table, checking names (valid, unique) and that all columns have one length.
    ///
    /// # Errors
    /// [`Error::NoColumns`], [`Error::InvalidName`], [`Error::DuplicateName`] or
    /// [`Error::ColumnLength`].
    pub fn new(columns: Vec<Column>) -> Result<Self> {
        check_names(columns.iter().map(|c| c.name.as_str()))?;
        if let Some(first) = columns.first() {
            for c in &columns[1..] {
                if c.values.len() != first.values.len() {
                    return Err(Error::ColumnLength {
                        first: first.name.clone(),
                        column: c.name.clone(),
                        expected: first.values.len(),
                        found: c.values.len(),
                    });
                }
            }
        }
        Ok(Self { columns })
    }

    /// The columns, in order.
    pub fn columns(&self) -> &[Column] {
        &self.columns
    }

    /// Gives the columns back.
    pub fn into_columns(self) -> Vec<Column> {
        self.columns
    }

    /// Number of rows (0 for a header-only table).
    pub fn n_rows(&self) -> usize {
        self.columns.first().map_or(0, |c| c.values.len())
    }

    /// Number of columns.
    pub fn n_columns(&self) -> usize {
        self.columns.len()
    }

    /// The column names, in order.
    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.columns.iter().map(|c| c.name.as_str())
    }

    /// The column called `name`, if any.
    pub fn column(&self, name: &str) -> Option<&Column> {
        self.columns.iter().find(|c| c.name == name)
    }

    /// The values of the column called `name`, if any.
    pub fn values(&self, name: &str) -> Option<&[f64]> {
        self.column(name).map(|c| c.values.as_slice())
    }

    /// The columns whose names start with `prefix` (e.g. `"q_"`), in order.
    pub fn columns_with_prefix<'a>(&'a self, prefix: &'a str) -> impl Iterator<Item = &'a Column> {
        self.columns
            .iter()
            .filter(move |c| c.name.starts_with(prefix))
    }

    /// Row `i` as a vector of values, one per column; `None` past the end.
    pub fn row(&self, i: usize) -> Option<Vec<f64>> {
        if i >= self.n_rows() {
            return None;
        }
        Some(self.columns.iter().map(|c| c.values[i]).collect())
    }
}

/// A [`RowSink`](crate::RowSink) that collects rows into columns: what the readers stream
/// into when the whole table is wanted.
#[derive(Debug, Clone)]
pub(crate) struct Collector {
    columns: Vec<Column>,
}

impl Collector {
    /// An empty collector for these column names.
    pub(crate) fn new(names: Vec<String>) -> Self {
        Self {
            columns: names
                .into_iter()
                .map(|n| Column::new(n, Vec::new()))
                .collect(),
        }
    }

    /// The collected table.
    ///
    /// # Errors
    /// The [`Table::new`] checks.
    pub(crate) fn into_table(self) -> Result<Table> {
        Table::new(self.columns)
    }
}

impl crate::RowSink for Collector {
    fn write_row(&mut self, row: &[f64]) -> Result<()> {
        for (c, &v) in self.columns.iter_mut().zip(row) {
            c.values.push(v);
        }
        Ok(())
    }

    fn flush(&mut self) -> Result<()> {
        Ok(())
    }

    fn finish(&mut self) -> Result<()> {
        Ok(())
    }

    fn rows_written(&self) -> u64 {
        self.columns.first().map_or(0, |c| c.values.len() as u64)
    }
}

/// Checks that `name` can be a CSV column name written without quoting and read back unchanged:
/// non-empty, no comma, double quote, carriage return or line feed, no surrounding whitespace.
///
/// # Errors
/// [`Error::InvalidName`] naming the reason.
pub fn check_column_name(name: &str) -> Result<()> {
    let reason = if name.is_empty() {
        Some("empty")
    } else if name.contains([',', '"', '\r', '\n']) {
        Some("contains a comma, double quote or line break")
    } else if name.trim() != name {
        Some("starts or ends with whitespace")
    } else {
        None
    };
    match reason {
        Some(reason) => Err(Error::InvalidName {
            name: name.to_owned(),
            reason,
        }),
        None => Ok(()),
    }
}

/// Checks a header: at least one name, each valid, none repeated.
pub(crate) fn check_names<'a>(names: impl IntoIterator<Item = &'a str>) -> Result<()> {
    let mut seen = std::collections::HashSet::new();
    for name in names {
        check_column_name(name)?;
        if !seen.insert(name) {
            return Err(Error::DuplicateName {
                name: name.to_owned(),
            });
        }
    }
    if seen.is_empty() {
        return Err(Error::NoColumns);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_unequal_lengths_naming_both_columns() {
        let err = Table::new(vec![
            Column::new("t", vec![0.0, 1.0]),
            Column::new("q_x", vec![0.0]),
        ])
        .unwrap_err();
        let msg = err.to_string();
        assert!(matches!(
            err,
            Error::ColumnLength {
                expected: 2,
                found: 1,
                ..
            }
        ));
        assert!(msg.contains("q_x") && msg.contains("`t`"), "{msg}");
    }

    #[test]
    fn rejects_bad_and_duplicate_names() {
        for bad in ["", "a,b", "a\"b", "a\nb", " a", "a "] {
            assert!(matches!(
                Table::new(vec![Column::new(bad, vec![])]),
                Err(Error::InvalidName { .. })
            ));
        }
        assert!(matches!(
            Table::new(vec![Column::new("t", vec![]), Column::new("t", vec![])]),
            Err(Error::DuplicateName { .. })
        ));
        assert!(matches!(Table::new(vec![]), Err(Error::NoColumns)));
    }

    #[test]
    fn lookups() {
        let t = Table::new(vec![
            Column::new("t", vec![0.0, 1.0]),
            Column::new("q_x", vec![2.0, 3.0]),
            Column::new("q_y", vec![4.0, 5.0]),
        ])
        .unwrap();
        assert_eq!(t.n_rows(), 2);
        assert_eq!(t.values("q_y"), Some(&[4.0, 5.0][..]));
        assert_eq!(t.columns_with_prefix("q_").count(), 2);
        assert_eq!(t.row(1), Some(vec![1.0, 3.0, 5.0]));
        assert_eq!(t.row(2), None);
    }
}
