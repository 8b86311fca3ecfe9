//! An expression Lagrangian recognised as separable takes the fast paths of the catalog
//! systems, and they agree with its general path (AD of the expression, no declared structure)
//! to round-off; a builtin and the same Lagrangian typed as text agree too.

use marsden::mechanics::Structure;
use marsden::numerics::banded::Banded;
use marsden::systems::{Kepler, Pendulum};
use marsden::{Integrator, Lagrangian, Midpoint, Rule, State, Trapezoid};
use marsden_expr::{Program, Symbols};
use marsden_spec::model::{ExprLagrangian, slots};

/// `text` over `coordinates` (velocities `<name>_dot`, time `t`) with parameters.
fn lagrangian(text: &str, coordinates: &[&str], params: &[(&str, f64)]) -> ExprLagrangian {
    let names: Vec<String> = coordinates.iter().map(|c| c.to_string()).collect();
    let mut symbols = Symbols::with_inputs(slots::tangent_inputs(&names)).unwrap();
    for &(name, value) in params {
        symbols.add_constant(name, value).unwrap();
    }
    let program = Program::compile(text, &symbols).unwrap_or_else(|e| panic!("{e}"));
    ExprLagrangian::new(program, coordinates.len())
}

/// `steps` steps of `rule` from `(q0, p0)`; the final state and the explicit steps taken.
fn run<L: Lagrangian, R: Rule>(
    l: L,
    rule: R,
    start: (&[f64], &[f64]),
    steps: usize,
) -> (State, usize) {
    let mut integrator = Integrator::new(rule.discretize(l));
    let mut state = State {
        t: 0.0,
        q: start.0.to_vec(),
        p: start.1.to_vec(),
    };
    integrator
        .advance(&mut state, 0.01, steps)
        .unwrap_or_else(|e| panic!("{e}"));
    (state, integrator.statistics().explicit_steps)
}

fn assert_states_close(a: &State, b: &State, tol: f64, what: &str) {
    for (x, y) in a.q.iter().chain(&a.p).zip(b.q.iter().chain(&b.p)) {
        assert!(
            (x - y).abs() <= tol * x.abs().max(1.0),
            "{what}: {x} vs {y}"
        );
    }
}

/// The separable Lagrangians of the structure tests of `marsden-expr`, with a start.
fn separable_cases() -> Vec<(ExprLagrangian, Vec<f64>, Vec<f64>)> {
    let chain =
        "0.5*(a_dot^2 + b_dot^2 + c_dot^2) - 0.5*a^2 - 0.5*(b - a)^2 - 0.25*(c - b)^4 - 0.5*c^2";
    vec![
        (
            lagrangian(
                "0.5*(x_dot^2 + y_dot^2) + mu/sqrt(x^2 + y^2)",
                &["x", "y"],
                &[("mu", 1.0)],
            ),
            vec![0.4, 0.0],
            vec![0.0, 2.0],
        ),
        (
            lagrangian(
                "0.5*m*l^2*th_dot^2 + m*g*l*cos(th)",
                &["th"],
                &[("m", 1.0), ("l", 1.0), ("g", 1.0)],
            ),
            vec![1.5],
            vec![0.0],
        ),
        (
            lagrangian(
                "x_dot^2 + x_dot*y_dot + y_dot^2 - x^2 - y^2 - x^4",
                &["x", "y"],
                &[],
            ),
            vec![0.3, -0.2],
            vec![0.1, 0.5],
        ),
        (
            lagrangian("0.5*x_dot^2 - 0.5*x^2*(1 + 0.3*cos(2*t))", &["x"], &[]),
            vec![1.0],
            vec![0.0],
        ),
        (
            lagrangian(chain, &["a", "b", "c"], &[]),
            vec![0.1, -0.2, 0.3],
            vec![0.0, 0.1, 0.0],
        ),
    ]
}

#[test]
fn fast_paths_of_detected_lagrangians_equal_their_general_path() {
    for (l, q0, p0) in separable_cases() {
        let text = l.program().text().to_owned();
        assert!(
            matches!(l.structure(), Structure::Separable { .. }),
            "{text}"
        );
        let general = l.clone().without_structure();
        assert_eq!(general.structure(), Structure::General);
        let start = (q0.as_slice(), p0.as_slice());
        // Trapezoid: explicit Störmer–Verlet against the general Newton step.
        let (fast, explicit) = run(&l, Trapezoid, start, 300);
        let (slow, none) = run(&general, Trapezoid, start, 300);
        assert_eq!((explicit, none), (300, 0), "{text}");
        assert_states_close(&fast, &slow, 1e-10, &text);
        // Midpoint: the separable α-rule Newton against the general Newton step.
        let (fast, _) = run(&l, Midpoint, start, 300);
        let (slow, _) = run(&general, Midpoint, start, 300);
        assert_states_close(&fast, &slow, 1e-10, &text);
    }
}

