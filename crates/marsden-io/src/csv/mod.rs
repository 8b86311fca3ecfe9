//! `trajectory.csv`: a header line of column names, then one line of numbers per row.
//!
//! # Format
//! * Comma-separated, `\n` line ends, no quoting: names are checked by
//!   [`check_column_name`](crate::check_column_name) so none is needed.
//! * Numbers are printed so that parsing them back gives the **bit-identical** `f64`
//!   (shortest round-trip digits, see [`format_f64`]): plain decimals for
//!   `1e-5 <= |x| < 1e16` and zero (`0.01`, `-0`, `123.5`), otherwise exponent form
//!   (`1e-300`, `-2.5e20`). `-0` keeps its sign.
//! * Non-finite values are written `NaN`, `inf` and `-inf`, which Rust's `f64::from_str`,
//!   Python's `float`, numpy and pandas all read. NaN payloads and signs are not kept.
//!
//! Lines are only ever handed to the file whole (the writer buffers whole rows and spills
//! them together), so a run killed abruptly leaves complete rows, barring a kill inside one
//! `write` system call.

mod loose;
mod number;
mod reader;
mod writer;

pub use loose::read_csv_numeric;
pub use number::{format_f64, parse_f64};
pub use reader::{MAX_LINE, read_csv, read_csv_from, read_csv_thinned};
pub use writer::{CsvWriter, cut_at, open_at_least, write_csv};
