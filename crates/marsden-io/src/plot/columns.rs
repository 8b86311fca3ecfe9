//! The columns a run's plots read, by the `trajectory.csv` naming convention, with declared
//! angles wrapped to (−π, π].

use std::collections::HashMap;

use super::angle::wrapped;
use super::options::PlotOptions;
use crate::table::Table;

/// The table's columns, with angle coordinates replaced by their wrapped values.
pub(crate) struct Columns<'a> {
    table: &'a Table,
    wrapped: HashMap<String, Vec<f64>>,
}

impl<'a> Columns<'a> {
    pub(crate) fn new(table: &'a Table, opts: &PlotOptions) -> Self {
        let wrapped = table
            .columns_with_prefix("q_")
            .filter(|c| opts.is_angle(&c.name))
            .map(|c| (c.name.clone(), wrapped(&c.values)))
            .collect();
        Self { table, wrapped }
    }

    /// The values of column `name` (wrapped if it is an angle); empty if absent.
    pub(crate) fn get(&self, name: &str) -> &[f64] {
        match self.wrapped.get(name) {
            Some(v) => v,
            None => self.table.values(name).unwrap_or(&[]),
        }
    }

    /// Coordinate names having both a `q_` and a `p_` column, in order.
    pub(crate) fn coordinates(&self) -> Vec<&'a str> {
        self.table
            .columns_with_prefix("q_")
            .map(|q| &q.name[2..])
            .filter(|name| self.table.values(&format!("p_{name}")).is_some())
            .collect()
    }
}

/// True when every finite value equals the first (or there are none).
pub(crate) fn is_constant(values: &[f64]) -> bool {
    let mut finite = values.iter().filter(|v| v.is_finite());
    match finite.next() {
        Some(first) => finite.all(|v| v == first),
        None => true,
    }
}
