//! Tight stepping loop for profilers: `cargo run --profile profiling --example profile_step -- pendulum 100000`.
use marsden::systems::{DoublePendulum, Kepler, Pendulum};
use marsden::{DiscreteAction, Integrator, Midpoint, Rule, State, Trapezoid};

fn run<A: DiscreteAction>(action: A, q: &[f64], p: &[f64], h: f64, n: usize) -> f64 {
    let mut integrator = Integrator::new(action);
    let mut s = State {
        t: 0.0,
        q: q.to_vec(),
        p: p.to_vec(),
    };
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
        Some("kepler") => run(Trapezoid.discretize(Kepler::default()), &q, &p, 0.01, n),
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
