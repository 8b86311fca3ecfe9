//! Work–precision of the outer solar system (HLW06 §I.2.4: the Sun with the inner planets
//! lumped in, Jupiter, Saturn, Uranus, Neptune, Pluto; `G = 2.95912208286·10⁻⁴` in AU, days and
//! solar masses; no softening): for each method and step size `h`, the maximal relative energy
//! error `max |ΔE/E₀|` over `[0, T]` against the wall time per step and per 10 simulated days.
//!
//! ```sh
//! cargo run --release -p marsden --features tools --example work_precision [FILE] [T] [T_IMPLICIT]
//! ```
//!
//! `FILE` defaults to `outer_solar_system_hlw.txt` of the benchmark data kept beside the repository
//! with the C reference `verlet.c` (the path is relative to the repository root), `T` to 10⁵ days
//! for the explicit methods (the trapezoid rule is Störmer–Verlet on this separable system, and its
//! compositions are explicit too), `T_IMPLICIT` to 4000 days for the Gauss methods (Newton on the
//! dense 6-body Jacobian costs milliseconds per step, so 10⁵ days would take minutes). The wall
//! time is the median of 3 runs that store no states; the energy comes from one more run that
//! evaluates `E = Σ|pᵢ|²/2mᵢ − Σ G mᵢ mⱼ/|qᵢ − qⱼ|` after every step. The cost per 10 days is
//! comparable with the C Störmer–Verlet of the C reference (`verlet.c`, kept beside the repository;
//! 144 ns per step at `h = 10` days).

use std::ops::ControlFlow;
use std::time::Instant;

use marsden::discrete::rules::{Method, WithRule};
use marsden::run::{RunOptions, StepView};
use marsden::systems::NBody;
use marsden::systems::nbody::file;
use marsden::{Initial, Problem, Rule, SolveOptions, TimeGrid};

/// Gravitational constant in AU³ / (solar mass · day²).
const G: f64 = 2.959_122_082_86e-4;
/// The methods compared, with whether they are implicit (Newton at each step).
const METHODS: [(&str, bool); 7] = [
    ("trapezoid", false),
    ("triple-jump-4(trapezoid)", false),
    ("kahan-li-6(trapezoid)", false),
    ("yoshida-6(trapezoid)", false),
    ("suzuki-umeno-8(trapezoid)", false),
    ("gauss-2", true),
    ("gauss-3", true),
];
/// Step sizes in days.
const STEP_SIZES: [f64; 6] = [10.0, 20.0, 40.0, 50.0, 60.0, 80.0];
/// Timed repeats (the median is reported).
const REPEATS: usize = 3;

type Failure = Box<dyn std::error::Error>;

fn main() -> Result<(), Failure> {
    let mut args = std::env::args().skip(1);
    let path = args
        .next()
        .unwrap_or_else(|| "../shared/bench/data/outer_solar_system_hlw.txt".to_owned());
    let t_explicit: f64 = args.next().map_or(Ok(1e5), |s| s.parse())?;
    let t_implicit: f64 = args.next().map_or(Ok(4000.0), |s| s.parse())?;
    let (system, q0, p0) = file::load(&path, G, 0.0)?;
    println!(
        "outer solar system ({} bodies, {path}); T = {t_explicit} days (explicit), \
         {t_implicit} days (implicit); median of {REPEATS} runs\n",
        system.bodies()
    );
    println!("| method | h (days) | T (days) | ns/step | ns per 10 days | max abs(ΔE/E₀) |");
    println!("|---|---:|---:|---:|---:|---:|");
    for (name, implicit) in METHODS {
        let method = Method::parse(name)?;
        let t_end = if implicit { t_implicit } else { t_explicit };
        for h in STEP_SIZES {
            let steps = (t_end / h).round().max(1.0) as usize;
            let problem = Problem::new(
                system.clone(),
                Initial::momentum(&q0, &p0),
                TimeGrid::new(0.0, h, steps)?,
            )?;
            let row = match method.dispatch(Measure { problem: &problem }) {
                Ok(m) => format!(
                    "{:.0} | {:.0} | {:.2e}",
                    m.ns_per_step,
                    m.ns_per_step * 10.0 / h,
                    m.max_rel_energy_error
                ),
                Err(e) => format!("failed | | ({e})"),
            };
            println!("| {name} | {h} | {} | {row} |", steps as f64 * h);
        }
    }
    Ok(())
}

/// What one method at one step size cost and how well it kept the energy.
struct Measurement {
    /// Median wall time per step.
    ns_per_step: f64,
    /// `max |E(t_k) − E₀| / |E₀|` over the run.
    max_rel_energy_error: f64,
}

/// Timing and energy of `problem` with a concrete rule.
struct Measure<'a> {
    problem: &'a Problem<NBody>,
}

impl WithRule for Measure<'_> {
    type Output = Result<Measurement, Failure>;

    fn call<R: Rule>(self, rule: &R) -> Self::Output {
        let options = SolveOptions {
            run: RunOptions { stride: usize::MAX },
            ..SolveOptions::default()
        };
        let steps = self.problem.grid().steps as f64;
        let mut times = Vec::with_capacity(REPEATS);
        for _ in 0..REPEATS {
            let clock = Instant::now();
            self.problem.solve(rule, &options)?;
            times.push(clock.elapsed().as_secs_f64() * 1e9 / steps);
        }
        times.sort_by(f64::total_cmp);
        let system = self.problem.lagrangian();
        let start = self.problem.start();
        let e0 = system.energy(&start.q, &start.p);
        let mut worst: f64 = 0.0;
        let mut monitor = |view: &StepView<'_>| {
            worst = worst.max(((system.energy(view.q, view.p) - e0) / e0).abs());
            ControlFlow::Continue(())
        };
        self.problem.solve_with(rule, &options, &mut monitor)?;
        Ok(Measurement {
            ns_per_step: times[REPEATS / 2],
            max_rel_energy_error: worst,
        })
    }
}