#[test]
fn kepler_and_pendulum_typed_as_text_equal_the_catalog() {
    let kepler = lagrangian(
        "0.5*(x_dot^2 + y_dot^2) + mu/sqrt(x^2 + y^2)",
        &["x", "y"],
        &[("mu", 1.0)],
    );
    // e = 0.6: q0 = (0.4, 0), p0 = (0, 2).
    let start: (&[f64], &[f64]) = (&[0.4, 0.0], &[0.0, 2.0]);
    let (a, _) = run(&kepler, Trapezoid, start, 2000);
    let (b, _) = run(Kepler::default(), Trapezoid, start, 2000);
    assert_states_close(&a, &b, 1e-10, "Kepler trapezoid");
    let pendulum = "0.5*m*l^2*th_dot^2 + m*g*l*cos(th)";
    let params = [("m", 1.0), ("l", 1.0), ("g", 1.0)];
    let p = Pendulum {
        m: 1.0,
        l: 1.0,
        g: 1.0,
    };
    let start: (&[f64], &[f64]) = (&[1.5], &[0.0]);
    let (a, _) = run(
        lagrangian(pendulum, &["th"], &params),
        Midpoint,
        start,
        2000,
    );
    let (b, _) = run(p, Midpoint, start, 2000);
    assert_states_close(&a, &b, 1e-10, "pendulum midpoint");
}

#[test]
fn non_separable_lagrangians_keep_the_general_path() {
    let cases = [
        ("0.5*(1 + x^2)*x_dot^2 - x^2", &["x"][..]),
        ("0.5*x_dot^2 + x*x_dot - x^2", &["x"][..]),
        (
            "0.5*(x_dot^2 + y_dot^2) + x*y_dot - y*x_dot",
            &["x", "y"][..],
        ),
        ("0.5*exp(t)*x_dot^2 - x^2", &["x"][..]),
    ];
    for (text, coordinates) in cases {
        let l = lagrangian(text, coordinates, &[]);
        assert_eq!(l.structure(), Structure::General, "{text}");
        let q0 = vec![0.2; coordinates.len()];
        let (_, explicit) = run(&l, Trapezoid, (&q0, &q0), 10);
        assert_eq!(explicit, 0, "{text}");
    }
}

/// The bits of a state.
fn bits(s: &State) -> Vec<u64> {
    std::iter::once(s.t)
        .chain(s.q.iter().copied())
        .chain(s.p.iter().copied())
        .map(f64::to_bits)
        .collect()
}

/// A chain of `n` masses, anharmonic springs and a time-dependent pull: ∇²V tridiagonal.
fn banded_chain(n: usize) -> ExprLagrangian {
    let names: Vec<String> = (0..n).map(|i| format!("q{i}")).collect();
    let kinetic: Vec<String> = names.iter().map(|q| format!("0.5*{q}_dot^2")).collect();
    let springs: Vec<String> = (1..n)
        .map(|i| format!("0.5*(q{i} - q{})^2 + 0.25*(q{i} - q{})^4", i - 1, i - 1))
        .collect();
    let text = format!(
        "{} - 0.5*q0^2 - {} - 0.5*q{}^2 + 0.1*sin(t)*q0",
        kinetic.join(" + "),
        springs.join(" - "),
        n - 1
    );
    let coordinates: Vec<&str> = names.iter().map(String::as_str).collect();
    lagrangian(&text, &coordinates, &[])
}

