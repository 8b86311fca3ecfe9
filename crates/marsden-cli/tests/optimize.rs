//! `marsden optimize`: the double integrator against its closed form ([BH75] §2: rest to rest
//! from 0 to 1 in T = 1 with cost ∫ ½u², optimum u(t) = 6 − 12t, cost 6), the convergence order
//! of the discrete optimum ([OJM11] §4), the forced discrete Euler–Lagrange equations checked
//! on the written files, the pendulum swing-up against an independent solver, the summary, and
//! every bad input.

use marsden::numerics::dense::max_or_nan;
use std::path::{Path, PathBuf};

use crate::util::{Run, column, marsden, repo_root};

/// The double integrator `L = ½ẋ²`, `f = u`, `C = ½u²`, rest to rest from 0 to 1 in T = 1.
const DOUBLE_INTEGRATOR: &str = r#"[system]
coordinates = ["x"]
lagrangian = "0.5*x_dot^2"
controls = ["u"]
forces = ["u"]
[[system.symmetry]]
translation = "x"
[optimal_control]
cost = "0.5*u^2"
t_end = 1.0
steps = 20
method = "midpoint"
start = { q = [0.0], v = [0.0] }
end = { q = [1.0], v = [0.0] }
[output]
plots = false
"#;

/// Writes `text` to a problem file in a fresh directory (kept alive by the returned guard).
fn problem(text: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("problem.toml");
    std::fs::write(&path, text).unwrap();
    (dir, path)
}

fn optimize(text: &str, extra: &[&str]) -> (tempfile::TempDir, Run) {
    let (dir, path) = problem(text);
    let run = marsden("optimize", &path, extra);
    (dir, run)
}

fn table(out: &Path, name: &str) -> marsden_io::Table {
    marsden_io::read_csv(out.join(name)).unwrap()
}

