//! [`CompiledVerlet`] against the velocity Störmer–Verlet loop written in Rust around the tape
//! interpreter (the loop of `marsden::separable::explicit` for a diagonal mass): **bit for bit**
//! equal states and gradients, the same steps done, the same stop at the first non-finite state.

use marsden_expr::Tape;
use marsden_jit::{CompiledVerlet, JitError, VerletGrid};

use super::agreement::{reference_forms, separable};

/// A run's final `(q, p, ∇V)` and the steps done.
#[derive(Debug, PartialEq)]
struct Run {
    q: Vec<u64>,
    p: Vec<u64>,
    g: Vec<u64>,
    done: usize,
}

fn bits(x: &[f64]) -> Vec<u64> {
    x.iter().map(|v| v.to_bits()).collect()
}

/// The reference loop: `p½ = p − c g`, `q' = q + d ⊙ p½`, `g' = ∇V(t₀ + k h, q')`,
/// `p' = p½ − c g'`, stopping before a non-finite `(q', p')`.
fn interpreted(tape: &Tape, t0: f64, h: f64, steps: usize, d: &[f64], start: [&[f64]; 3]) -> Run {
    let [mut q, mut p, mut g] = start.map(<[f64]>::to_vec);
    let n = q.len();
    let c = 0.5 * h;
    let (mut regs, mut g_next) = (Vec::new(), vec![0.0; n]);
    let mut done = 0;
    for k in 1..=steps {
        let p_half: Vec<f64> = (0..n).map(|i| p[i] - c * g[i]).collect();
        let q_next: Vec<f64> = (0..n).map(|i| q[i] + d[i] * p_half[i]).collect();
        let mut x = q_next.clone();
        x.push(t0 + k as f64 * h);
        tape.eval_into(&x, &mut regs, &mut g_next);
        let p_next: Vec<f64> = (0..n).map(|i| p_half[i] - c * g_next[i]).collect();
        if !q_next.iter().chain(&p_next).all(|v| v.is_finite()) {
            break;
        }
        (q, p) = (q_next, p_next);
        g.copy_from_slice(&g_next);
        done = k;
    }
    Run {
        q: bits(&q),
        p: bits(&p),
        g: bits(&g),
        done,
    }
}

fn compiled(
    kernel: &CompiledVerlet,
    grid: (f64, f64),
    steps: usize,
    d: &[f64],
    start: [&[f64]; 3],
) -> Run {
    let [mut q, mut p, mut g] = start.map(<[f64]>::to_vec);
    let grid = VerletGrid {
        t0: grid.0,
        h: grid.1,
        steps,
    };
    let done = kernel.run(grid, d, &mut q, &mut p, &mut g);
    Run {
        q: bits(&q),
        p: bits(&p),
        g: bits(&g),
        done,
    }
}

/// Both runs from `(q, p)` (the gradient at the start by the interpreter), asserted equal.
fn assert_same_run(
    tape: &Tape,
    grid: (f64, f64),
    steps: usize,
    d: &[f64],
    q: &[f64],
    p: &[f64],
    what: &str,
) -> usize {
    let mut g = vec![0.0; q.len()];
    let mut x = q.to_vec();
    x.push(grid.0);
    tape.eval_into(&x, &mut Vec::new(), &mut g);
    let kernel = CompiledVerlet::compile(tape, q.len()).unwrap();
    assert_eq!(kernel.dof(), q.len());
    let expected = interpreted(tape, grid.0, grid.1, steps, d, [q, p, &g]);
    let got = compiled(&kernel, grid, steps, d, [q, p, &g]);
    assert_eq!(got, expected, "{what}");
    got.done
}

/// Kepler (e = 0.6 from pericentre, reference case R10), the pendulum and a coupled double
/// pendulum, 3000 steps each.
#[test]
fn reference_potentials_run_as_the_interpreted_loop() {
    let starts: [(&[f64], &[f64]); 3] = [
        (&[0.4, 0.0], &[0.0, 2.0]),
        (&[1.5], &[0.0]),
        (&[1.5, 2.0], &[0.0, 0.3]),
    ];
    for ((name, form), start) in reference_forms().into_iter().zip(starts) {
        let tape = form.gradient().unwrap();
        let d = vec![0.01; start.0.len()];
        let done = assert_same_run(tape, (0.0, 0.01), 3000, &d, start.0, start.1, name);
        assert_eq!(done, 3000, "{name}");
    }
}

/// Unequal masses (`d = h/m` per coordinate), a time-dependent force, a start time other than
/// zero, calls of `exp`, `atan2` and a non-integer power inside the loop, and zero steps.
#[test]
fn time_dependent_potential_with_unequal_masses_and_calls() {
    let form = separable(
        "0.5*(2*a_dot^2 + 3*b_dot^2 + 0.5*c_dot^2) + cos(a - b) - exp(0.1*c) \
         - 0.2*atan2(b, 1 + a^2) - (1 + c^2)^0.75 + 0.3*sin(2*t)*a",
        &["a", "b", "c"],
        &[],
    );
    let tape = form.gradient().unwrap();
    let h = 0.02;
    let d = [h / 2.0, h / 3.0, h / 0.5];
    let start: (&[f64], &[f64]) = (&[0.3, -0.2, 0.5], &[0.1, 0.4, -0.3]);
    assert_eq!(
        assert_same_run(tape, (1.7, h), 2500, &d, start.0, start.1, "3 dof"),
        2500
    );
    assert_eq!(
        assert_same_run(tape, (1.7, h), 0, &d, start.0, start.1, "no steps"),
        0
    );
}

/// `V = −exp(x²)` drives `x` to infinity: both runs stop before the same step, at the same
/// (finite) state.
#[test]
fn runaway_run_stops_before_the_first_non_finite_state() {
    let form = separable("0.5*x_dot^2 + exp(x^2)", &["x"], &[]);
    let tape = form.gradient().unwrap();
    let done = assert_same_run(tape, (0.0, 0.05), 1000, &[0.05], &[1.0], &[1.0], "runaway");
    assert!(done > 0 && done < 1000, "{done}");
}

/// A tape without one output per coordinate, or reading more than `[q, t]`, is refused.
#[test]
fn mismatched_gradient_tapes_are_refused() {
    let form = separable("0.5*(x_dot^2 + y_dot^2) - x^2*y", &["x", "y"], &[]);
    let tape = form.gradient().unwrap();
    assert_eq!(
        CompiledVerlet::compile(tape, 3).err(),
        Some(JitError::Outputs { outputs: 2, dof: 3 })
    );
    assert!(matches!(
        CompiledVerlet::compile(tape, 0).err(),
        Some(JitError::Inputs { .. })
    ));
}
