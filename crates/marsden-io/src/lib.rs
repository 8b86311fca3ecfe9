//! marsden-io: writers (CSV, `.npy`) and plots (PNG) for marsden trajectories, kept out of the
//! core library and independent of it: inputs are plain columns of `f64`.
//!
//! Map of the crate:
//! * [`table`] — [`Table`]/[`Column`]: named columns of equal length.
//! * [`layout`] — [`Layout`]/[`Group`]: how flat rows group into arrays (`t`, `q`, `p`, …);
//!   its docs show how the CLI streams a run and plots it.
//! * [`csv`] — [`CsvWriter`] (streaming), [`write_csv`], [`read_csv`]; round-trip numbers.
//! * [`npy`] — [`NpyWriter`], [`NpyDirWriter`] (streaming, one file per group),
//!   [`write_npy_dir`], [`read_npy`], [`read_npy_dir`].
//! * [`sink`] — [`RowSink`]: the streaming interface both writers implement.
//! * [`thin`] — [`Thinner`]: a bounded sketch of a long run (first, last, extremes) for plots,
//!   filled by [`read_csv_thinned`] / [`read_npy_dir_thinned`] in one streaming pass.
//! * [`plot`] — PNG plots: phase portrait, energy error, momentum-map drift, constraint
//!   residual; text uses a font embedded in the crate, so no system font is needed.
//! * [`error`] — [`Error`]: every failure is a value naming its file.

pub mod atomic;
pub mod csv;
pub mod error;
pub mod layout;
pub mod npy;
pub mod plot;
pub mod sink;
pub mod table;
pub mod thin;

pub use atomic::write_atomically;
pub use csv::{
    CsvWriter, cut_at, open_at_least, read_csv, read_csv_from, read_csv_numeric, read_csv_thinned,
    write_csv,
};
pub use error::{Error, Result};
pub use layout::{Group, GroupKind, Layout};
pub use npy::{
    NpyArray, NpyDirWriter, NpyShape, NpyWriter, read_npy, read_npy_dir, read_npy_dir_thinned,
    write_npy_dir,
};
pub use plot::{
    PhaseCurve, PlotOptions, PlotReport, Series, plot_constraint_residual,
    plot_constraint_residuals, plot_energy_balance, plot_energy_error, plot_momentum_drift,
    plot_phase_portrait, plot_run,
};
pub use sink::{RowSink, SinkMark};
pub use table::{Column, Table, check_column_name};
pub use thin::{Thinned, Thinner};
