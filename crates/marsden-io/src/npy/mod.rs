//! `.npy` output: one little-endian `f64` (`<f8`) array per column group, C order.
//!
//! The writer is hand-rolled (the NPY v1.0 format is a 128-byte header and raw data) so that
//! it can **stream**: the header reserves room for any row count, rows are appended, and the
//! header's shape is rewritten in place every time buffered rows reach the file and at
//! [`finish`](NpyWriter::finish). At any moment the file on disk is a valid `.npy` holding
//! at least the rows written up to the last spill; after `flush`/`finish`, exactly all rows.
//! Reading back uses the `npyz` crate.

mod dir;
mod header;
mod reader;
mod writer;

pub use dir::{NpyDirWriter, read_npy_dir, read_npy_dir_thinned, write_npy_dir};
pub use reader::{NpyArray, read_npy};
pub use writer::{NpyShape, NpyWriter};
