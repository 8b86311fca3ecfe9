//! One step of the transcription as a function of its local unknowns `w = (q_k, u_k, q_{k+1})`.
//!
//! The rule's discrete Lagrangian gives `D₁L_d`, `D₂L_d` (by nested dual numbers, so that the
//! drivers of `marsden::numerics::ad` differentiate them once more for the constraint Jacobian
//! and twice more for the Hessian of the Lagrangian). The controls enter the rule's own force
//! quadrature as *frozen coordinates*: the rule discretises the force on `x = (q, u)` with the
//! offset of `u` zero over the step, so every node of its quadrature sees `u_k` exactly and the
//! discrete forces are the core's `f_d^±` of `f(·, ·, ·, u_k)` bit for bit. The running cost is
//! discretised the same way, as a Lagrangian on `(q, u)`: midpoint `h C(t_{k+½}, q_{k+½}, v_k,
//! u_k)`, trapezoid `(h/2)[C(t_k, q_k, v_k, u_k) + C(t_{k+1}, q_{k+1}, v_k, u_k)]`
//! ([OJM11] §3.2).
//!
//! [OJM11]: crate#references

use marsden::numerics::ad::{self, MultiFunction};
use marsden::{DiscreteAction, DiscreteForce, Force, Lagrangian, Scalar};

use crate::model::{ControlForce, FinalCost, RunningCost};

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

/// `L_d(q₀, q₁)` of one step as a function of `(q₀, q₁)` (the offset form of the action).
struct TwoPoint<'a, A> {
    ld: &'a A,
    t0: f64,
    h: f64,
    n: usize,
}

impl<A: DiscreteAction> MultiFunction for TwoPoint<'_, A> {
    fn inputs(&self) -> usize {
        2 * self.n
    }
    fn outputs(&self) -> usize {
        1
    }
    fn eval<S: Scalar>(&self, x: &[S], out: &mut [S]) {
        let (q0, q1) = x.split_at(self.n);
        let offsets: Vec<S> = q1.iter().zip(q0).map(|(&b, &a)| b - a).collect();
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

/// Step `k` from `t0` with step `h`: inputs `w = (q_k, u_k, q_{k+1})` (`2n + m`), outputs
/// `(D₁L_d + f_d⁻, D₂L_d + f_d⁺, C_d [+ Φ])` (`2n + 1`).
pub struct StepFunction<'a, A, FD, CD, P> {
    /// The discrete objects.
    pub parts: StepParts<'a, A, FD, CD, P>,
    /// Start of the step.
    pub t0: f64,
    /// Step size.
    pub h: f64,
}

impl<A, FD, CD, P> MultiFunction for StepFunction<'_, A, FD, CD, P>
where
    A: DiscreteAction,
    FD: DiscreteForce,
    CD: DiscreteAction,
    P: FinalCost,
{
    fn inputs(&self) -> usize {
        2 * self.parts.n + self.parts.m
    }
    fn outputs(&self) -> usize {
        2 * self.parts.n + 1
    }
    fn eval<S: Scalar>(&self, w: &[S], out: &mut [S]) {
        let StepParts { n, m, .. } = self.parts;
        let (q0, rest) = w.split_at(n);
        let (u, q1) = rest.split_at(m);
        let zero = S::from(0.0);
        let two_point = TwoPoint {
            ld: self.parts.ld,
            t0: self.t0,
            h: self.h,
            n,
        };
        let x: Vec<S> = q0.iter().chain(q1).copied().collect();
        ad::nested_gradient(&two_point, &x, 0..2 * n, &mut out[..2 * n]);
        // The augmented point (q_k, u_k) and its offset (q_{k+1} − q_k, 0).
        let xa: Vec<S> = q0.iter().chain(u).copied().collect();
        let mut offsets = vec![zero; n + m];
        offsets[..n]
            .iter_mut()
            .zip(q1.iter().zip(q0))
            .for_each(|(o, (&b, &a))| *o = b - a);
        let mut f = vec![zero; 2 * (n + m)];
        self.parts
            .fd
            .discrete_force(self.t0, self.h, &xa, &offsets, &mut f);
        for i in 0..n {
            out[i] += f[i];
            out[n + i] += f[n + m + i];
        }
        let mut cost = self.parts.cd.action(self.t0, self.h, &xa, &offsets);
        if let Some(phi) = self.parts.final_cost {
            cost += phi.cost(q1, &out[n..2 * n]);
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
