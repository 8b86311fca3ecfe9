//! The initial guess of the solver, and controls as core forces.
//!
//! Default guess, in this order: the user's ([`crate::OptimalControl::with_guess`]); the
//! straight line between the boundary positions with `u = 0` when both ends fix every
//! position; the core integrator's run from a complete start with `u = 0`; else the start
//! positions (free components from the end, or 0) at every node.

use marsden::{Force, Initial, Lagrangian, Problem, Rule, Scalar, SolveOptions, TimeGrid};

use crate::model::{ControlForce, FinalCost, PathConstraint, RunningCost};
use crate::problem::{OptimalControl, Rate};
use crate::stages::ControlStages;
use crate::transcription::Layout;

/// The controlled force at constant controls `u`, as a core [`Force`].
#[derive(Debug, Clone)]
pub struct FrozenControl<F> {
    /// The controlled force.
    pub force: F,
    /// The controls.
    pub u: Vec<f64>,
}

impl<F: ControlForce> Force for FrozenControl<F> {
    fn force<S: Scalar>(&self, t: S, q: &[S], v: &[S], out: &mut [S]) {
        let u: Vec<S> = self.u.iter().map(|&x| S::from(x)).collect();
        self.force.force(t, q, v, &u, out);
    }
}

/// Piecewise-constant controls on a grid as a core [`Force`]: `u_k` for `t ∈ [t_k, t_{k+1})`.
///
/// For feeding a solution's controls to [`marsden::Integrator`]: exact for rules that sample
/// the force strictly inside a step (midpoint, the α rules with `0 < α < 1`); a rule with a
/// node at a step's end (trapezoid) would see the next step's control there.
#[derive(Debug, Clone)]
pub struct SampledControl<F> {
    /// The controlled force.
    pub force: F,
    /// The grid of the controls.
    pub grid: TimeGrid,
    /// `u_0 … u_{N−1}`.
    pub u: Vec<Vec<f64>>,
}

impl<F: ControlForce> Force for SampledControl<F> {
    fn force<S: Scalar>(&self, t: S, q: &[S], v: &[S], out: &mut [S]) {
        let s = ((t.re() - self.grid.t0) / self.grid.h).floor();
        let k = if s > 0.0 { s as usize } else { 0 };
        let k = k.min(self.u.len().saturating_sub(1));
        let u: Vec<S> = self.u[k].iter().map(|&x| S::from(x)).collect();
        self.force.force(t, q, v, &u, out);
    }
}

/// The controls of one step of a solution as a core [`Force`]: the polynomial through the
/// step's stage values (constant for one value per step), so that the rule's quadrature nodes
/// see the values the transcription gave them ([`crate::stages`]).
#[derive(Debug, Clone)]
pub struct StepControl<'a, F> {
    /// The controlled force.
    pub force: F,
    /// The step's start `t_k` and length `h`.
    pub step: (f64, f64),
    /// The stage times.
    pub stages: &'a ControlStages,
    /// The step's control values, stage by stage.
    pub u: &'a [Vec<f64>],
}

impl<F: ControlForce> Force for StepControl<'_, F> {
    fn force<S: Scalar>(&self, t: S, q: &[S], v: &[S], out: &mut [S]) {
        let (t0, h) = self.step;
        let mut weights = vec![0.0; self.stages.count()];
        self.stages.weights_at((t.re() - t0) / h, &mut weights);
        let m = self.u.first().map_or(0, Vec::len);
        let u: Vec<S> = (0..m)
            .map(|j| {
                let value = (weights.iter().zip(self.u)).fold(0.0, |s, (w, u)| s + w * u[j]);
                S::from(value)
            })
            .collect();
        self.force.force(t, q, v, &u, out);
    }
}

/// The flat initial guess `z` of `problem` in `layout`: the nodes, each step's control (at
/// every stage) and its inner control points on the straight line between its nodes.
pub(crate) fn initial<L, F, C, P, G, R>(
    problem: &OptimalControl<L, F, C, P, G>,
    rule: &R,
    stages: &ControlStages,
    layout: &Layout,
) -> Vec<f64>
where
    L: Lagrangian,
    F: ControlForce,
    C: RunningCost,
    P: FinalCost,
    G: PathConstraint,
    R: Rule,
{
    let nodes = match &problem.guess {
        Some(guess) => guess.q.clone(),
        None => default_nodes(problem, rule),
    };
    let mut z = vec![0.0; layout.unknowns()];
    let n = layout.n;
    for (k, q) in nodes.iter().enumerate() {
        z[layout.q(k)..layout.q(k) + n].copy_from_slice(q);
    }
    for (k, ends) in nodes.windows(2).enumerate() {
        let inner = &stages.points[1..stages.points.len() - 1];
        for (j, d) in inner.iter().enumerate() {
            let at = layout.inner_points(k) + j * n;
            for i in 0..n {
                z[at + i] = ends[0][i] + d * (ends[1][i] - ends[0][i]);
            }
        }
    }
    if let Some(guess) = &problem.guess {
        for (k, u) in guess.u.iter().enumerate() {
            for stage in 0..layout.stages {
                let at = layout.u(k) + stage * layout.m;
                z[at..at + layout.m].copy_from_slice(u);
            }
        }
    }
    z
}

fn default_nodes<L, F, C, P, G, R>(
    problem: &OptimalControl<L, F, C, P, G>,
    rule: &R,
) -> Vec<Vec<f64>>
where
    L: Lagrangian,
    F: ControlForce,
    C: RunningCost,
    P: FinalCost,
    G: PathConstraint,
    R: Rule,
{
    let steps = problem.grid.steps;
    let (start, end) = (&problem.start, &problem.end);
    let n = problem.dof();
    let a: Vec<f64> = (0..n)
        .map(|i| start.q[i].or(end.q[i]).unwrap_or(0.0))
        .collect();
    if start.q.iter().chain(&end.q).all(Option::is_some) {
        let b: Vec<f64> = end.q.iter().map(|x| x.unwrap_or(0.0)).collect();
        return (0..=steps)
            .map(|k| {
                let s = k as f64 / steps as f64;
                a.iter().zip(&b).map(|(x, y)| x + s * (y - x)).collect()
            })
            .collect();
    }
    if start.is_complete()
        && let Some(nodes) = simulate(problem, rule, &a)
    {
        return nodes;
    }
    vec![a; steps + 1]
}

/// The core integrator's run from the (complete) start with `u = 0`, if it succeeds.
fn simulate<L, F, C, P, G, R>(
    problem: &OptimalControl<L, F, C, P, G>,
    rule: &R,
    q0: &[f64],
) -> Option<Vec<Vec<f64>>>
where
    L: Lagrangian,
    F: ControlForce,
    C: RunningCost,
    P: FinalCost,
    G: PathConstraint,
    R: Rule,
{
    let rate: Vec<f64> = problem
        .start
        .rate_values()
        .iter()
        .map(|x| x.unwrap_or(0.0))
        .collect();
    let initial = match problem.start.rate {
        Rate::Velocity(_) => Initial::velocity(q0, &rate),
        Rate::Momentum(_) => Initial::momentum(q0, &rate),
    };
    let zero = FrozenControl {
        force: &problem.force,
        u: vec![0.0; problem.controls()],
    };
    let run = Problem::new(&problem.lagrangian, initial, problem.grid)
        .ok()?
        .with_force(zero);
    let trajectory = run.solve(rule, &SolveOptions::default()).ok()?;
    if trajectory.len() != problem.grid.steps + 1 {
        return None;
    }
    Some(
        (0..trajectory.len())
            .map(|k| trajectory.q(k).to_vec())
            .collect(),
    )
}
