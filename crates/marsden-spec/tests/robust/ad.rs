//! Terms whose derivative is `0·∞` at the evaluation point must not invent a NaN: `0*sqrt(t)`
//! and `t^2.5` at `t = 0` leave the motion of `L = ½ẋ² − x²` unchanged.

use marsden_spec::{Controls, RunSpec, RunStatus, Store, execute};

fn run(lagrangian: &str, method: &str) -> marsden_spec::Summary {
    let text = format!(
        "[system]\ncoordinates = [\"x\"]\nlagrangian = \"{lagrangian}\"\n\
         [initial]\nq = [1]\nv = [0]\n[integrator]\nmethod = \"{method}\"\nh = 0.1\nsteps = 10\n\
         [output]\nplots = false\n"
    );
    let spec = RunSpec::from_toml_str(&text, "p.toml").unwrap();
    execute(&spec, Store::Memory, &Controls::none())
        .unwrap()
        .summary
}

#[test]
fn terms_with_infinite_derivative_times_zero_do_not_make_nan() {
    let plain = "0.5*x_dot^2 - x^2";
    for method in ["trapezoid", "alpha-0", "lobatto-3"] {
        let reference = run(plain, method);
        assert_eq!(reference.status, RunStatus::Completed);
        for extra in ["0*sqrt(t)", "0*t^2.5"] {
            let l = format!("{plain} + {extra}");
            let s = run(&l, method);
            assert_eq!(
                s.status,
                RunStatus::Completed,
                "{l} with {method}: {:?}",
                s.error
            );
            assert_eq!(
                s.final_state.q, reference.final_state.q,
                "{l} with {method}"
            );
        }
        // t^2.5 itself changes the energy but not the motion (no x in it): its derivatives
        // at t = 0 vanish.
        let l = format!("{plain} + t^2.5");
        let s = run(&l, method);
        assert_eq!(
            s.status,
            RunStatus::Completed,
            "{l} with {method}: {:?}",
            s.error
        );
        let dq = (s.final_state.q[0] - reference.final_state.q[0]).abs();
        assert!(dq < 1e-12, "{l} with {method}: Δq = {dq:e}");
    }
}

/// `(x^2)^1.5` is `|x|³`: a run through x = 0 with every rule completes and equals the same
/// Lagrangian written with `abs(x)^3` bit for bit (the chain rule of `(x²)^1.5` would form
/// `u^(−1/2)·(u′)² = ∞·0` at x = 0 in the second derivative).
#[test]
fn a_power_of_a_square_has_finite_derivatives_at_zero() {
    let run_from_zero = |l: &str, method: &str| {
        let text = format!(
            "[system]\ncoordinates = [\"x\"]\nlagrangian = \"{l}\"\n\
             [initial]\nq = [0]\nv = [1]\n[integrator]\nmethod = \"{method}\"\nh = 0.1\n\
             steps = 40\n[output]\nplots = false\n"
        );
        let spec = RunSpec::from_toml_str(&text, "p.toml").unwrap();
        execute(&spec, Store::Memory, &Controls::none())
            .unwrap()
            .summary
    };
    for method in ["midpoint", "trapezoid", "lobatto-3", "gauss-2"] {
        let s = run_from_zero("0.5*x_dot^2 - 0.5*x^2 - 0.1*(x^2)^1.5", method);
        assert_eq!(s.status, RunStatus::Completed, "{method}: {:?}", s.error);
        let a = run_from_zero("0.5*x_dot^2 - 0.5*x^2 - 0.1*abs(x)^3", method);
        assert_eq!(s.final_state.q, a.final_state.q, "{method}");
        assert!(s.final_state.q[0].is_finite());
    }
}
