//! One step of the transcription as a function of its local unknowns
//! `w = (q_k, u_k, Q_1 … Q_{s−1}, q_{k+1})`: the step's nodes, its control values
//! ([`ControlStages`]: one, or one per stage) and the rule's inner control points (none for a
//! two-point rule).
//!
//! The rule's discrete action gives `D_jL_d` at every control point `Q_j` (by nested dual
//! numbers, so that the drivers of `marsden::numerics::ad` differentiate them once more for the
//! constraint Jacobian and twice more for the Hessian of the Lagrangian): `D₀` and `D_s` enter
//! the forced discrete Euler–Lagrange equations at the nodes, the inner ones are the step's own
//! equations `D_jL_d + f_j = 0` (the Newton system the core's step solves, [`marsden::Rule`]).
//! The controls enter the rule's own force quadrature as coordinates of the augmented
//! configuration `x = (q, u)`: with one value per step the offset of `u` is zero over the step,
//! so every node of the quadrature sees `u_k` exactly and the discrete forces are the core's
//! `f_d^±` of `f(·, ·, ·, u_k)` bit for bit; with stage values the control points of `u` carry
//! the polynomial through them ([`crate::stages`]). The running cost is discretised the same
//! way, as a Lagrangian on `(q, u)`: midpoint `h C(t_{k+½}, q_{k+½}, v_k, u_k)`, trapezoid
//! `(h/2)[C(t_k, q_k, v_k, u_k) + C(t_{k+1}, q_{k+1}, v_k, u_k)]`, Gauss
//! `h Σ_i b_i C(t_k + c_i h, q(c_i h), q̇(c_i h), u_{k,i})` ([OJM11] §3.2, §4.2).
//!
//! [OJM11]: crate#references

use marsden::numerics::ad::{self, MultiFunction};
use marsden::{DiscreteAction, DiscreteForce, Force, Lagrangian, Scalar};

use crate::model::{ControlForce, FinalCost, RunningCost};
use crate::stages::ControlStages;

/// The controlled force on the augmented coordinates `x = (q, u)`: `(f(t, q, v, u), 0)`.
#[derive(Debug, Clone)]
pub struct Augmented<F> {
    /// The controlled force.
    pub force: F,
    /// Degrees of freedom `n`.
    pub n: usize,
}

impl<F: ControlForce> Force for Augmented<F> {
    fn force<S: Scalar>(&self, t: S, x: &[S], w: &[S], out: &mut [S]) {
        let n = self.n;
        out[n..].iter_mut().for_each(|f| *f = S::from(0.0));
        self.force
            .force(t, &x[..n], &w[..n], &x[n..], &mut out[..n]);
    }
}

/// The running cost as a Lagrangian on `x = (q, u)`, so that the rule's quadrature of `L`
/// applies to it: `ℓ(t, x, ẋ) = C(t, q, q̇, u)`.
#[derive(Debug, Clone)]
pub struct CostLagrangian<C> {
    /// The running cost.
    pub cost: C,
    /// Degrees of freedom `n`.
    pub n: usize,
    /// Number of controls `m`.
    pub m: usize,
}

impl<C: RunningCost> Lagrangian for CostLagrangian<C> {
    fn dof(&self) -> usize {
        self.n + self.m
    }
    fn lagrangian<S: Scalar>(&self, t: S, x: &[S], w: &[S]) -> S {
        let n = self.n;
        self.cost.cost(t, &x[..n], &w[..n], &x[n..])
    }
}

/// `L_d(Q₀, …, Q_s)` of one step as a function of its control points (the offset form of the
/// action: `Δ_j = Q_j − Q₀`).
struct OnPoints<'a, A> {
    ld: &'a A,
    t0: f64,
    h: f64,
    n: usize,
    /// Control points `s + 1`.
    points: usize,
}

