//! Solves the cart-pole swing-up of the bench (N from the command line) and prints the result.

use marsden_control::{Boundary, Effort, Horizon, InputMap, OptimalControl, SqpOptions};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let steps: usize = std::env::args().nth(1).map_or(Ok(200), |a| a.parse())?;
    let duration: f64 = std::env::args().nth(2).map_or(Ok(2.0), |a| a.parse())?;
    let problem = OptimalControl::new(
        marsden::systems::PendulumOnCart::default(),
        InputMap::new(&[0]),
        Effort::default(),
        Horizon {
            t0: 0.0,
            duration,
            steps,
        },
        Boundary::rest(&[0.0, 0.0]),
        Boundary::rest(&[0.0, std::f64::consts::PI]),
    )?;
    let clock = std::time::Instant::now();
    let s = problem.solve(&marsden::Midpoint, &SqpOptions::default())?;
    for it in &s.history {
        println!(
            "cost {:.8} viol {:.2e} kkt {:.2e} step {:.2e} delta {:.1e}",
            it.cost, it.violation, it.kkt, it.step, it.regularization
        );
    }
    let umax =
        s.u.iter()
            .map(|u| u[0].abs())
            .fold(0.0, marsden::numerics::dense::max_or_nan);
    let xmax =
        s.q.iter()
            .map(|q| q[0].abs())
            .fold(0.0, marsden::numerics::dense::max_or_nan);
    println!(
        "{:?} cost {:.8}, {} iterations, max |u| {umax:.3}, max |x| {xmax:.3}, {:.3} s",
        s.status,
        s.cost,
        s.iterations,
        clock.elapsed().as_secs_f64()
    );
    Ok(())
}
