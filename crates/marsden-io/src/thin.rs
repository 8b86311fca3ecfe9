//! A bounded sketch of a long trajectory, for plots: the rows worth drawing, read once.
//!
//! A run of 3·10⁷ rows does not fit in a plot's memory budget, and does not need to: a
//! picture is a few thousand pixels wide. [`Thinner`] takes rows one at a time (it is a
//! [`RowSink`], so a reader streams a file into it) and keeps, for consecutive buckets of rows,
//!
//! * the bucket's first row,
//! * for each *monitored* column (energy, momentum maps, residuals: where a spike is the
//!   news), the rows holding the bucket's minimum and maximum,
//! * the first row in which a monitored column is not finite (so gaps stay visible),
//!
//! and the very last row. When the number of buckets reaches its limit, neighbouring buckets
//! merge (their kept rows compete again, which keeps exactly the extremes of the union) and the
//! bucket size doubles, so memory stays bounded whatever the length of the run while every
//! monitored extreme of the whole run survives. This is the min/max reduction of
//! [`plot`](crate::plot)'s time series, done on whole rows and in one pass.

use crate::error::Result;
use crate::sink::RowSink;
use crate::table::{Column, Table};

/// Default memory budget of the kept rows, in bytes.
pub const DEFAULT_BUDGET: usize = 16 << 20;
/// At most this many columns are monitored for extremes (the first ones asked for).
const MAX_MONITORED: usize = 16;
/// Bucket-count limits (before merging); the budget chooses within them.
const MIN_BUCKETS: usize = 16;
const MAX_BUCKETS: usize = 1000;
/// How errors name a thinner (it writes no file).
const SKETCH: &str = "<plot sketch>";

/// One kept row: its index in the input and its values.
#[derive(Debug, Clone)]
struct Kept {
    index: u64,
    values: Vec<f64>,
}

/// The kept rows of one bucket, in input order, without repeats.
#[derive(Debug, Clone, Default)]
struct Bucket {
    rows: Vec<Kept>,
}

/// What [`Thinner::finish_table`] returns: the kept rows as a table, and how many were read.
#[derive(Debug, Clone, PartialEq)]
pub struct Thinned {
    /// The kept rows, in input order, with the input's column names.
    pub table: Table,
    /// Number of rows read.
    pub rows_read: u64,
    /// Why rows at the end were left out (the `.npy` files of a run cut short end at
    /// different rows), or `None`.
    pub cut: Option<String>,
}

impl Thinned {
    /// A one-line note saying how the rows were chosen, or `None` if every row was kept.
    pub fn note(&self) -> Option<String> {
        let kept = self.table.n_rows() as u64;
        let thinned = (kept < self.rows_read).then(|| {
            format!(
                "drawn from {kept} of {} rows: first, last, and each stretch's extremes",
                self.rows_read
            )
        });
        match (thinned, &self.cut) {
            (Some(a), Some(b)) => Some(format!("{a}; {b}")),
            (a, b) => a.or_else(|| b.clone()),
        }
    }
}

/// Streaming row reducer with bounded memory (see the module docs).
#[derive(Debug, Clone)]
pub struct Thinner {
    names: Vec<String>,
    monitored: Vec<usize>,
    max_buckets: usize,
    /// Rows per bucket (doubles at each merge).
    size: u64,
    buckets: Vec<Bucket>,
    current: Bucket,
    last: Option<Kept>,
    read: u64,
    finished: bool,
}

impl Thinner {
    /// A thinner for rows with these column names, watching the columns named in `monitored`
    /// (unknown names are ignored, at most 16 are watched) and keeping about `budget` bytes.
    pub fn new(names: Vec<String>, monitored: &[&str], budget: usize) -> Self {
        let monitored: Vec<usize> = monitored
            .iter()
            .filter_map(|m| names.iter().position(|n| n == m))
            .take(MAX_MONITORED)
            .collect();
        let per_bucket = 2 + 2 * monitored.len();
        let row_bytes = 8 * names.len().max(1) + std::mem::size_of::<Kept>();
        // At most 2·max_buckets buckets exist at once (just before a merge).
        let max_buckets = (budget / (row_bytes * per_bucket * 2)).clamp(MIN_BUCKETS, MAX_BUCKETS);
        Self {
            names,
            monitored,
            max_buckets,
            size: 1,
            buckets: Vec::new(),
            current: Bucket::default(),
            last: None,
            read: 0,
            finished: false,
        }
    }

    /// Number of rows read so far.
    pub fn rows_read(&self) -> u64 {
        self.read
    }

    /// Takes one row (whose length must be the number of columns).
    fn push(&mut self, row: &[f64]) {
        let index = self.read;
        self.read += 1;
        self.current.rows.push(Kept {
            index,
            values: row.to_vec(),
        });
        // Reduce in batches: the kept set of a bucket is at most 2 + 2·(monitored) rows.
        if self.current.rows.len() > 4 * (2 + self.monitored.len()) {
            self.current = select(std::mem::take(&mut self.current), &self.monitored);
        }
        // The last row reuses its buffer: one copy per row, not two.
        match &mut self.last {
            Some(last) => {
                last.index = index;
                last.values.clear();
                last.values.extend_from_slice(row);
            }
            None => {
                self.last = Some(Kept {
                    index,
                    values: row.to_vec(),
                })
            }
        }
        if self.read.is_multiple_of(self.size) {
            let full = select(std::mem::take(&mut self.current), &self.monitored);
            self.buckets.push(full);
            if self.buckets.len() >= 2 * self.max_buckets {
                self.merge_pairs();
            }
        }
    }

