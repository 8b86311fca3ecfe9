//! Memory and time of an adjoint gradient over a long run: Kepler e = 0.6, midpoint, h = 0.01,
//! `K` steps (default 10⁶), loss on the final position; prints the plain run's time, the
//! adjoint's, the checkpoints and segment held, and the peak resident set size (Linux
//! `VmHWM`) before and after the adjoint.
//!
//! `cargo run --release -p marsden --example adjoint_memory [steps]`

use marsden::sensitivity::{AdjointOptions, adjoint};
use marsden::systems::Kepler;
use marsden::{Integrator, Midpoint, Rule, State, TimeGrid};
use std::time::Instant;

/// Peak resident set size in kB (`VmHWM` of /proc/self/status), if the system reports it.
fn peak_rss_kb() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let steps: usize = std::env::args()
        .nth(1)
        .map_or(Ok(1_000_000), |s| s.parse())?;
    let (q, p) = Kepler::pericentre(0.6);
    let start = State {
        t: 0.0,
        q: q.to_vec(),
        p: p.to_vec(),
    };
    let grid = TimeGrid::new(0.0, 0.01, steps)?;
    let action = Midpoint.discretize(Kepler::default());

    let clock = Instant::now();
    let mut plain = start.clone();
    Integrator::new(action.clone()).advance(&mut plain, grid.h, steps)?;
    let run_time = clock.elapsed().as_secs_f64();
    let before = peak_rss_kb();

    let clock = Instant::now();
    let mut vi = Integrator::new(action);
    let loss = |k: usize, x: &State, out: &mut [f64]| {
        if k == steps {
            out[0] += x.q[0];
            out[1] += x.q[1];
        }
    };
    let g = adjoint(&mut vi, start, &grid, loss, &AdjointOptions::default())?;
    let adjoint_time = clock.elapsed().as_secs_f64();
    println!(
        "{steps} steps: plain run {run_time:.3} s, adjoint {adjoint_time:.3} s ({:.2}× the run)",
        adjoint_time / run_time
    );
    println!(
        "{} checkpoints, segments of {} steps; gradient of x_K + y_K w.r.t. (q₀, p₀): {:?}",
        g.checkpoints, g.segment, g.gradient
    );
    println!(
        "peak RSS: {} kB after the plain run, {} kB after the adjoint",
        before.map_or("?".into(), |k| k.to_string()),
        peak_rss_kb().map_or("?".into(), |k| k.to_string())
    );
    Ok(())
}
