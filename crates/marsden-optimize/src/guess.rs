//! The solver's first iterate from the file's `guess`: the forward simulation with zero
//! controls from a complete `start` (the default), or the straight line between the ends.

use marsden::{Initial, Lagrangian, Problem, Rule, SolveOptions, TimeGrid};
use marsden_control::{ControlForce, FrozenControl, Guess};
use marsden_problem::problem::optimal_control::{EndSpec, GuessKind, OptimalControlSpec, RateSpec};

/// The first iterate and how it was made.
#[derive(Debug, Clone, PartialEq)]
pub struct FirstIterate {
    /// Positions at the nodes, zero controls.
    pub guess: Guess,
    /// `"simulation"` or `"line"` (a simulation that could not run falls back to the line).
    pub kind: &'static str,
}

/// The first iterate of `spec` with `rule`.
pub fn initial<L: Lagrangian, F: ControlForce, R: Rule>(
    spec: &OptimalControlSpec,
    lagrangian: &L,
    force: &F,
    grid: TimeGrid,
    rule: &R,
) -> FirstIterate {
    let u = vec![vec![0.0; spec.controls.len()]; spec.steps];
    if spec.guess == GuessKind::Simulation
        && let Some(q) = simulate(&spec.start, lagrangian, force, grid, rule)
    {
        return FirstIterate {
            guess: Guess { q, u },
            kind: "simulation",
        };
    }
    FirstIterate {
        guess: Guess {
            q: line(&spec.start, &spec.end, spec.steps),
            u,
        },
        kind: "line",
    }
}

/// `q_k = a + (k/N)(b − a)`, with free components held at the other end's value or 0.
fn line(start: &EndSpec, end: &EndSpec, steps: usize) -> Vec<Vec<f64>> {
    let a: Vec<f64> = (start.q.iter().zip(&end.q))
        .map(|(s, e)| s.or(*e).unwrap_or(0.0))
        .collect();
    let b: Vec<f64> = end.q.iter().zip(&a).map(|(e, a)| e.unwrap_or(*a)).collect();
    (0..=steps)
        .map(|k| {
            let s = k as f64 / steps as f64;
            a.iter().zip(&b).map(|(x, y)| x + s * (y - x)).collect()
        })
        .collect()
}

/// The core integrator's run from a complete start with `u = 0`, if it succeeds.
fn simulate<L: Lagrangian, F: ControlForce, R: Rule>(
    start: &EndSpec,
    lagrangian: &L,
    force: &F,
    grid: TimeGrid,
    rule: &R,
) -> Option<Vec<Vec<f64>>> {
    let q0: Option<Vec<f64>> = start.q.iter().copied().collect();
    let initial = match &start.rate {
        RateSpec::Velocity(v) => {
            Initial::velocity(&q0?, &v.iter().copied().collect::<Option<Vec<f64>>>()?)
        }
        RateSpec::Momentum(p) => {
            Initial::momentum(&q0?, &p.iter().copied().collect::<Option<Vec<f64>>>()?)
        }
    };
    let zero = FrozenControl {
        force,
        u: vec![0.0; force.controls()],
    };
    let run = Problem::new(lagrangian, initial, grid)
        .ok()?
        .with_force(zero);
    let trajectory = run.solve(rule, &SolveOptions::default()).ok()?;
    let nodes: Vec<Vec<f64>> = (0..trajectory.len())
        .map(|k| trajectory.q(k).to_vec())
        .collect();
    let finite = nodes.iter().flatten().all(|x| x.is_finite());
    (nodes.len() == grid.steps + 1 && finite).then_some(nodes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_line_holds_free_positions_at_the_other_end() {
        let start = EndSpec {
            q: vec![Some(0.0), None, None],
            rate: RateSpec::Momentum(vec![None; 3]),
        };
        let end = EndSpec {
            q: vec![Some(2.0), Some(1.0), None],
            rate: RateSpec::Momentum(vec![None; 3]),
        };
        let nodes = line(&start, &end, 4);
        assert_eq!(nodes.len(), 5);
        assert_eq!(nodes[0], [0.0, 1.0, 0.0]);
        assert_eq!(nodes[2], [1.0, 1.0, 0.0]);
        assert_eq!(nodes[4], [2.0, 1.0, 0.0]);
    }
}