/// Native code for the tapes (default `jit` feature) and their interpreter (what
/// `MARSDEN_JIT=0` selects) give the same trajectories bit for bit: Kepler typed as text (e = 0.6,
/// reference case R10; explicit Störmer–Verlet through ∇V, and midpoint through ∇²V) and a banded
/// chain (midpoint's banded Newton through ∇²V).
#[test]
fn native_and_interpreted_tapes_give_identical_trajectories() {
    let kepler = lagrangian(
        "0.5*(x_dot^2 + y_dot^2) + mu/sqrt(x^2 + y^2)",
        &["x", "y"],
        &[("mu", 1.0)],
    );
    let chain = banded_chain(12);
    assert_eq!(chain.potential_bandwidth(), Some(1));
    let q0: Vec<f64> = (0..12).map(|i| 0.1 * (f64::from(i) * 0.7).sin()).collect();
    let p0: Vec<f64> = (0..12).map(|i| 0.05 * f64::from(i % 3)).collect();
    let cases = [(kepler, vec![0.4, 0.0], vec![0.0, 2.0]), (chain, q0, p0)];
    for (l, q0, p0) in cases {
        let text = l.program().text().to_owned();
        #[cfg(all(feature = "jit", any(target_arch = "x86_64", target_arch = "aarch64")))]
        assert!(l.gradient_is_native(), "{text}: not compiled");
        let interpreted = l.clone().interpreted();
        assert!(!interpreted.gradient_is_native());
        let start = (q0.as_slice(), p0.as_slice());
        let (a, explicit) = run(&l, Trapezoid, start, 2000);
        let (b, _) = run(&interpreted, Trapezoid, start, 2000);
        assert_eq!(explicit, 2000, "{text}");
        assert_eq!(bits(&a), bits(&b), "{text}: trapezoid");
        let (a, _) = run(&l, Midpoint, start, 500);
        let (b, _) = run(&interpreted, Midpoint, start, 500);
        assert_eq!(bits(&a), bits(&b), "{text}: midpoint");
        // ∇²V itself, entry by entry.
        let n = l.dof();
        let band = l.potential_bandwidth().unwrap_or(n - 1);
        let (mut h1, mut h2) = (Banded::new(n, band), Banded::new(n, band));
        l.potential_hessian(0.3, &a.q, &mut h1);
        interpreted.potential_hessian(0.3, &a.q, &mut h2);
        for i in 0..n {
            for j in h1.columns(i) {
                assert_eq!(
                    h1.get(i, j).to_bits(),
                    h2.get(i, j).to_bits(),
                    "{text}: ∇²V"
                );
            }
        }
    }
}

/// The compiled `∇²V` handed to the small separable kernels as its packed upper triangle
/// (`Lagrangian::potential_hessian_packed`) has exactly the entries `potential_hessian` writes
/// into the band storage, bit for bit, when its outputs are the whole triangle; a Hessian with
/// an entry identically zero, or the interpreted tapes, decline (`false`), and the kernels then
/// take the band storage. The pendulum typed as text runs the same either way (midpoint).
#[test]
fn packed_hessian_holds_the_band_storages_entries() {
    let cases = [
        ("0.5*th_dot^2 + 9.81*cos(th)", vec!["th"], true),
        (
            "0.5*(x_dot^2 + y_dot^2) + 1/sqrt(x^2 + y^2)",
            vec!["x", "y"],
            true,
        ),
        (
            "0.5*(x_dot^2 + 2*y_dot^2) - x^2*y - exp(t*x)*y^3",
            vec!["x", "y"],
            true,
        ),
        (
            "0.5*(a_dot^2 + b_dot^2 + c_dot^2) - a*b*c - cos(a + c) - b^2*c^2",
            vec!["a", "b", "c"],
            true,
        ),
        // ∂²V/∂x∂y ≡ 0: no packed triangle.
        (
            "0.5*(x_dot^2 + y_dot^2) - x^4 - cos(y)",
            vec!["x", "y"],
            false,
        ),
    ];
    for (text, names, full) in cases {
        let l = lagrangian(text, &names, &[]);
        let n = l.dof();
        let q: Vec<f64> = (0..n).map(|i| 0.3 + 0.2 * i as f64).collect();
        let mut band = Banded::new(n, n - 1);
        l.potential_hessian(0.7, &q, &mut band);
        let mut packed = vec![f64::NAN; n * (n + 1) / 2];
        let jit = cfg!(all(
            feature = "jit",
            any(target_arch = "x86_64", target_arch = "aarch64")
        ));
        let given = l.potential_hessian_packed(0.7, &q, &mut packed);
        assert_eq!(given, full && jit, "{text}");
        if given {
            let triangle = (0..n).flat_map(|i| (i..n).map(move |j| (i, j)));
            for ((i, j), value) in triangle.zip(&packed) {
                assert_eq!(
                    value.to_bits(),
                    band.get(i, j).to_bits(),
                    "{text}: ({i}, {j})"
                );
            }
        }
        let interpreted = l.clone().interpreted();
        assert!(
            !interpreted.potential_hessian_packed(0.7, &q, &mut packed),
            "{text}"
        );
    }
    let pendulum = lagrangian("0.5*th_dot^2 + 9.81*cos(th)", &["th"], &[]);
    let start = ([1.2].as_slice(), [0.3].as_slice());
    let (a, _) = run(&pendulum, Midpoint, start, 2000);
    let (b, _) = run(pendulum.clone().interpreted(), Midpoint, start, 2000);
    assert_eq!(bits(&a), bits(&b), "pendulum: packed and band storage");
}

