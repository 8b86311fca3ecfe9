//! Prints the SQP history of the pendulum swing-up (N and α from the command line).

use std::f64::consts::PI;

use marsden::GeneralizedMidpoint;
use marsden::systems::Pendulum;
use marsden_control::{Boundary, Effort, Horizon, InputMap, OptimalControl, SqpOptions};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let steps: usize = args.next().map_or(Ok(120), |a| a.parse())?;
    let alpha: f64 = args.next().map_or(Ok(0.5), |a| a.parse())?;
    let problem = OptimalControl::new(
        Pendulum::default(),
        InputMap::full(1),
        Effort::default(),
        Horizon {
            t0: 0.0,
            duration: 6.0,
            steps,
        },
        Boundary::rest(&[0.0]),
        Boundary::rest(&[PI]),
    )?;
    let clock = std::time::Instant::now();
    let solution = problem.solve(&GeneralizedMidpoint::new(alpha)?, &SqpOptions::default())?;
    for (i, it) in solution.history.iter().enumerate() {
        println!(
            "{i:3} cost {:.8} viol {:.2e} kkt {:.2e} step {:.2e} delta {:.1e}",
            it.cost, it.violation, it.kkt, it.step, it.regularization
        );
    }
    println!(
        "{:?} cost {:.8} in {} iterations, {:.3} s",
        solution.status,
        solution.cost,
        solution.iterations,
        clock.elapsed().as_secs_f64()
    );
    Ok(())
}
