//! Plot inputs and outputs: sizes, series, and what was noted while drawing.

use std::path::PathBuf;

/// Size and density of a plot.
#[derive(Debug, Clone, PartialEq)]
pub struct PlotOptions {
    /// Image width in pixels (200..=10000).
    pub width: u32,
    /// Image height in pixels (200..=10000).
    pub height: u32,
    /// Longest series drawn point by point; longer time series are reduced to the minimum
    /// and maximum of `max_points / 2` buckets (spikes survive), longer phase curves are drawn
    /// as a thinned point cloud.
    pub max_points: usize,
    /// At most this many coordinates get a phase-portrait panel (the first ones).
    pub max_phase_panels: usize,
    /// Coordinates that are angles (names without the `q_` prefix): drawn wrapped to (−π, π].
    pub angles: Vec<String>,
    /// A remark printed on every plot, e.g. how the rows of a long run were chosen.
    pub note: Option<String>,
    /// Whether the `energy` column is a conserved quantity whose relative error is worth a
    /// plot. False for forced or time-dependent runs: their energy changes by the work done,
    /// and an "energy error" would mislead (their balance is drawn by
    /// [`plot_energy_balance`](crate::plot_energy_balance) from the work).
    pub energy_conserved: bool,
}

impl PlotOptions {
    /// Whether the column `q_<name>` (or the coordinate `<name>`) was declared an angle.
    pub fn is_angle(&self, column: &str) -> bool {
        let name = column.strip_prefix("q_").unwrap_or(column);
        self.angles.iter().any(|a| a == name)
    }
}

impl Default for PlotOptions {
    fn default() -> Self {
        Self {
            width: 1200,
            height: 800,
            max_points: 4000,
            max_phase_panels: 4,
            angles: Vec::new(),
            note: None,
            energy_conserved: true,
        }
    }
}

/// A named series of values over time, e.g. one momentum map `J_rot`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Series<'a> {
    /// Legend label.
    pub name: &'a str,
    /// One value per time in `t`.
    pub values: &'a [f64],
}

/// One coordinate's trajectory in phase space, for a phase portrait.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhaseCurve<'a> {
    /// Coordinate name; the axes are labelled `q_<name>` and `p_<name>`.
    pub name: &'a str,
    /// Positions.
    pub q: &'a [f64],
    /// Conjugate momenta, same length as `q`.
    pub p: &'a [f64],
}

/// What a plot function wrote.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PlotReport {
    /// The PNG file written.
    pub path: PathBuf,
    /// Remarks also printed on the plot: degenerate data (empty, constant, non-finite values),
    /// reductions (bucketing, omitted coordinates), values a log axis cannot show.
    pub notes: Vec<String>,
}