impl<A: DiscreteAction> MultiFunction for OnPoints<'_, A> {
    fn inputs(&self) -> usize {
        self.points * self.n
    }
    fn outputs(&self) -> usize {
        1
    }
    fn eval<S: Scalar>(&self, x: &[S], out: &mut [S]) {
        let (q0, later) = x.split_at(self.n);
        let offsets: Vec<S> = (later.iter().enumerate())
            .map(|(i, &b)| b - q0[i % self.n])
            .collect();
        out[0] = self.ld.action(self.t0, self.h, q0, &offsets);
    }
}

/// The step's discrete objects: `L_d`, the augmented discrete force and discrete cost.
pub struct StepParts<'a, A, FD, CD, P> {
    /// `L_d` of the system.
    pub ld: &'a A,
    /// `f_d^±` of [`Augmented`] (on `n + m` coordinates).
    pub fd: &'a FD,
    /// The discrete running cost (the rule applied to [`CostLagrangian`]).
    pub cd: &'a CD,
    /// `Φ(q_N, p_N)`, on the last step only.
    pub final_cost: Option<&'a P>,
    /// How the step sees its controls ([`ControlStages`]).
    pub stages: &'a ControlStages,
    /// Degrees of freedom `n`.
    pub n: usize,
    /// Number of controls `m`.
    pub m: usize,
}

impl<A, FD, CD, P> Clone for StepParts<'_, A, FD, CD, P> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<A, FD, CD, P> Copy for StepParts<'_, A, FD, CD, P> {}

/// Step `k` from `t0` with step `h`: inputs `w = (q_k, u_{k,1…σ}, Q_1 … Q_{s−1}, q_{k+1})`
/// (`2n + σm + (s−1)n`), outputs `(D₀L_d + f_0, D_sL_d + f_s, C_d [+ Φ], D_jL_d + f_j for the
/// inner points j = 1 … s−1)` (`2n + 1 + (s−1)n`).
pub struct StepFunction<'a, A, FD, CD, P> {
    /// The discrete objects.
    pub parts: StepParts<'a, A, FD, CD, P>,
    /// Start of the step.
    pub t0: f64,
    /// Step size.
    pub h: f64,
}

impl<A, FD, CD, P> StepFunction<'_, A, FD, CD, P> {
    /// The augmented control points `X_j = (Q_j, U_j)` as `X_0` and the offsets `X_j − X_0`.
    fn augmented<S: Scalar>(&self, q: &[S], u: &[S]) -> (Vec<S>, Vec<S>) {
        let StepParts { n, m, stages, .. } = self.parts;
        let sigma = stages.count();
        let points = stages.points.len();
        let zero = S::from(0.0);
        let control = |j: usize, c: usize| {
            let row = &stages.to_points[j * sigma..(j + 1) * sigma];
            (row.iter().enumerate()).fold(zero, |s, (i, &e)| s + u[i * m + c] * e)
        };
        let x0: Vec<S> = (0..n + m)
            .map(|a| if a < n { q[a] } else { control(0, a - n) })
            .collect();
        let offsets = (1..points)
            .flat_map(|j| (0..n + m).map(move |a| (j, a)))
            .map(|(j, a)| match a < n {
                true => q[j * n + a] - q[a],
                false => control(j, a - n) - x0[a],
            })
            .collect();
        (x0, offsets)
    }
}

