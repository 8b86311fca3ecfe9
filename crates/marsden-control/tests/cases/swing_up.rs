//! The pendulum swing-up: `L = θ̇²/2 + cos θ`, torque `u`, from rest at `θ = 0` to rest at
//! `θ = π` in `T = 6`, cost `Σ h u_k²/2` (midpoint: `f_d^± = h u_k/2`).
//!
//! Reference: the same discrete problem solved by CasADi + IPOPT from `q` linear and `u = 0`
//! found a local optimum of cost 1.1192 at N = 120 (four digits given).

use std::f64::consts::PI;
use std::time::Instant;

use marsden::Midpoint;
use marsden::systems::Pendulum;
use marsden_control::{Boundary, Effort, Horizon, InputMap, OptimalControl, SqpOptions, Status};

/// The swing-up with `steps` steps.
pub fn swing_up(steps: usize) -> OptimalControl<Pendulum, InputMap, Effort> {
    OptimalControl::new(
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
    )
    .unwrap()
}

/// N = 120 reaches the reference's local optimum, cost 1.1192 (±1e-4: the reference's last
/// digit), with the boundary conditions met.
#[test]
fn swing_up_matches_the_reference_optimum_at_n120() {
    let problem = swing_up(120);
    let clock = Instant::now();
    let solution = problem.solve(&Midpoint, &SqpOptions::default()).unwrap();
    let elapsed = clock.elapsed();
    println!(
        "swing-up N = 120: {:?}, cost {:.6}, {} iterations, KKT {:.1e}, violation {:.1e}, {:.3} s",
        solution.status,
        solution.cost,
        solution.iterations,
        solution.kkt_residual,
        solution.constraint_violation,
        elapsed.as_secs_f64()
    );
    assert_eq!(solution.status, Status::Converged);
    assert!(
        (solution.cost - 1.1192).abs() <= 1e-4,
        "cost {}",
        solution.cost
    );
    assert!(solution.constraint_violation <= 1e-10);
    assert!(solution.kkt_residual <= 1e-8);
    assert!(solution.q[0][0].abs() <= 1e-12);
    assert!((solution.q[120][0] - PI).abs() <= 1e-10);
    assert!(solution.p[0][0].abs() <= 1e-10 && solution.p[120][0].abs() <= 1e-10);
}