    /// Halves the number of buckets by merging neighbours; the bucket size doubles.
    fn merge_pairs(&mut self) {
        let old = std::mem::take(&mut self.buckets);
        let mut it = old.into_iter();
        while let Some(mut a) = it.next() {
            if let Some(b) = it.next() {
                a.rows.extend(b.rows);
            }
            self.buckets.push(select(a, &self.monitored));
        }
        self.size *= 2;
    }

    /// The kept rows as a table (first, extremes, last), and the number of rows read.
    ///
    /// # Errors
    /// [`Error::NoColumns`](crate::Error::NoColumns) and the other [`Table::new`] checks.
    pub fn finish_table(mut self) -> Result<Thinned> {
        let mut rows: Vec<Kept> = std::mem::take(&mut self.buckets)
            .into_iter()
            .chain(std::iter::once(std::mem::take(&mut self.current)))
            .flat_map(|b| b.rows)
            .collect();
        if let Some(last) = self.last.take()
            && rows.last().is_none_or(|r| r.index != last.index)
        {
            rows.push(last);
        }
        let columns = self
            .names
            .iter()
            .enumerate()
            .map(|(j, name)| Column::new(name.clone(), rows.iter().map(|r| r.values[j]).collect()))
            .collect();
        Ok(Thinned {
            table: Table::new(columns)?,
            rows_read: self.read,
            cut: None,
        })
    }
}

/// The rows of `b` worth keeping: first, extremes of monitored columns, first non-finite.
fn select(b: Bucket, monitored: &[usize]) -> Bucket {
    let rows = b.rows;
    let mut keep = vec![false; rows.len()];
    if rows.is_empty() {
        return Bucket { rows };
    }
    keep[0] = true;
    for &c in monitored {
        let finite = |i: &usize| rows[*i].values[c].is_finite();
        let value = |i: &usize| rows[*i].values[c];
        let indices = || (0..rows.len()).filter(finite);
        if let Some(i) = indices().min_by(|a, b| value(a).total_cmp(&value(b))) {
            keep[i] = true;
        }
        if let Some(i) = indices().max_by(|a, b| value(a).total_cmp(&value(b))) {
            keep[i] = true;
        }
    }
    if let Some(i) =
        (0..rows.len()).find(|&i| monitored.iter().any(|&c| !rows[i].values[c].is_finite()))
    {
        keep[i] = true;
    }
    let rows = rows
        .into_iter()
        .zip(keep)
        .filter_map(|(r, k)| k.then_some(r))
        .collect();
    Bucket { rows }
}

impl RowSink for Thinner {
    fn write_row(&mut self, row: &[f64]) -> Result<()> {
        if self.finished {
            return Err(crate::Error::Finished {
                path: SKETCH.into(),
            });
        }
        if row.len() != self.names.len() {
            return Err(crate::Error::RowLength {
                path: SKETCH.into(),
                row: self.read,
                expected: self.names.len(),
                found: row.len(),
            });
        }
        self.push(row);
        Ok(())
    }

    fn flush(&mut self) -> Result<()> {
        Ok(())
    }

    fn finish(&mut self) -> Result<()> {
        self.finished = true;
        Ok(())
    }

    fn rows_written(&self) -> u64 {
        self.read
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn thin(n: u64, budget: usize, f: impl Fn(u64) -> f64) -> Thinned {
        let mut t = Thinner::new(vec!["t".into(), "energy".into()], &["energy"], budget);
        for i in 0..n {
            t.write_row(&[i as f64, f(i)]).unwrap();
        }
        t.finish_table().unwrap()
    }

    #[test]
    fn short_runs_are_kept_whole() {
        let out = thin(50, DEFAULT_BUDGET, |i| i as f64);
        assert_eq!(out.table.n_rows(), 50);
        assert_eq!(out.note(), None);
    }

    #[test]
    fn long_runs_keep_first_last_and_every_extreme() {
        let n = 2_000_000;
        let spike = 1_234_567;
        let dip = 777_777;
        let nan = 1_999_000;
        let out = thin(n, 1 << 20, |i| match i {
            _ if i == spike => 5.0,
            _ if i == dip => -7.0,
            _ if i == nan => f64::NAN,
            _ => (i as f64 * 1e-3).sin() * 1e-9,
        });
        let t = out.table.values("t").unwrap();
        let e = out.table.values("energy").unwrap();
        assert!(out.table.n_rows() < 20_000, "{}", out.table.n_rows());
        assert_eq!(out.rows_read, n);
        assert_eq!((t[0], *t.last().unwrap()), (0.0, (n - 1) as f64));
        assert!(t.windows(2).all(|w| w[0] < w[1]), "rows stay in order");
        assert!(t.contains(&(spike as f64)) && t.contains(&(dip as f64)));
        assert!(t.contains(&(nan as f64)) && e.iter().any(|v| v.is_nan()));
        assert!(out.note().unwrap().contains("of 2000000 rows"));
    }

    #[test]
    fn memory_stays_within_the_budget() {
        let budget = 1 << 20;
        let mut t = Thinner::new(vec!["t".into(), "energy".into()], &["energy"], budget);
        for i in 0..300_000u64 {
            t.write_row(&[i as f64, (i as f64).sin()]).unwrap();
            let rows: usize = t.buckets.iter().map(|b| b.rows.len()).sum();
            assert!(rows <= 2 * t.max_buckets * 4 + 4);
        }
    }

    #[test]
    fn rows_of_the_wrong_length_are_refused() {
        let mut t = Thinner::new(vec!["t".into()], &[], DEFAULT_BUDGET);
        assert!(t.write_row(&[1.0, 2.0]).is_err());
    }
}
