//! Tight stepping loop for profilers:
//! `cargo run --profile profiling -p marsden --features tools --example profile_step -- [pendulum|double|coupled4|kepler|constrained|gauss4|gauss4-compensated] 100000 [baseline]`.
//! `baseline` keeps the small kernels in baseline x86-64 code (`Integrator::with_wide_instructions`),
//! for valgrind 3.19, which does not decode every AVX instruction of the x86-64-v3 copy.
use marsden::discrete::rules::Galerkin;
use marsden::holonomic::MomentumProjection;
use marsden::systems::{CartesianPendulum, DoublePendulum, Kepler, Pendulum};
use marsden::{
    Constraint, DiscreteAction, DiscreteForce, Integrator, Lagrangian, Midpoint, NewtonOptions,
    Problem, Rule, Scalar, State, TimeGrid, Trapezoid,
};

/// Four angles with a configuration-dependent mass (the n = 4 static kernel):
/// `L = ½ Σ vᵢ² + 0.3 Σ_{i<j} vᵢ vⱼ cos(qᵢ − qⱼ) + Σ cos qᵢ`.
struct Coupled4;

impl Lagrangian for Coupled4 {
    fn dof(&self) -> usize {
        4
    }
    #[inline(always)]
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        let mut l = S::from(0.0);
        for i in 0..4 {
            l += v[i] * v[i] * 0.5 + q[i].cos();
            for j in i + 1..4 {
                l += v[i] * v[j] * (q[i] - q[j]).cos() * 0.3;
            }
        }
        l
    }
}

fn run<A: DiscreteAction>(action: A, q: &[f64], p: &[f64], h: f64, n: usize) -> f64 {
    run_compensated(action, q, p, h, n, false)
}

fn run_compensated<A: DiscreteAction>(
    action: A,
    q: &[f64],
    p: &[f64],
    h: f64,
    n: usize,
    compensated: bool,
) -> f64 {
    let s = State {
        t: 0.0,
        q: q.to_vec(),
        p: p.to_vec(),
    };
    let integrator = Integrator::new(action).with_compensated_summation(compensated);
    run_integrator(integrator, s, h, n)
}

/// The SHAKE + RATTLE pendulum of `benches/constrained.rs` (`h = 0.01`, `θ₀ = 1.5`).
fn constrained(n: usize) -> f64 {
    let sys = CartesianPendulum::default();
    let Ok(grid) = TimeGrid::new(0.0, 0.01, 1) else {
        return f64::NAN;
    };
    let problem =
        Problem::new(sys, sys.initial(1.5, 0.0), grid).and_then(|p| p.with_constraint(sys));
    let Ok(problem) = problem else {
        return f64::NAN;
    };
    match problem.integrator(&Midpoint, NewtonOptions::default()) {
        Ok(integrator) => run_integrator(integrator, problem.start().clone(), 0.01, n),
        Err(_) => f64::NAN,
    }
}

fn run_integrator<A, F, C, P>(
    integrator: Integrator<A, F, C, P>,
    mut s: State,
    h: f64,
    n: usize,
) -> f64
where
    A: DiscreteAction,
    F: DiscreteForce,
    C: Constraint,
    P: MomentumProjection,
{
    let wide = std::env::args().nth(3).as_deref() != Some("baseline");
    let mut integrator = integrator.with_wide_instructions(wide);
    let start = std::time::Instant::now();
    for _ in 0..n {
        if integrator.step(&mut s, h).is_err() {
            break;
        }
    }
    let ns = start.elapsed().as_secs_f64() / n as f64 * 1e9;
    println!("{ns:.1} ns/step, iterations {:?}", integrator.statistics());
    s.q[0]
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(100_000);
    let (q, p) = Kepler::pericentre(0.6);
    let x = match args.get(1).map(String::as_str) {
        Some("double") => run(
            Midpoint.discretize(DoublePendulum::default()),
            &[1.0, 0.5],
            &[0.0, 0.0],
            0.01,
            n,
        ),
        Some("coupled4") => run(
            Midpoint.discretize(Coupled4),
            &[0.4, 0.1, -0.2, -0.5],
            &[0.0, 0.1, 0.2, 0.3],
            0.01,
            n,
        ),
        Some("constrained") => constrained(n),
        Some("kepler") => run(Trapezoid.discretize(Kepler::default()), &q, &p, 0.01, n),
        Some(mode @ ("gauss4" | "gauss4-compensated")) => match Galerkin::gauss(4) {
            Ok(rule) => run_compensated(
                rule.discretize(Kepler::default()),
                &q,
                &p,
                2.0 * std::f64::consts::PI / 200.0,
                n,
                mode == "gauss4-compensated",
            ),
            Err(_) => f64::NAN,
        },
        _ => run(
            Midpoint.discretize(Pendulum::default()),
            &[1.5],
            &[0.0],
            0.05,
            n,
        ),
    };
    println!("{x}");
}
