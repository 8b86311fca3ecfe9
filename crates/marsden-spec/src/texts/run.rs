//! The one-screen summary on stdout: what ran, how long, what was preserved and how well.
//!
//! ```text
//! pendulum: builtin pendulum, 1 coordinate (theta), midpoint (order 2), h = 0.05
//!   completed   100000 steps, t = 0 → 5000, in 0.21 s (2.1 µs/step)
//!   newton      1.02 iterations/step (max 3), tolerance 1e-12
//!   energy      E0 = -0.0707372, max |ΔE/E0| = 1.27e-3, final 8.6e-5, drift 3.1e-12 per unit time
//!   momentum    Lz: J0 = 0.8, max |ΔJ| = 3.3e-16
//!   constraints max |φ(q)| = 2.2e-16
//!   wrote       out/pendulum: trajectory.csv (100001 rows), summary.json, …
//! ```

use std::fmt::Write as _;

use crate::problem::check::count_coordinates;
use crate::run::{Outcome, RunStatus};

/// `1 body`, `2 bodies`.
fn count(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// The report of a run.
pub fn render(outcome: &Outcome) -> String {
    let s = &outcome.summary;
    let mut out = String::new();
    let _ = writeln!(
        out,
        "{}: {}, {}, {} ({}), h = {}",
        s.name,
        s.system,
        match (&s.rigid_body, &s.multibody, s.coordinates.is_empty()) {
            (Some(_), _, true) => "on SO(3)".to_owned(),
            (Some(_), _, false) => format!("on SO(3) × ℝ³ ({})", s.coordinates.join(", ")),
            (None, Some(m), _) if m.particles == 0 => format!(
                "{} on (SO(3) × ℝ³)^{}, {}",
                count(m.bodies, "body", "bodies"),
                m.bodies,
                count(m.joints.len(), "joint", "joints")
            ),
            (None, Some(m), _) if m.bodies == 0 => format!(
                "{} on (ℝ³)^{}, {}",
                count(m.particles, "particle", "particles"),
                m.particles,
                count(m.joints.len(), "joint", "joints")
            ),
            (None, Some(m), _) => format!(
                "{} and {} on (SO(3) × ℝ³)^{} × (ℝ³)^{}, {}",
                count(m.bodies, "body", "bodies"),
                count(m.particles, "particle", "particles"),
                m.bodies,
                m.particles,
                count(m.joints.len(), "joint", "joints")
            ),
            (None, None, _) => count_coordinates(&s.coordinates),
        },
        s.method,
        match s.energy_not_available {
            Some(_) => "the file's own L_d".to_owned(),
            None => crate::problem::method::order_text(s.order),
        },
        num(s.h)
    );
    let span = format!("t = {} → {}", num(s.t_initial), num(s.t_final));
    match &s.error {
        None if s.status == RunStatus::Interrupted => line(
            &mut out,
            "INTERRUPTED",
            format!(
                "after {} of {} steps ({span}), in {}",
                s.steps,
                s.steps_requested,
                seconds(s.wall_seconds)
            ),
        ),
        None if s.status == RunStatus::Stopped => line(
            &mut out,
            "stopped",
            format!(
                "by event {} after {} of {} steps ({span}), in {}",
                s.stopped_by_event.as_deref().unwrap_or("?"),
                s.steps,
                s.steps_requested,
                seconds(s.wall_seconds)
            ),
        ),
        None => line(
            &mut out,
            "completed",
            format!(
                "{} steps{}, {span}, in {}",
                s.steps,
                last_step_text(s.last_step),
                timing(s.wall_seconds, s.jit_compile_seconds, s.steps)
            ),
        ),
        Some(e) => line(
            &mut out,
            "FAILED",
            format!(
                "after {} of {} steps ({span}): {e}",
                s.steps, s.steps_requested
            ),
        ),
    }
    let mean = s.newton.iterations_total as f64 / s.steps.max(1) as f64;
    let explicit = s.steps > 0 && s.newton.explicit_steps == s.steps;
    line(
        &mut out,
        "newton",
        match explicit {
            true => {
                "none: every step explicit (Störmer–Verlet form, no system to solve)".to_owned()
            }
            false => format!(
                "{mean:.2} iterations/step (max {}), tolerance {:e}",
                s.newton.iterations_max, s.newton.tolerance
            ),
        },
    );
    energy_lines(&mut out, s);
    let over = over_samples(s);
    if let Some(r) = &s.rigid_body {
        line(
            &mut out,
            "rigid body",
            format!(
                "max |RᵀR − I| = {}, Casimir |Π|²: {} with max drift {}{over}",
                sci(r.orthogonality_defect),
                num(r.casimir.initial),
                sci(r.casimir.max_abs_drift)
            ),
        );
    }
    if let Some(m) = &s.multibody {
        let l = &m.angular_momentum;
        let joints: Vec<String> = (m.joints.iter())
            .map(|j| format!("{} ({}, {}–{})", j.name, j.kind, j.bodies[0], j.bodies[1]))
            .collect();
        let joints = match joints.is_empty() {
            true => "none".to_owned(),
            false => joints.join(", "),
        };
        line(
            &mut out,
            "joints",
            format!(
                "{joints}; max |RᵀR − I| = {}{over}",
                sci(m.orthogonality_defect)
            ),
        );
        line(
            &mut out,
            "momentum",
            format!(
                "L = Σ RΠ + x × p: L0 = ({}, {}, {}), max |ΔL| = ({}, {}, {}){over}; monitored: conserved only about an axis through the origin that gravity and the ground joints are symmetric about",
                num(l.initial[0]),
                num(l.initial[1]),
                num(l.initial[2]),
                sci(l.max_abs_drift[0]),
                sci(l.max_abs_drift[1]),
                sci(l.max_abs_drift[2])
            ),
        );
    }
    for (name, m) in &s.momenta {
        line(
            &mut out,
            "momentum",
            format!(
                "{name}: J0 = {}, max |ΔJ| = {}{over}{}",
                num(m.initial),
                sci(m.max_abs_drift),
                match m.symmetry {
                    true => "",
                    false => " (not a symmetry: monitored, not conserved)",
                }
            ),
        );
    }
    for (name, b) in &s.noether_balance {
        line(
            &mut out,
            "noether",
            format!(
                "{name} balance (forces act): J_N − J0 = {}, impulse {}, unaccounted {} (max {} per step)",
                sci(b.momentum_change),
                sci(b.total_impulse),
                sci(b.total_defect),
                sci(b.max_defect)
            ),
        );
    }
    certificate_lines(&mut out, s);
    if let Some(r) = s.constraints.max_residual {
        line(
            &mut out,
            "constraints",
            format!(
                "max |φ(q)| = {} ({} constraint(s)){over}",
                sci(r),
                s.constraints.count
            ),
        );
    }
    if !s.events.is_empty() {
        let counts: Vec<String> = (s.events.iter())
            .map(|(name, n)| format!("{name}: {n} crossing{}", if *n == 1 { "" } else { "s" }))
            .collect();
        line(&mut out, "events", counts.join(", "));
    }
    if let Some(samples) = &s.samples {
        let by = match samples.reached_by {
            "step" => "by steps of their own size",
            _ => "on the steps' interpolants",
        };
        let reached = match samples.taken == samples.requested {
            true => format!("{} requested time(s) sampled {by}", samples.taken),
            false => format!(
                "{} of {} requested times sampled {by} (the run ended before the others)",
                samples.taken, samples.requested
            ),
        };
        line(&mut out, "samples", reached);
    }
    let files: Vec<String> = s
        .output
        .files
        .iter()
        .map(|f| match f.as_str() {
            "trajectory.csv" | "t.npy" => format!("{f} ({} rows)", s.output.rows),
            _ => f.clone(),
        })
        .collect();
    match &outcome.dir {
        Some(dir) => line(
            &mut out,
            "wrote",
            format!("{}: {}", dir.display(), files.join(", ")),
        ),
        None => line(
            &mut out,
            "kept",
            format!("{} samples in memory", s.output.rows),
        ),
    }
    out
}

/// The energy line: its error where energy is conserved, otherwise the discrete energy balance
/// (or, without one, why there is no error to report).
fn energy_lines(out: &mut String, s: &crate::run::Summary) {
    let e = &s.energy;
    if let Some(why) = s.energy_not_available {
        return line(out, "energy", why.to_owned());
    }
    let over = over_samples(s);
    match (s.energy_not_conserved, &s.energy_balance) {
        (None, _) => line(
            out,
            "energy",
            format!(
                "E0 = {}, max |ΔE/E0| = {}, final {}, drift {} per unit time{over}",
                num(e.initial),
                sci(e.max_rel_error),
                sci(e.final_rel_error),
                sci(e.drift_per_unit_time)
            ),
        ),
        (Some(why), Some(b)) => line(
            out,
            "energy",
            format!(
                "balance ({why}): E0 = {}, E_N − E0 = {}, work {}{}, unaccounted {} (max {} per step)",
                num(e.initial),
                sci(b.energy_change),
                sci(b.total_work),
                b.total_time_work.map_or(String::new(), |w| format!(
                    ", by the time dependence {}",
                    sci(w)
                )),
                sci(b.total_defect),
                sci(b.max_defect)
            ),
        ),
        (Some(why), None) => line(
            out,
            "energy",
            format!(
                "not conserved ({why}): E0 = {}; no energy error to report, and no balance: {}",
                num(e.initial),
                s.energy_balance_not_available
                    .unwrap_or("none was computed"),
            ),
        ),
    }
}

/// The certificate lines (`[analysis] certify = true`): symplecticity, then equivariance.
fn certificate_lines(out: &mut String, s: &crate::run::Summary) {
    let Some(c) = &s.certificate else { return };
    let y = &c.symplecticity;
    let defect = |x: Option<f64>| x.map_or("n/a".to_owned(), sci);
    let note = y.note.as_ref().map_or(String::new(), |n| format!(" ({n})"));
    let measure = match y.restricted_to {
        Some(_) => "on T*N max|ω(DF u, DF w) − ω(u, w)|/max|DF u|²",
        None => "‖DFᵀJDF − J‖/‖DF‖²",
    };
    line(
        out,
        "certificate",
        format!(
            "symplecticity defect {measure} = {} (first step), {} (from the final state){note}",
            defect(y.start),
            defect(y.end)
        ),
    );
    for (name, e) in &c.equivariance {
        line(
            out,
            "certificate",
            format!(
                "{name}: equivariance defect of L_d {} (relative {})",
                sci(e.max_abs_defect),
                sci(e.max_rel_defect)
            ),
        );
    }
}

/// ` (over N stored samples)` when the maxima did not see every step, else nothing.
fn over_samples(s: &crate::run::Summary) -> String {
    // A file's own `L_d` has no energy to count samples by: its momenta and constraints are
    // monitored at the stored rows.
    let monitored = match s.energy_not_available {
        Some(_) => usize::try_from(s.output.rows).unwrap_or(usize::MAX),
        None => s.energy.samples,
    };
    match monitored {
        n if n < s.steps + 1 => format!(" (over {n} stored samples)"),
        _ => String::new(),
    }
}

fn line(out: &mut String, label: &str, text: String) {
    let _ = writeln!(out, "  {label:<11} {text}");
}

/// A number as Rust prints it (shortest round trip, `0.8`, `-0.0707372`), or in exponent form
/// beyond 1e15 or below 1e-5 in magnitude: `1e300` is not printed as 301 digits.
pub fn num(x: f64) -> String {
    let a = x.abs();
    match a != 0.0 && a.is_finite() && !(1e-5..1e15).contains(&a) {
        true => format!("{x:e}"),
        false => format!("{x}"),
    }
}

/// `1.27e-3`, `0`.
fn sci(x: f64) -> String {
    if x == 0.0 {
        "0".to_owned()
    } else {
        format!("{x:.2e}")
    }
}

/// `0.213 s (2.1 µs/step)`; with native code compiled during the run, its time is said apart
/// and left out of the time per step: `2.4 ms (95 ns/step; 2.3 ms of it compiling native
/// code)`.
fn timing(wall: f64, jit: f64, steps: usize) -> String {
    let per_step = match steps {
        0 => 0.0,
        n => (wall - jit).max(0.0) / n as f64,
    };
    match jit > 0.0 {
        true => format!(
            "{} ({}/step; {} of it compiling native code)",
            seconds(wall),
            seconds(per_step),
            seconds(jit)
        ),
        false => format!("{} ({}/step)", seconds(wall), seconds(per_step)),
    }
}

/// `0.213 s`, `2.1 µs`.
fn seconds(s: f64) -> String {
    match s {
        s if s >= 1.0 => format!("{s:.2} s"),
        s if s >= 1e-3 => format!("{:.1} ms", s * 1e3),
        s if s >= 1e-6 => format!("{:.2} µs", s * 1e6),
        s => format!("{:.0} ns", s * 1e9),
    }
}

/// `" (the last one shorter, h = …, to end at t_end)"` for a grid with a shorter last step.
fn last_step_text(last: Option<f64>) -> String {
    match last {
        Some(h) => format!(" (the last one shorter, h = {}, to end at t_end)", num(h)),
        None => String::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short() {
        assert_eq!(sci(1.2345e-3), "1.23e-3");
        assert_eq!(sci(0.0), "0");
        assert_eq!(seconds(2.5e-6), "2.50 µs");
        assert_eq!(seconds(0.25), "250.0 ms");
    }

    /// A short run's time per step leaves out the JIT's compilation: 1000 steps in 2.4 ms of
    /// which 2.3 ms compiled native code are 100 ns per step, not 2.4 µs.
    #[test]
    fn time_per_step_excludes_the_jit_compilation() {
        assert_eq!(
            timing(2.4e-3, 2.3e-3, 1000),
            "2.4 ms (100 ns/step; 2.3 ms of it compiling native code)"
        );
        assert_eq!(timing(2.4e-3, 0.0, 1000), "2.4 ms (2.40 µs/step)");
        assert_eq!(timing(0.0, 0.0, 0), "0 ns (0 ns/step)");
    }

    /// Huge and tiny numbers in exponent form (a value of 1e300 was printed as 301 digits);
    /// ordinary ones as Rust's shortest round trip.
    #[test]
    fn numbers_beyond_1e15_are_printed_in_exponent_form() {
        assert_eq!(num(1e300), "1e300");
        assert_eq!(num(-2.5e16), "-2.5e16");
        assert_eq!(num(3e-9), "3e-9");
        assert_eq!(num(-0.0707372), "-0.0707372");
        assert_eq!(num(5000.0), "5000");
        assert_eq!(num(0.0), "0");
        assert_eq!(num(f64::NAN), "NaN");
    }
}