/// Least-squares slope of `log e` against `log h`.
fn slope(h: &[f64], e: &[f64]) -> f64 {
    let x: Vec<f64> = h.iter().map(|h| h.ln()).collect();
    let y: Vec<f64> = e.iter().map(|e| e.ln()).collect();
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(&y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = x.iter().map(|a| (a - mx).powi(2)).sum();
    sxy / sxx
}

/// [BH75]: the continuous optimum of the double integrator costs 6; the discrete optimum of
/// the midpoint and trapezoid transcriptions converges to it at order 2 ([OJM11] §4), the
/// slope fitted over N = 10, 20, 40; the controls approach u(t) = 6 − 12t.
#[test]
fn double_integrator_cost_converges_to_six_at_order_two() {
    for method in ["midpoint", "trapezoid"] {
        let text = DOUBLE_INTEGRATOR.replace("\"midpoint\"", &format!("\"{method}\""));
        let mut errors = Vec::new();
        let mut steps = Vec::new();
        for n in [10, 20, 40] {
            let (_dir, run) = optimize(&text, &["--steps", &n.to_string(), "--quiet"]);
            assert_eq!(run.code, 0, "{method} N = {n}: {}", run.stderr);
            let s = run.summary();
            assert_eq!(s["optimal_control"]["status"], "converged");
            let cost = s["optimal_control"]["cost"].as_f64().unwrap();
            errors.push((cost - 6.0).abs());
            steps.push(1.0 / n as f64);
            let controls = table(&run.out, "controls.csv");
            let (t, u) = (column(&controls, "t"), column(&controls, "u"));
            let h = 1.0 / n as f64;
            let worst = t
                .iter()
                .zip(u)
                .map(|(t, u)| (u - (6.0 - 12.0 * (t + h / 2.0))).abs())
                .fold(0.0, marsden::numerics::dense::max_or_nan);
            println!("{method} N = {n}: cost {cost:.12}, max |u_k − u(t_k+½)| = {worst:.3e}");
            assert!(worst < 10.0 * h * h, "{method} N = {n}: {worst}");
        }
        let p = slope(&steps, &errors);
        println!("{method}: errors {errors:?}, fitted order {p:.3}");
        assert!((p - 2.0).abs() < 0.2, "{method}: order {p}");
    }
}

/// The written trajectory and controls satisfy the forced discrete Euler–Lagrange equations of
/// the midpoint rule, written out by hand for `L = ½ẋ²`, `f = u` ([MW01] §3.2,
/// `f_d^± = (h/2) u_k`): `p_k = (x_k − x_{k−1})/h + (h/2)u_{k−1} = (x_{k+1} − x_k)/h − (h/2)u_k`,
/// to the solver's tolerance; the core integrator replays them (summary `replay_defect`), and
/// the momentum of the translation changes by the work of the controls (forced Noether).
#[test]
fn controls_fed_back_reproduce_the_trajectory() {
    let (_dir, run) = optimize(DOUBLE_INTEGRATOR, &["--quiet"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let trajectory = table(&run.out, "trajectory.csv");
    let controls = table(&run.out, "controls.csv");
    let (x, p) = (column(&trajectory, "q_x"), column(&trajectory, "p_x"));
    let u = column(&controls, "u");
    let h = 1.0 / 20.0;
    assert_eq!((x.len(), u.len()), (21, 20));
    let mut worst: f64 = 0.0;
    for k in 0..20 {
        let right = (x[k + 1] - x[k]) / h - h / 2.0 * u[k];
        let left = (x[k + 1] - x[k]) / h + h / 2.0 * u[k];
        worst = max_or_nan(
            max_or_nan(worst, (p[k] - right).abs()),
            (p[k + 1] - left).abs(),
        );
    }
    println!("forced DEL residual on the files: {worst:.3e}");
    assert!(worst < 1e-8, "{worst}");
    assert!((x[0], x[20]) == (0.0, 1.0) || (x[20] - 1.0).abs() < 1e-10);
    let s = run.summary();
    let replay = s["optimal_control"]["replay_defect"].as_f64().unwrap();
    assert!(replay < 1e-9, "replay defect {replay}");
    // Rest to rest: p_x changes by 0, so the impulse Σ h u_k of the controls is 0 as well.
    let noether = &s["optimal_control"]["noether_balance"]["Px"];
    assert!(noether["max_defect"].as_f64().unwrap() < 1e-9, "{noether}");
    assert!(
        noether["total_impulse"].as_f64().unwrap().abs() < 1e-9,
        "{noether}"
    );
    assert_eq!(noether["steps"], 20);
}

/// The swing-up example at N = 120 reaches the local optimum an independent solver (CasADi +
/// IPOPT, same transcription and first iterate) found: cost 1.1192 (four digits given).
#[test]
fn pendulum_swing_up_matches_the_independent_optimum() {
    let file = repo_root().join("examples/pendulum_swing_up.toml");
    let run = marsden("optimize", &file, &["--steps", "120"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(run.stdout.contains("converged"), "{}", run.stdout);
    let s = run.summary();
    let oc = &s["optimal_control"];
    let cost = oc["cost"].as_f64().unwrap();
    assert!((cost - 1.1192).abs() < 1e-4, "cost {cost}");
    assert!(oc["kkt_residual"].as_f64().unwrap() <= 1e-8);
    assert!(oc["constraint_violation"].as_f64().unwrap() <= 1e-10);
    assert!(oc["noether_balance"].is_null(), "no symmetry declared");
    assert_eq!(
        s["history"].as_array().unwrap().len(),
        oc["iterations"].as_u64().unwrap() as usize
    );
    for f in [
        "controls.png",
        "time_series.png",
        "phase_portrait.png",
        "convergence.png",
    ] {
        assert!(run.out.join(f).is_file(), "{f}");
    }
}

/// Too few iterations: status "iteration limit", exit 1, and the last iterate still written.
#[test]
fn iteration_limit_exits_one_and_writes_the_last_iterate() {
    let text = std::fs::read_to_string(repo_root().join("examples/pendulum_swing_up.toml"))
        .unwrap()
        .replace("steps = 100", "steps = 100\nmax_iterations = 2");
    let (_dir, run) = optimize(&text, &["--quiet"]);
    assert_eq!(run.code, 1, "{}", run.stderr);
    assert!(
        run.stderr.contains("status \"iteration limit\""),
        "{}",
        run.stderr
    );
    let s = run.summary();
    let oc = &s["optimal_control"];
    assert_eq!(oc["status"], "iteration limit");
    assert_eq!(oc["last_iterate"], true);
    assert_eq!(oc["iterations"], 2);
    assert!(
        oc["kkt_residual"].as_f64().unwrap() > 1e-8,
        "not converged: {oc}"
    );
    let trajectory = table(&run.out, "trajectory.csv");
    assert_eq!(column(&trajectory, "q_theta").len(), 101);
    assert_eq!(column(&table(&run.out, "controls.csv"), "u").len(), 100);
}

/// Each bad input: exit 2, the message with its caret, nothing written.
#[test]
fn bad_inputs_exit_two_and_write_nothing() {
    let cases = [
        (
            ("controls = [\"u\"]", "controls = [\"u\", \"w\"]"),
            "control `w` is not used by any force",
        ),
        (
            ("cost = \"0.5*u^2\"", "cost = \"0.5*u^2 + k*x\""),
            "in [optimal_control] cost: unknown name `k`",
        ),
        (
            (
                "end = { q = [1.0], v = [0.0] }",
                "end = { q = [1.0], v = [0.0], p = [0.0] }",
            ),
            "`end` gives both `v` and `p`",
        ),
        (
            (
                "[output]",
                "[optimal_control.bounds]\nu = [1.0, -1.0]\n[output]",
            ),
            "bounds on `u`: the lower bound 1 is above the upper bound -1",
        ),
        (
            ("method = \"midpoint\"", "method = \"exact\""),
            "`exact` cannot be used for optimal control",
        ),
        (
            ("[output]", "path = [\"x - 0.8\", \"u - k\"]\n[output]"),
            "in [optimal_control] path[1]: unknown name `k`",
        ),
        (("[output]", "path = []\n[output]"), "`path` is empty"),
    ];
    for ((from, to), message) in cases {
        assert!(DOUBLE_INTEGRATOR.contains(from), "{from}");
        let (_dir, run) = optimize(&DOUBLE_INTEGRATOR.replacen(from, to, 1), &[]);
        assert_eq!(run.code, 2, "{message}: {}", run.stderr);
        assert!(run.stderr.contains(message), "{message}: {}", run.stderr);
        assert!(
            run.stderr.contains("--> ") && run.stderr.contains('^'),
            "{}",
            run.stderr
        );
        assert!(!run.out.exists(), "{message}: nothing written");
    }
    let (_dir, run) = optimize(DOUBLE_INTEGRATOR, &[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let (dir, path) = problem(DOUBLE_INTEGRATOR);
    let refused = marsden("run", &path, &[]);
    assert_eq!(refused.code, 2);
    assert!(
        refused.stderr.contains("solve it with `marsden optimize`"),
        "{}",
        refused.stderr
    );
    drop(dir);
}

/// The double integrator must travel 1 in T = 1 with |u| ≤ 1: impossible, since rest to rest
/// with |u| ≤ 1 covers at most T²/4 = 0.25 (bang-bang, [BH75] §3). The dynamics are linear, so
/// the QP's checked certificate proves the discrete problem infeasible: status "infeasible",
/// exit 1, the bound on `u` named, the last iterate still written.
#[test]
fn unreachable_target_is_reported_infeasible_with_the_bound_named() {
    let text = DOUBLE_INTEGRATOR.replacen(
        "[output]",
        "[optimal_control.bounds]\nu = [-1.0, 1.0]\n[output]",
        1,
    );
    let (_dir, run) = optimize(&text, &["--quiet"]);
    assert_eq!(run.code, 1, "{}", run.stderr);
    assert!(
        run.stderr.contains("status \"infeasible\""),
        "{}",
        run.stderr
    );
    assert!(run.stderr.contains("the bounds on `u`"), "{}", run.stderr);
    let oc = &run.summary()["optimal_control"];
    assert_eq!(oc["status"], "infeasible");
    assert_eq!(oc["last_iterate"], true);
    assert!(
        oc["failure"]
            .as_str()
            .unwrap()
            .contains("at the first iterate"),
        "{oc}"
    );
    let trajectory = table(&run.out, "trajectory.csv");
    assert_eq!(column(&trajectory, "q_x").len(), 21);
    // The unconstrained optimum u = 6 − 12t stays within |u| ≤ 6: bounds ±6.5 converge.
    let text = text.replace("u = [-1.0, 1.0]", "u = [-6.5, 6.5]");
    let (_dir, run) = optimize(&text, &["--quiet"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
}

/// The two-link manipulator with torques bounded by ±1.5 (the example has ±2): the
/// linearisation at the straight-line first iterate cannot meet the bounds (a checked
/// certificate), and the iteration goes on in elastic mode, minimising the violation, until the
/// subproblems have solutions again: it converges, within the bounds, to a trajectory the core
/// integrator replays. With ±1.0 the violation stops decreasing at a positive value: the status
/// says "infeasible", names both torques' bounds and the elastic steps, and the last iterate is
/// written.
#[test]
fn two_link_manipulator_with_tight_torques_recovers_in_elastic_mode() {
    let with_bounds = |bound: &str| {
        std::fs::read_to_string(repo_root().join("examples/two_link_manipulator.toml"))
            .unwrap()
            .replace("[-2.0, 2.0]", &format!("[-{bound}, {bound}]"))
            .replace("dir = \"out/two_link_manipulator\"", "plots = false")
    };
    let (_dir, run) = optimize(&with_bounds("1.5"), &["--quiet"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let summary = run.summary();
    let oc = &summary["optimal_control"];
    assert_eq!(oc["status"], "converged", "{oc}");
    assert!(
        oc["constraint_violation"].as_f64().unwrap() <= 1e-10,
        "{oc}"
    );
    assert!(oc["replay_defect"].as_f64().unwrap() <= 1e-9, "{oc}");
    let first = summary["history"][0]["violation"].as_f64().unwrap();
    assert!(
        first > 1.0,
        "the first iterate was far from feasible: {first}"
    );
    let controls = table(&run.out, "controls.csv");
    for name in ["tau1", "tau2"] {
        let worst = column(&controls, name)
            .iter()
            .fold(0.0, |m, u| max_or_nan(m, u.abs()));
        assert!(worst <= 1.5 + 1e-9, "{name}: {worst}");
    }

    let (_dir, run) = optimize(&with_bounds("1.0"), &["--quiet"]);
    assert_eq!(run.code, 1, "{}", run.stderr);
    let oc = &run.summary()["optimal_control"];
    assert_eq!(oc["status"], "infeasible", "{oc}");
    let failure = oc["failure"].as_str().unwrap();
    assert!(failure.contains("the bounds on `tau1`, `tau2`"), "{oc}");
    assert!(
        failure.contains("elastic steps reduced the violation"),
        "{oc}"
    );
    assert!(oc["constraint_violation"].as_f64().unwrap() > 0.1, "{oc}");
    assert_eq!(column(&table(&run.out, "controls.csv"), "tau1").len(), 100);
}

/// State bounds that exclude a fixed end position: refused at load time (exit 2, caret at the
/// bounds), nothing solved or written.
#[test]
fn state_bounds_excluding_the_end_exit_two() {
    let text = DOUBLE_INTEGRATOR.replacen(
        "[output]",
        "[optimal_control.bounds]\nx = [-1.0, 0.5]\n[output]",
        1,
    );
    let (_dir, run) = optimize(&text, &[]);
    assert_eq!(run.code, 2, "{}", run.stderr);
    assert!(
        run.stderr
            .contains("bounds on `x` = [-1, 0.5] exclude its `end` value 1"),
        "{}",
        run.stderr
    );
    assert!(run.stderr.contains('^'), "{}", run.stderr);
    assert!(!run.out.exists());
}

/// `examples/orbit_transfer.toml`: the low-thrust transfer from the circle r = 1 to r = 1.5
/// (μ = 1) converges and ends on the target circle — r = 1.5, p_r = 0, angular momentum
/// p_θ = √1.5 and the energy of a circle, H = ½(p_r² + p_θ²/r²) − 1/r = −1/(2r) = −1/3 — and
/// a longer transfer needs less thrust: the cost falls as T grows over 6, 8, 12 (a physical
/// check, not a number of the code's).
#[test]
fn orbit_transfer_ends_on_the_target_circle_and_costs_less_when_longer() {
    let text = std::fs::read_to_string(repo_root().join("examples/orbit_transfer.toml")).unwrap();
    let mut costs = Vec::new();
    for t_end in [6.0, 8.0, 12.0] {
        let text = text.replace("t_end = 8.0", &format!("t_end = {t_end:?}"));
        let (_dir, run) = optimize(&text, &["--quiet"]);
        assert_eq!(run.code, 0, "T = {t_end}: {}", run.stderr);
        let oc = &run.summary()["optimal_control"];
        assert_eq!(oc["status"], "converged", "{oc}");
        let trajectory = table(&run.out, "trajectory.csv");
        let last = |name: &str| *column(&trajectory, name).last().unwrap();
        let (r, p_r, p_theta) = (last("q_r"), last("p_r"), last("p_theta"));
        let energy = 0.5 * (p_r * p_r + p_theta * p_theta / (r * r)) - 1.0 / r;
        println!("T = {t_end}: r = {r}, p_r = {p_r:e}, p_θ = {p_theta}, H = {energy}");
        assert!((r - 1.5).abs() < 1e-9, "r = {r}");
        assert!(p_r.abs() < 1e-9, "p_r = {p_r}");
        assert!((p_theta - 1.5_f64.sqrt()).abs() < 1e-9, "p_θ = {p_theta}");
        assert!((energy + 1.0 / 3.0).abs() < 1e-9, "H = {energy}");
        costs.push(oc["cost"].as_f64().unwrap());
    }
    println!("costs for T = 6, 8, 12: {costs:?}");
    assert!(costs.windows(2).all(|w| w[1] < w[0]), "{costs:?}");
}

/// The closed-form optimum of the oscillator `L = ½ẋ² − ½x²`, `f = u`, `C = ½u²`, rest at 0 to
/// rest at 1 in T = 1 (Pontryagin, [BH75] §2.8): `u = A cos t + B sin t` with `q(1) = 1`,
/// `q̇(1) = 0` fixing `A`, `B`; `J = ½[A²(½ + sin 2/4) + B²(½ − sin 2/4) + AB sin²1]`.
fn oscillator_optimal_cost() -> f64 {
    let (s, c) = 1.0_f64.sin_cos();
    let (a11, a12, a21, a22) = (s / 2.0, (s - c) / 2.0, (s + c) / 2.0, s / 2.0);
    let det = a11 * a22 - a12 * a21;
    let (a, b) = (a22 / det, -a21 / det);
    let s2 = 2.0_f64.sin();
    0.5 * (a * a * (0.5 + s2 / 4.0) + b * b * (0.5 - s2 / 4.0) + a * b * s * s)
}

/// `gauss-2` and `lobatto-3` (order 4) take one control per quadrature node: the discrete
/// optimum of the oscillator converges to the closed form at order 4 ([OJM11] §4.2), with
/// `controls.csv` holding a row per node at `t_k + c_i h` and the summary saying so.
#[test]
fn fourth_order_rules_converge_at_order_four_with_a_control_per_node() {
    let oscillator = DOUBLE_INTEGRATOR
        .replace("0.5*x_dot^2", "0.5*x_dot^2 - 0.5*x^2")
        .replace("[[system.symmetry]]\ntranslation = \"x\"\n", "")
        .replace(
            "steps = 20",
            "steps = 20\ntolerance = 1e-11\nconstraint_tolerance = 1e-12",
        );
    let optimum = oscillator_optimal_cost();
    for method in ["gauss-2", "lobatto-3"] {
        let text = oscillator.replace("\"midpoint\"", &format!("\"{method}\""));
        let (mut errors, mut steps) = (Vec::new(), Vec::new());
        for n in [4, 8, 16] {
            let (_dir, run) = optimize(&text, &["--steps", &n.to_string(), "--quiet"]);
            assert_eq!(run.code, 0, "{method} N = {n}: {}", run.stderr);
            let oc = &run.summary()["optimal_control"];
            assert_eq!(oc["status"], "converged", "{oc}");
            assert_eq!(
                oc["controls_per_step"],
                if method == "gauss-2" { 2 } else { 3 }
            );
            let nodes: Vec<f64> = (oc["control_nodes"].as_array().unwrap().iter())
                .map(|c| c.as_f64().unwrap())
                .collect();
            let controls = table(&run.out, "controls.csv");
            let t = column(&controls, "t");
            let h = 1.0 / n as f64;
            assert_eq!(t.len(), n * nodes.len());
            for (r, t) in t.iter().enumerate() {
                let want = (r / nodes.len()) as f64 * h + nodes[r % nodes.len()] * h;
                assert!(
                    (t - want).abs() < 1e-14,
                    "{method}: row {r} at {t}, not {want}"
                );
            }
            errors.push((oc["cost"].as_f64().unwrap() - optimum).abs());
            steps.push(h);
        }
        let p = slope(&steps, &errors);
        println!("{method}: |J − J*| = {errors:?}, fitted order {p:.3}");
        assert!((p - 4.0).abs() < 0.25, "{method}: order {p}");
    }
}

/// With inner control points (Gauss's, a composition's), the solution is still the core
/// integrator's steps under its controls (`replay_defect`) and keeps the forced Noether
/// balance of the translation, now with the forces on the inner points: from rest to `v = ½`,
/// `p_x` changes by ½ and the controls' impulse must match it step by step.
#[test]
fn inner_control_points_keep_the_replay_and_the_noether_balance() {
    let text = DOUBLE_INTEGRATOR.replace(
        "end = { q = [1.0], v = [0.0] }",
        "end = { q = [1.0], v = [0.5] }",
    );
    for method in ["gauss-2", "suzuki-4(midpoint)"] {
        let text = text.replace("\"midpoint\"", &format!("\"{method}\""));
        let (_dir, run) = optimize(&text, &["--quiet"]);
        assert_eq!(run.code, 0, "{method}: {}", run.stderr);
        let oc = &run.summary()["optimal_control"];
        assert_eq!(oc["status"], "converged", "{oc}");
        let replay = oc["replay_defect"].as_f64().unwrap();
        assert!(replay < 1e-9, "{method}: replay defect {replay}");
        let noether = &oc["noether_balance"]["Px"];
        let change = noether["momentum_change"].as_f64().unwrap();
        assert!((change - 0.5).abs() < 1e-9, "{method}: {noether}");
        assert!(
            noether["max_defect"].as_f64().unwrap() < 1e-9,
            "{method}: {noether}"
        );
        assert!((noether["total_impulse"].as_f64().unwrap() - 0.5).abs() < 1e-9);
    }
}

/// The Bryson–Denham problem ([BH75] §3.11) from a file, its state constraint `x ≤ 1/9` as
/// the path inequality `path = ["x - 1/9"]`: the continuous optimum costs 4 with the
/// constraint active on `[⅓, ⅔]`. The discrete optimum converges to 4 at order 2 (slope over
/// N = 40, 80, 160). It touches the constraint where the continuous arc begins and ends (the
/// first and last active midpoints within 2h of ⅓ and ⅔, with positive multipliers) and stays
/// within `h²` below it in between — the discrete optimum rides the arc to `O(h²)`, like the
/// cost. `summary.json` counts the active points the trajectory shows, the console says so.
#[test]
fn bryson_denham_path_inequality_from_a_file_converges_at_order_two() {
    let text = DOUBLE_INTEGRATOR
        .replace(
            "start = { q = [0.0], v = [0.0] }",
            "start = { q = [0.0], v = [1.0] }",
        )
        .replace(
            "end = { q = [1.0], v = [0.0] }",
            "end = { q = [0.0], v = [-1.0] }",
        )
        .replace("[output]", "path = [\"x - 1/9\"]\n[output]");
    let ell = 1.0 / 9.0;
    let (mut steps, mut errors) = (Vec::new(), Vec::new());
    for n in [40, 80, 160] {
        let (_dir, run) = optimize(&text, &["--steps", &n.to_string()]);
        assert_eq!(run.code, 0, "N = {n}: {}", run.stderr);
        let oc = &run.summary()["optimal_control"];
        assert_eq!(oc["status"], "converged");
        let g = &oc["path"][0];
        assert_eq!(g["expression"], "x - 1/9");
        assert_eq!(g["points"], n);
        println!("N = {n}: cost {}, path {g}", oc["cost"]);
        assert!(g["max"].as_f64().unwrap() <= 1e-10, "{g}");
        assert!(g["max_multiplier"].as_f64().unwrap() > 0.0, "{g}");
        let trajectory = table(&run.out, "trajectory.csv");
        let x = column(&trajectory, "q_x");
        let h = 1.0 / n as f64;
        let values: Vec<(f64, f64)> = (x.windows(2).enumerate())
            .map(|(k, w)| ((k as f64 + 0.5) * h, 0.5 * (w[0] + w[1]) - ell))
            .collect();
        let active: Vec<f64> = values
            .iter()
            .filter(|v| v.1 >= -1e-8)
            .map(|v| v.0)
            .collect();
        assert_eq!(g["active_points"], active.len());
        let (first, last) = (active[0], active[active.len() - 1]);
        assert!((first - 1.0 / 3.0).abs() <= 2.0 * h && (last - 2.0 / 3.0).abs() <= 2.0 * h);
        let arc = values.iter().filter(|v| v.0 >= first && v.0 <= last);
        let lowest = arc.map(|v| v.1).fold(0.0, f64::min);
        println!(
            "  active from {first:.4} to {last:.4}, at most {:.3} h² below",
            -lowest / (h * h)
        );
        assert!(lowest >= -h * h, "{lowest}");
        assert!(run.stdout.contains("path x - 1/9 <= 0"), "{}", run.stdout);
        errors.push((oc["cost"].as_f64().unwrap() - 4.0).abs());
        steps.push(h);
    }
    let p = slope(&steps, &errors);
    println!("errors {errors:?}, fitted order {p:.3}");
    assert!((p - 2.0).abs() < 0.15, "order {p}");
}