/// `steps` steps of the trapezoid rule in runs of `pieces` steps (`advance`), or one
/// `Integrator::step` at a time when `pieces` is 0: the state, the outcome's message (empty
/// when every step was taken) and the statistics' steps, explicit steps and gradients.
fn trapezoid_run(
    l: &ExprLagrangian,
    start: (&[f64], &[f64]),
    h: f64,
    steps: usize,
    pieces: usize,
) -> (State, String, [usize; 3]) {
    let mut integrator = Integrator::new(Trapezoid.discretize(l));
    let mut state = State {
        t: 0.0,
        q: start.0.to_vec(),
        p: start.1.to_vec(),
    };
    let mut outcome = String::new();
    let mut done = 0;
    while done < steps && outcome.is_empty() {
        let take = if pieces == 0 {
            1
        } else {
            pieces.min(steps - done)
        };
        let result = if pieces == 0 {
            integrator.step(&mut state, h).map(|_| ())
        } else {
            integrator.advance(&mut state, h, take).map(|_| ())
        };
        if let Err(e) = result {
            outcome = e.to_string();
        }
        done += take;
    }
    let s = integrator.statistics();
    let counts = [s.steps, s.explicit_steps, s.potential_gradients];
    (state, outcome, counts)
}

/// The trapezoid rule's run compiled with ∇V inside its loop (`CompiledVerlet`, the default
/// with the `jit` feature) takes exactly the generic loop's steps: bit for bit the same states
/// as the interpreted tapes' run (and for an autonomous `V` as runs in pieces and single
/// steps), the same statistics, the same stop at the first non-finite state. Cases: Kepler
/// typed as text (e = 0.6, reference case R10), a time-dependent 12-mass chain (more coordinates
/// than the generic loop's fixed-size arrays: no kernel), unequal masses with `sin`, `exp`,
/// `atan2`, a non-integer power and a time-dependent force inside the loop, and a runaway
/// potential `V = −exp(x²)` whose run overflows.
#[test]
fn compiled_verlet_run_takes_the_generic_loops_steps_bit_for_bit() {
    let masses = lagrangian(
        "0.5*(2*a_dot^2 + 3*b_dot^2 + 0.5*c_dot^2) + cos(a - b) - exp(0.1*c) \
         - 0.2*atan2(b, 1 + a^2) - (1 + c^2)^0.75 + 0.3*sin(2*t)*a",
        &["a", "b", "c"],
        &[],
    );
    let runaway = lagrangian("0.5*x_dot^2 + exp(x^2)", &["x"], &[]);
    let chain_q: Vec<f64> = (0..12).map(|i| 0.1 * (f64::from(i) * 0.7).sin()).collect();
    let chain_p: Vec<f64> = (0..12).map(|i| 0.05 * f64::from(i % 3)).collect();
    let kepler = lagrangian(
        "0.5*(x_dot^2 + y_dot^2) + mu/sqrt(x^2 + y^2)",
        &["x", "y"],
        &[("mu", 1.0)],
    );
    let cases = [
        (kepler, vec![0.4, 0.0], vec![0.0, 2.0], 0.01),
        (banded_chain(12), chain_q, chain_p, 0.01),
        (masses, vec![0.3, -0.2, 0.5], vec![0.1, 0.4, -0.3], 0.02),
        (runaway, vec![1.0], vec![1.0], 0.05),
    ];
    for (l, q0, p0, h) in cases {
        let text = l.program().text().to_owned();
        #[cfg(all(feature = "jit", any(target_arch = "x86_64", target_arch = "aarch64")))]
        assert!(l.verlet_kernel().is_some(), "{text}: no compiled run");
        let interpreted = l.clone().interpreted();
        assert!(interpreted.verlet_kernel().is_none());
        let start = (q0.as_slice(), p0.as_slice());
        let compiled = trapezoid_run(&l, start, h, 2000, 2000);
        let reference = trapezoid_run(&interpreted, start, h, 2000, 2000);
        let in_pieces = trapezoid_run(&l, start, h, 2000, 700);
        let single = trapezoid_run(&l, start, h, 2000, 0);
        // A run in pieces restarts its grid at each piece's `t`: the same numbers only
        // when `V` does not depend on time.
        let autonomous = !text.contains("(t)") && !text.contains("*t");
        let mut others = vec![(&reference, "interpreted")];
        if autonomous {
            others.push((&in_pieces, "in pieces"));
        }
        for (other, what) in others {
            assert_eq!(bits(&compiled.0), bits(&other.0), "{text}: {what}");
            assert_eq!(compiled.1, other.1, "{text}: {what}");
            assert_eq!(compiled.2, reference.2, "{text}: {what}: statistics");
        }
        // Single steps accumulate `t + h`: for an autonomous `V` the same positions and
        // momenta, not the same `t`.
        let (a, b) = (bits(&compiled.0), bits(&single.0));
        assert!(!autonomous || a[1..] == b[1..], "{text}: single steps");
        assert_eq!(compiled.1.is_empty(), single.1.is_empty(), "{text}");
        let runs_away = text.contains("exp(x^2)");
        assert_eq!(compiled.1.is_empty(), !runs_away, "{text}: {}", compiled.1);
        assert!(
            compiled
                .0
                .q
                .iter()
                .chain(&compiled.0.p)
                .all(|x| x.is_finite())
        );
    }
}

