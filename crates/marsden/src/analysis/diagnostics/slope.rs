//! Least-squares slope of a series against time, batch and streaming.

/// Slope `b` of the least-squares line `y ≈ a + b x` (0 for fewer than two points or constant x).
pub fn least_squares_slope(x: &[f64], y: &[f64]) -> f64 {
    let mut acc = OnlineSlope::default();
    x.iter().zip(y).for_each(|(&xi, &yi)| acc.push(xi, yi));
    acc.slope()
}

/// Streaming least-squares slope (Welford-style centred updates, stable for 10⁸ points).
///
/// Data are shifted by the first point (exact for nearby values, Sterbenz), so a large common
/// offset does not cost accuracy.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct OnlineSlope {
    origin: (f64, f64),
    count: f64,
    mean_x: f64,
    mean_y: f64,
    sxx: f64,
    sxy: f64,
}

impl OnlineSlope {
    /// Adds a point.
    pub fn push(&mut self, x: f64, y: f64) {
        if self.count == 0.0 {
            self.origin = (x, y);
        }
        let (x, y) = (x - self.origin.0, y - self.origin.1);
        self.count += 1.0;
        let dx = x - self.mean_x;
        self.mean_x += dx / self.count;
        self.mean_y += (y - self.mean_y) / self.count;
        self.sxx += dx * (x - self.mean_x);
        self.sxy += dx * (y - self.mean_y);
    }

    /// The current slope.
    pub fn slope(&self) -> f64 {
        if self.count < 2.0 || self.sxx == 0.0 {
            0.0
        } else {
            self.sxy / self.sxx
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recovers_a_line_with_offset() {
        let x: Vec<f64> = (0..1000).map(|i| 1e3 + i as f64 * 0.1).collect();
        let y: Vec<f64> = x.iter().map(|t| 3.0 - 2.5e-7 * t).collect();
        let b = least_squares_slope(&x, &y);
        assert!((b + 2.5e-7).abs() < 1e-12 * 2.5e-7, "{b:e}");
    }

    #[test]
    fn symmetric_oscillation_has_no_slope() {
        let x: Vec<f64> = (0..=2000).map(|i| i as f64 * 0.01).collect();
        let y: Vec<f64> = x.iter().map(|t| (t * std::f64::consts::PI).cos()).collect();
        assert!(least_squares_slope(&x, &y).abs() < 1e-4);
    }
}