impl<A, FD, CD, P> MultiFunction for StepFunction<'_, A, FD, CD, P>
where
    A: DiscreteAction,
    FD: DiscreteForce,
    CD: DiscreteAction,
    P: FinalCost,
{
    fn inputs(&self) -> usize {
        let StepParts { n, m, stages, .. } = self.parts;
        2 * n + stages.count() * m + stages.inner() * n
    }
    fn outputs(&self) -> usize {
        2 * self.parts.n + 1 + self.parts.stages.inner() * self.parts.n
    }
    fn eval<S: Scalar>(&self, w: &[S], out: &mut [S]) {
        let StepParts { n, m, stages, .. } = self.parts;
        let (q0, rest) = w.split_at(n);
        let (u, later) = rest.split_at(stages.count() * m);
        let points = stages.points.len();
        let on_points = OnPoints {
            ld: self.parts.ld,
            t0: self.t0,
            h: self.h,
            n,
            points,
        };
        let q: Vec<S> = q0.iter().chain(later).copied().collect();
        let mut d = vec![S::from(0.0); points * n];
        ad::nested_gradient(&on_points, &q, 0..points * n, &mut d);
        let (xa, offsets) = self.augmented(&q, u);
        let nm = n + m;
        let mut f = vec![S::from(0.0); points * nm];
        self.parts
            .fd
            .discrete_force(self.t0, self.h, &xa, &offsets, &mut f);
        // Point j's row: the start, the end, then the inner points after the cost.
        let slot = |j: usize| match j {
            0 => 0,
            j if j + 1 == points => n,
            j => 2 * n + 1 + (j - 1) * n,
        };
        for j in 0..points {
            for i in 0..n {
                out[slot(j) + i] = d[j * n + i] + f[j * nm + i];
            }
        }
        let mut cost = self.parts.cd.action(self.t0, self.h, &xa, &offsets);
        if let Some(phi) = self.parts.final_cost {
            cost += phi.cost(&q[(points - 1) * n..], &out[n..2 * n]);
        }
        out[2 * n] = cost;
    }
}

/// `p = ∂L/∂v(t, q, v)` at fixed `t, v` as a function of `q` (a boundary velocity given as a
/// condition on the momentum).
pub struct BoundaryMomentum<'a, L> {
    /// The system.
    pub lagrangian: &'a L,
    /// The boundary time.
    pub t: f64,
    /// The boundary velocity.
    pub v: Vec<f64>,
}

/// `L(t, q, v)` as a function of `(q, v)`.
struct OnTangentBundle<'a, L> {
    lagrangian: &'a L,
    t: f64,
}

impl<L: Lagrangian> MultiFunction for OnTangentBundle<'_, L> {
    fn inputs(&self) -> usize {
        2 * self.lagrangian.dof()
    }
    fn outputs(&self) -> usize {
        1
    }
    fn eval<S: Scalar>(&self, z: &[S], out: &mut [S]) {
        let (q, v) = z.split_at(self.lagrangian.dof());
        out[0] = self.lagrangian.lagrangian(S::from(self.t), q, v);
    }
}

impl<L: Lagrangian> MultiFunction for BoundaryMomentum<'_, L> {
    fn inputs(&self) -> usize {
        self.lagrangian.dof()
    }
    fn outputs(&self) -> usize {
        self.lagrangian.dof()
    }
    fn eval<S: Scalar>(&self, q: &[S], out: &mut [S]) {
        let n = q.len();
        let z: Vec<S> = q
            .iter()
            .copied()
            .chain(self.v.iter().map(|&v| S::from(v)))
            .collect();
        let tangent = OnTangentBundle {
            lagrangian: self.lagrangian,
            t: self.t,
        };
        ad::nested_gradient(&tangent, &z, n..2 * n, out);
    }
}

/// `Σ_i weights_i f_i(x)`: the part of the Lagrangian of the program one function contributes,
/// for its Hessian.
pub struct Weighted<'a, F> {
    /// The function.
    pub f: &'a F,
    /// One weight per output.
    pub weights: &'a [f64],
}

impl<F: MultiFunction> MultiFunction for Weighted<'_, F> {
    fn inputs(&self) -> usize {
        self.f.inputs()
    }
    fn outputs(&self) -> usize {
        1
    }
    fn eval<S: Scalar>(&self, x: &[S], out: &mut [S]) {
        let mut values = vec![S::from(0.0); self.f.outputs()];
        self.f.eval(x, &mut values);
        out[0] = values
            .iter()
            .zip(self.weights)
            .filter(|&(_, &w)| w != 0.0)
            .fold(S::from(0.0), |s, (&v, &w)| s + v * w);
    }
}