/// The double pendulum: `M(q)` depends on the angle difference, so no separable form.
const DOUBLE_PENDULUM: &str = "0.5*(m1 + m2)*l1^2*a_dot^2 + 0.5*m2*l2^2*b_dot^2 \
     + m2*l1*l2*a_dot*b_dot*cos(a - b) + (m1 + m2)*g*l1*cos(a) + m2*g*l2*cos(b)";

/// A Lagrangian without the separable form, of up to four degrees of freedom, takes the small
/// step kernel with its dual numbers composed from the native value, gradient and Hessian of
/// `L` (`marsden::numerics::dual::compose`): the run equals the interpreted program's and the
/// catalog's double pendulum to round-off, and so do the general path's (no small kernel)
/// and a time-dependent Lagrangian's.
#[test]
fn lagrangians_without_the_separable_form_compose_their_duals_from_native_taylor_data() {
    use marsden::systems::DoublePendulum;
    let params = [
        ("m1", 1.0),
        ("m2", 1.3),
        ("l1", 1.0),
        ("l2", 0.8),
        ("g", 9.81),
    ];
    let text = lagrangian(DOUBLE_PENDULUM, &["a", "b"], &params);
    assert_eq!(text.structure(), Structure::General);
    assert!(text.jet_is_native(), "the jet is compiled on this machine");
    let interpreted = text.clone().interpreted();
    assert!(!interpreted.jet_is_native());
    let builtin = DoublePendulum {
        m1: 1.0,
        m2: 1.3,
        l1: 1.0,
        l2: 0.8,
        g: 9.81,
    };
    // Two time units from a chaotic start (longer, round-off grows past any tolerance).
    let start: (&[f64], &[f64]) = (&[1.5, 2.0], &[0.3, -0.2]);
    let (a, _) = run(&text, Midpoint, start, 200);
    let (b, _) = run(&interpreted, Midpoint, start, 200);
    let (c, _) = run(builtin, Midpoint, start, 200);
    assert_states_close(&a, &b, 1e-11, "composed against interpreted");
    assert_states_close(&a, &c, 1e-11, "composed against the catalog");
    assert!(
        bits(&a) != bits(&b),
        "the composed duals are another evaluation (else this test shows nothing)"
    );
    // A time-dependent, velocity-coupled Lagrangian of three coordinates (t among the inputs).
    let driven = "0.5*(1 + x^2)*x_dot^2 + 0.5*y_dot^2 + 0.5*z_dot^2 + x*y_dot - y*x_dot \
                  - 0.5*(x^2 + y^2 + z^2) + z*sin(2*t) - 0.1*x^2*y*z";
    let l = lagrangian(driven, &["x", "y", "z"], &[]);
    assert!(l.jet_is_native());
    let start: (&[f64], &[f64]) = (&[0.3, -0.2, 0.5], &[0.1, 0.4, -0.3]);
    let (a, _) = run(&l, Midpoint, start, 500);
    let (b, _) = run(l.clone().interpreted(), Midpoint, start, 500);
    assert_states_close(
        &a,
        &b,
        1e-11,
        "time-dependent, composed against interpreted",
    );
    assert!(bits(&a) != bits(&b), "the composed duals took these steps");
}
