//! End-to-end: forces written in the momenta `p_<coordinate>` (`f_H`) run as `f_L = f_H ∘ FL`
//! ([MW01] §3.1), and the misuses are refused with a pointed message.

use crate::util::{assert_close, assert_rejected, column, run_ok};

/// For `L = ½ m ẋ² − ½ k x²`, `FL(x, ẋ) = m ẋ`, so the damping `−c p_x / m` is the damping
/// `−c ẋ`: the two runs (midpoint, 1500 steps, m = 2) agree to round-off (1e-14) at every stored
/// row, positions and momenta.
#[test]
fn momentum_damping_equals_velocity_damping_r12_oscillator() {
    let p = run_ok("damped_force_p.toml", &[]);
    let v = run_ok("damped_force_v.toml", &[]);
    assert_eq!(p.summary()["status"], "completed");
    let (tp, tv) = (p.trajectory(), v.trajectory());
    for name in ["q_x", "p_x"] {
        let (a, b) = (column(&tp, name), column(&tv, name));
        assert_eq!(a.len(), b.len());
        assert!(a.len() > 100);
        for (x, y) in a.iter().zip(b) {
            assert_close(*x, *y, 1e-14, name);
        }
    }
    // The damping acted: the amplitude A(t) = A₀ exp(−c t / 2m), A₀ = √(1 + m v₀²/k) ≈ 1.06,
    // is 0.13 over the last 10 rows (t ≥ 28).
    let x = column(&tp, "q_x");
    let tail = &x[x.len() - 10..];
    assert!(tail.iter().all(|x| x.abs() < 0.15), "{tail:?}");
}

#[test]
fn a_force_reads_momenta_of_existing_coordinates_only() {
    assert_rejected(
        "force_unknown_momentum.toml",
        &["[system] forces[0]", "p_y", "p_x", "^"],
    );
}

#[test]
fn forces_use_velocities_or_momenta_not_both() {
    assert_rejected(
        "force_velocity_and_momentum.toml",
        &[
            "both the velocity `y_dot` and the momentum `p_x`",
            "forces[1]",
            "^",
        ],
    );
}
