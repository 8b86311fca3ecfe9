//! The planar pendulum (q₀ = 1.5, at rest) with the midpoint rule: energy error and timing.
//!
//! `cargo run --release --example pendulum [steps] [h]`

use marsden::analysis::diagnostics::EnergyReport;
use marsden::systems::Pendulum;
use marsden::{Initial, Midpoint, Problem, SolveOptions, TimeGrid};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let steps: usize = args.next().map_or(Ok(100_000), |s| s.parse())?;
    let h: f64 = args.next().map_or(Ok(0.05), |s| s.parse())?;
    let pendulum = Pendulum::default();
    let problem = Problem::new(
        pendulum,
        Initial::velocity(&[1.5], &[0.0]),
        TimeGrid::new(0.0, h, steps)?,
    )?;
    let start = std::time::Instant::now();
    let trajectory = problem.solve(&Midpoint, &SolveOptions::default())?;
    let wall = start.elapsed().as_secs_f64();
    let energy = EnergyReport::of(&pendulum, &trajectory)?;
    let last = trajectory.len() - 1;
    println!(
        "pendulum, midpoint rule, h = {h}, {steps} steps in {wall:.3} s ({:.0} ns/step)",
        wall / steps as f64 * 1e9
    );
    println!(
        "final state: t = {}, q = {:.15}, p = {:.15}",
        trajectory.t(last),
        trajectory.q(last)[0],
        trajectory.p(last)[0]
    );
    println!(
        "energy: E0 = {:.15}, max |ΔE| = {:.4e}, max |ΔE/E0| = {:.4e}, drift {:.2e} per unit time",
        energy.initial, energy.max_abs_error, energy.max_rel_error, energy.drift_per_unit_time
    );
    println!(
        "newton: {} iterations over {} steps (max {} in one step)",
        trajectory.statistics.newton_iterations,
        trajectory.statistics.steps,
        trajectory.statistics.max_newton_iterations
    );
    Ok(())
}
