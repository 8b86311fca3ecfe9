//! Reducing long series to what a plot can show, without hiding spikes or gaps.

/// A series ready to draw: finite points only, split where non-finite values interrupt it.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Segments {
    /// Polylines of finite `(x, y)` points.
    pub segments: Vec<Vec<(f64, f64)>>,
    /// Number of input points with a non-finite coordinate.
    pub non_finite: usize,
    /// Number of min/max buckets the series was reduced to; 0 when kept whole.
    pub buckets: usize,
}

impl Segments {
    /// Total number of points kept.
    #[cfg(test)]
    pub fn len(&self) -> usize {
        self.segments.iter().map(Vec::len).sum()
    }

    /// Iterates over all kept points.
    pub fn points(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.segments.iter().flatten().copied()
    }
}

fn finite(x: f64, y: f64) -> bool {
    x.is_finite() && y.is_finite()
}

/// Splits `(x[i], y[i])` into runs of finite points (no reduction).
pub(crate) fn finite_segments(x: &[f64], y: &[f64]) -> Segments {
    let mut out = Segments::default();
    let mut current = Vec::new();
    for (&xi, &yi) in x.iter().zip(y) {
        if finite(xi, yi) {
            current.push((xi, yi));
        } else {
            out.non_finite += 1;
            if !current.is_empty() {
                out.segments.push(std::mem::take(&mut current));
            }
        }
    }
    if !current.is_empty() {
        out.segments.push(current);
    }
    out
}

/// Reduces a time series to at most about `max_points` points: the index range is cut into
/// `max_points / 2` buckets and each keeps its minimum and its maximum (in index order), so
/// spikes survive. A bucket containing a non-finite value ends the current polyline, so gaps
/// stay visible. Series of at most `max_points` points are kept whole.
pub(crate) fn min_max(x: &[f64], y: &[f64], max_points: usize) -> Segments {
    let n = x.len().min(y.len());
    let max_points = max_points.max(4);
    if n <= max_points {
        return finite_segments(&x[..n], &y[..n]);
    }
    let buckets = max_points / 2;
    let size = n.div_ceil(buckets);
    let mut out = Segments {
        buckets: n.div_ceil(size),
        ..Segments::default()
    };
    let mut current = Vec::new();
    for start in (0..n).step_by(size) {
        let end = (start + size).min(n);
        let mut lo: Option<usize> = None;
        let mut hi: Option<usize> = None;
        let mut gap = false;
        for i in start..end {
            if !finite(x[i], y[i]) {
                out.non_finite += 1;
                gap = true;
                continue;
            }
            if lo.is_none_or(|j| y[i] < y[j]) {
                lo = Some(i);
            }
            if hi.is_none_or(|j| y[i] > y[j]) {
                hi = Some(i);
            }
        }
        if let (Some(a), Some(b)) = (lo, hi) {
            let (first, second) = if a <= b { (a, b) } else { (b, a) };
            current.push((x[first], y[first]));
            if second != first {
                current.push((x[second], y[second]));
            }
        }
        if gap && !current.is_empty() {
            out.segments.push(std::mem::take(&mut current));
        }
    }
    if !current.is_empty() {
        out.segments.push(current);
    }
    out
}

/// Keeps one point per cell of a `cells.0 × cells.1` grid over the rectangle `x × y`
/// (the first point to land in each cell), for drawing huge point clouds in bounded time.
/// Points outside the rectangle or non-finite are dropped.
pub(crate) fn grid_thin(
    points: impl Iterator<Item = (f64, f64)>,
    x: (f64, f64),
    y: (f64, f64),
    cells: (usize, usize),
) -> Vec<(f64, f64)> {
    let (w, h) = (cells.0.max(1), cells.1.max(1));
    let mut seen = vec![false; w * h];
    let cell = |v: f64, (lo, hi): (f64, f64), n: usize| -> Option<usize> {
        let f = if hi > lo { (v - lo) / (hi - lo) } else { 0.5 };
        if !(0.0..=1.0).contains(&f) {
            return None;
        }
        // `f` is in [0, 1], so the cast is in range; the `min` folds f == 1 into the last cell.
        Some(((f * n as f64) as usize).min(n - 1))
    };
    let mut out = Vec::new();
    for (px, py) in points {
        if let (Some(i), Some(j)) = (cell(px, x, w), cell(py, y, h)) {
            let k = j * w + i;
            if !seen[k] {
                seen[k] = true;
                out.push((px, py));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn short_series_are_kept_and_split_at_nan() {
        let x = [0.0, 1.0, 2.0, 3.0, 4.0];
        let y = [1.0, f64::NAN, 2.0, 3.0, f64::INFINITY];
        let s = min_max(&x, &y, 100);
        assert_eq!(s.buckets, 0);
        assert_eq!(s.non_finite, 2);
        assert_eq!(
            s.segments,
            vec![vec![(0.0, 1.0)], vec![(2.0, 2.0), (3.0, 3.0)]]
        );
    }

    #[test]
    fn a_single_spike_survives_bucketing() {
        let n = 1_000_000;
        let x: Vec<f64> = (0..n).map(|i| i as f64).collect();
        let mut y: Vec<f64> = (0..n).map(|i| (i as f64 * 1e-3).sin() * 1e-12).collect();
        y[654_321] = 1e-3;
        y[123_456] = -2e-3;
        let s = min_max(&x, &y, 4000);
        assert!(s.buckets == 2000 && s.len() <= 4000, "{}", s.len());
        let pts: Vec<_> = s.points().collect();
        assert!(pts.contains(&(654_321.0, 1e-3)));
        assert!(pts.contains(&(123_456.0, -2e-3)));
        assert!(
            pts.windows(2).all(|w| w[0].0 < w[1].0),
            "x stays increasing"
        );
    }

    #[test]
    fn nan_in_long_series_makes_a_gap() {
        let n = 100_000;
        let x: Vec<f64> = (0..n).map(|i| i as f64).collect();
        let mut y = vec![1.0; n];
        y[50_000] = f64::NAN;
        let s = min_max(&x, &y, 1000);
        assert_eq!(s.segments.len(), 2);
        assert_eq!(s.non_finite, 1);
        let all_nan = min_max(&x, &vec![f64::NAN; n], 1000);
        assert!(all_nan.segments.is_empty());
        assert_eq!(all_nan.non_finite, n);
    }

    #[test]
    fn grid_thinning_is_bounded() {
        let pts = (0..1_000_000).map(|i| {
            let a = i as f64 * 0.001;
            (a.cos(), a.sin())
        });
        let kept = grid_thin(pts, (-1.0, 1.0), (-1.0, 1.0), (100, 100));
        assert!(kept.len() <= 10_000 && kept.len() > 100, "{}", kept.len());
    }
}
