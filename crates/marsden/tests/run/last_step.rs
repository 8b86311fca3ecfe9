//! A grid that ends with one shorter step ([`TimeGrid::ending_at`]): the run ends at `t_end`
//! exactly, the last step is the variational step of its own size, and the method keeps its
//! order at `t_end`.

// Tests may unwrap.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use marsden::discrete::rules::Galerkin;
use marsden::systems::HarmonicOscillator;
use marsden::{Initial, Midpoint, Problem, Rule, SolveOptions, TimeGrid, Trapezoid};

/// The oscillator (m = k = 1) from q = 1, p = 0 on `grid`.
fn oscillator(grid: TimeGrid) -> Problem<HarmonicOscillator> {
    let initial = Initial::momentum(&[1.0], &[0.0]);
    Problem::new(HarmonicOscillator::default(), initial, grid).unwrap()
}

/// The final `(t, q, p)` of a run of `rule` on `grid`.
fn end<R: Rule>(rule: &R, grid: TimeGrid) -> (f64, f64, f64) {
    let traj = oscillator(grid)
        .solve(rule, &SolveOptions::default())
        .unwrap();
    let last = traj.len() - 1;
    (traj.t(last), traj.q(last)[0], traj.p(last)[0])
}

/// One midpoint step of size `h` of the oscillator: the Cayley rotation
/// `(I − hA/2)⁻¹(I + hA/2)` with `A = [[0, 1], [−1, 0]]` (reference case R1).
fn cayley(h: f64, q: f64, p: f64) -> (f64, f64) {
    let a = h * h / 4.0;
    (
        (q * (1.0 - a) + h * p) / (1.0 + a),
        (p * (1.0 - a) - h * q) / (1.0 + a),
    )
}

#[test]
fn grid_ending_at_a_time_off_the_steps_has_a_shorter_last_step() {
    let grid = TimeGrid::ending_at(0.0, 1.05, 0.1).unwrap();
    assert_eq!(grid.steps, 11);
    assert_eq!(grid.time(11), 1.05, "the final time is t_end itself");
    assert_eq!(grid.time(10), 1.0);
    let last = grid.last_step().unwrap();
    assert!((last - 0.05).abs() < 1e-15, "{last}");
    assert_eq!(grid.step_size(9), 0.1);
    assert_eq!(grid.step_size(10), last);
    let whole = TimeGrid::ending_at(0.0, 10.0, 0.1).unwrap();
    assert_eq!(
        (whole.steps, whole.end),
        (100, None),
        "a whole number stays uniform"
    );
}

/// R1: ten midpoint steps of h = 0.1 and one of 0.05 are the closed form's ten Cayley rotations
/// and one of the shorter step.
#[test]
fn midpoint_last_step_is_the_cayley_map_of_its_own_size_r1() {
    let (t, q, p) = end(&Midpoint, TimeGrid::ending_at(0.0, 1.05, 0.1).unwrap());
    let mut z = (1.0, 0.0);
    for _ in 0..10 {
        z = cayley(0.1, z.0, z.1);
    }
    z = cayley(1.05 - 1.0, z.0, z.1);
    assert_eq!(t, 1.05);
    assert!(
        (q - z.0).abs() < 1e-14 && (p - z.1).abs() < 1e-14,
        "{q} {p} vs {z:?}"
    );
    // The wrong step (a full h) would land 0.05 further round the circle.
    let wrong = cayley(0.1, z.0, z.1);
    assert!((q - wrong.0).abs() > 1e-3);
    // H = (q² + p²)/2 is a quadratic invariant of every midpoint step, whatever its size.
    assert!((0.5 * (q * q + p * p) - 0.5).abs() < 1e-14);
}

/// The error at t_end = 1 against the exact flow (cos t, −sin t) with steps that never divide
/// the interval: the fitted order is the method's (2 for midpoint and trapezoid, 4 for
/// gauss-2), so the shorter last step costs no order.
#[test]
fn order_is_kept_at_a_t_end_off_the_grid() {
    fn slope<R: Rule>(rule: &R) -> f64 {
        let hs = [0.3, 0.15, 0.075, 0.0375];
        let errors: Vec<f64> = hs
            .iter()
            .map(|&h| {
                let grid = TimeGrid::ending_at(0.0, 1.0, h).unwrap();
                assert!(grid.end.is_some(), "h = {h} must not divide 1");
                let (t, q, p) = end(rule, grid);
                assert_eq!(t, 1.0);
                ((q - 1f64.cos()).powi(2) + (p + 1f64.sin()).powi(2)).sqrt()
            })
            .collect();
        let (x, y) = (hs.map(f64::ln), errors.iter().map(|e| e.ln()));
        let y: Vec<f64> = y.collect();
        let (mx, my) = (x.iter().sum::<f64>() / 4.0, y.iter().sum::<f64>() / 4.0);
        let cov: f64 = x.iter().zip(&y).map(|(a, b)| (a - mx) * (b - my)).sum();
        cov / x.iter().map(|a| (a - mx).powi(2)).sum::<f64>()
    }
    let midpoint = slope(&Midpoint);
    let trapezoid = slope(&Trapezoid);
    let gauss = slope(&Galerkin::gauss(2).unwrap());
    assert!((midpoint - 2.0).abs() < 0.15, "midpoint {midpoint}");
    assert!((trapezoid - 2.0).abs() < 0.15, "trapezoid {trapezoid}");
    assert!((gauss - 4.0).abs() < 0.3, "gauss-2 {gauss}");
}

#[test]
fn a_grid_whose_end_lies_outside_its_last_step_is_refused() {
    let grid = TimeGrid {
        end: Some(2.0),
        ..TimeGrid::new(0.0, 0.1, 10).unwrap()
    };
    assert!(grid.validate().is_err());
    let initial = Initial::momentum(&[1.0], &[0.0]);
    assert!(Problem::new(HarmonicOscillator::default(), initial, grid).is_err());
}

/// `TimeGrid::ending_exactly_at`: from 1 to 1.7 with h = 0.01 is a whole number of steps (70),
/// but `1 + 70·0.01` rounds to 1.7000000000000002; the grid ends at 1.7 itself with a last step
/// `1.7 − t₆₉` equal to h to round-off, and the run's last state is the uniform run's to
/// round-off (R1's Cayley rotation is continuous in h). A grid that is uniform to the bit
/// stays as `ending_at` builds it.
#[test]
fn a_grid_ending_exactly_at_a_whole_number_of_steps_lands_on_the_bit() {
    let exact = TimeGrid::ending_exactly_at(1.0, 1.7, 0.01).unwrap();
    let uniform = TimeGrid::ending_at(1.0, 1.7, 0.01).unwrap();
    assert_eq!((exact.steps, uniform.steps), (70, 70));
    assert_eq!(uniform.t_end(), 1.7000000000000002);
    assert_eq!(exact.t_end(), 1.7);
    let last = exact.last_step().unwrap();
    assert!((last - 0.01).abs() < 1e-15, "last step {last}");
    exact.validate().unwrap();
    let (t, q, p) = end(&Midpoint, exact);
    let (_, q_uniform, p_uniform) = end(&Midpoint, uniform);
    assert_eq!(t, 1.7);
    assert!((q - q_uniform).abs() < 1e-15 && (p - p_uniform).abs() < 1e-15);
    let whole = TimeGrid::ending_exactly_at(0.0, 1.0, 0.125).unwrap();
    assert_eq!(whole, TimeGrid::ending_at(0.0, 1.0, 0.125).unwrap());
}
