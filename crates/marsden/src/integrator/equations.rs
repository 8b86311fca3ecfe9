//! The implicit equations of one step, assembled for Newton's method.
//!
//! Unknowns `z = (Δ₁, …, Δ_s, λ, Λ₁, …, Λ_c)`: the offsets `Δ_j = Q_j − q_k` of the control points
//! after `Q₀ = q_k` (so `q_{k+1} = q_k + Δ_s`) and the constraint multipliers. Offsets, not
//! positions, keep velocities `Δ/h` free of the `ε|q|/h` cancellation error of `(q_{k+1} − q_k)/h`.
//! Equations ([conventions](crate#conventions); forced DEL in position–momentum form, [MW01] §3.2;
//! SHAKE, [LMO08]):
//!
//! ```text
//!     p_k + ∂L_d/∂Q₀ + F₀ − h Dφ(q_k)ᵀ λ = 0          (discrete Legendre transform F⁻)
//!           ∂L_d/∂Q_j + F_j               = 0,  0 < j < s   (internal stages)
//!     φ(Q_s)                              = 0          (holonomic constraints)
//! ```
//!
//! With stage constraints ([`DiscreteAction::constrained_stages`]: constrained Lobatto IIIA–IIIB,
//! [Jay96]; compositions of RATTLE steps, [Rei96]) the action is augmented by the constraint at
//! the `c` stage points `X_i` (linear in the control points), one multiplier `Λ_i` each:
//!
//! ```text
//!     L_d  →  L_d − h Σ_i ⟨Λ_i, φ(X_i)⟩,        φ(X_i) = 0,  i = 1 … c,
//! ```
//!
//! so its derivatives carry the stage constraint forces (and the Newton matrix their curvature
//! `Λ_i·∇²φ`) through the same hyper-dual evaluation. The Jacobian column of `Λ_i` in the
//! momentum rows needs `∂φ(X_i)/∂Q₀`, which by translation invariance (`Σ_j ∂X_i/∂Q_j = I`) is
//! `Dφ(X_i) − Σ_{j≥1} ∂φ(X_i)/∂Q_j`; `Dφ(X_i)` is evaluated beside.
//!
//! and afterwards `p_{k+1} = ∂L_d/∂Q_s + F_s` (discrete Legendre transform F⁺). One hyper-dual
//! evaluation of `(L_d, F, φ)` with eps₁ seeded on `Q₀ … Q_{s−1}` and eps₂ on `Q₁ … Q_s` gives
//! the residual (eps₁ part of `L_d`, values of `F`, `φ`), the Jacobian (eps₁eps₂ part of `L_d`,
//! eps₂ parts of `F` and `φ`) and `p_{k+1}` (eps₂ part of `L_d`, last block) at once. In offset
//! variables `∂/∂Q₀` (all other `Q_j` fixed) is the direction `(e, −e, …, −e)`; the seeds of `q₀`
//! are therefore subtracted from every offset inside the evaluation ([`StepFunction`]), which
//! leaves the offsets' real parts untouched.
//!
//! [MW01]: crate#references
//! [LMO08]: crate#references
//! [Jay96]: crate#references
//! [Rei96]: crate#references

use crate::discrete::lagrangian::fixed_points;
use crate::discrete::{DiscreteAction, DiscreteForce};
use crate::mechanics::{Constraint, constraint_jacobian};
use crate::numerics::ad::{self, HessianParts, MultiFunction};
use crate::numerics::dense::max_norm;
use crate::numerics::newton::NonlinearSystem;
use crate::numerics::scratch::{Buffer, NODE};
use crate::scalar::Scalar;

/// Sizes of a step's Newton system.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StepShape {
    /// Degrees of freedom.
    pub n: usize,
    /// Number of step segments `s` (internal stages + 1): control points `Q₀ … Q_s`.
    pub s: usize,
    /// Number of constraints.
    pub d: usize,
    /// Whether a force contributes.
    pub forced: bool,
    /// Stage constraints: interior points with `φ = 0` imposed (0 without constraints).
    pub stages: usize,
}

impl StepShape {
    /// Number of control points times n: `(s + 1)·n`.
    pub fn points_len(&self) -> usize {
        (self.s + 1) * self.n
    }
    /// Number of unknowns `s·n + d·(1 + c)` (`c` stage constraints).
    pub fn unknowns(&self) -> usize {
        self.s * self.n + self.multipliers()
    }
    /// Number of multipliers `d·(1 + c)`: `λ` at the step start, then `Λ₁ … Λ_c`.
    pub fn multipliers(&self) -> usize {
        self.d * (1 + self.stages)
    }
    fn force_outputs(&self) -> usize {
        if self.forced { self.points_len() } else { 0 }
    }
}

/// Inline capacity for the offsets of a step (`s·n`).
const OFFSETS: usize = 16;

/// `(L_d, F, φ)` of one step as a vector function of `q₀` and the offsets.
pub(crate) struct StepFunction<'a, A, F, C> {
    pub action: &'a A,
    pub force: &'a F,
    pub constraint: &'a C,
    pub t0: f64,
    pub h: f64,
    pub shape: StepShape,
    /// The stage multipliers `Λ₁ … Λ_c` of the current iterate (empty without stages).
    pub stage_multipliers: Vec<f64>,
}

impl<A: DiscreteAction, F: DiscreteForce, C: Constraint> MultiFunction
    for StepFunction<'_, A, F, C>
{
    const MAX_INPUTS: Option<usize> = fixed_points::<A>();
    fn inputs(&self) -> usize {
        self.shape.points_len()
    }
    fn outputs(&self) -> usize {
        1 + self.shape.force_outputs() + self.shape.multipliers()
    }
    #[inline]
    fn eval<S: Scalar>(&self, x: &[S], out: &mut [S]) {
        let sh = self.shape;
        let (q0, offsets) = x.split_at(sh.n);
        let zero = S::from(0.0);
        // Δ_j − (q₀ − re q₀): same real part, derivatives taken with Q_j = q₀ + Δ_j held fixed.
        let shifted = |i: usize| {
            let a = q0[i % sh.n];
            offsets[i] + (S::from(a.re()) - a)
        };
        let mut held = Buffer::<S, OFFSETS>::empty();
        let offsets: &[S] = held.from_fn(offsets.len(), zero, shifted);
        out[0] = self.action.action(self.t0, self.h, q0, offsets);
        let nf = sh.force_outputs();
        if nf > 0 {
            let forces = &mut out[1..1 + nf];
            self.force
                .discrete_force(self.t0, self.h, q0, offsets, forces);
        }
        if sh.d > 0 {
            let last = &offsets[(sh.s - 1) * sh.n..];
            let mut q_end = Buffer::<S, NODE>::empty();
            let q_end = q_end.from_fn(sh.n, zero, |i| q0[i] + last[i]);
            self.constraint
                .constraint(q_end, &mut out[1 + nf..1 + nf + sh.d]);
            if sh.stages > 0 {
                self.stage_constraints(q0, offsets, &mut out[..]);
            }
        }
    }
}

impl<A: DiscreteAction, F, C: Constraint> StepFunction<'_, A, F, C> {
    /// `φ(X_i)` into the stage outputs and `−h Σ_i ⟨Λ_i, φ(X_i)⟩` onto the action.
    #[inline]
    fn stage_constraints<S: Scalar>(&self, q0: &[S], offsets: &[S], out: &mut [S]) {
        let sh = self.shape;
        let zero = S::from(0.0);
        let first = 1 + sh.force_outputs() + sh.d;
        for i in 0..sh.stages {
            let block = first + i * sh.d;
            let mut stage = Buffer::<S, NODE>::empty();
            let x = stage.filled(sh.n, zero);
            self.action.stage_point(i, q0, offsets, x);
            self.constraint.constraint(x, &mut out[block..block + sh.d]);
            for c in 0..sh.d {
                let weight = self.h * self.stage_multipliers[i * sh.d + c];
                out[0] -= out[block + c] * weight;
            }
        }
    }
}

/// The Newton system of one step from `(q_k, p_k)`.
pub(crate) struct StepSystem<'a, A, F, C> {
    pub func: StepFunction<'a, A, F, C>,
    pub q0: &'a [f64],
    pub p0: &'a [f64],
    /// `Dφ(q_k)`, row-major d × n.
    pub dphi0: &'a [f64],
    /// `(q₀, Δ₁ … Δ_s)`, length `(s+1)·n`.
    pub points: &'a mut Vec<f64>,
    pub parts: &'a mut HessianParts,
    /// `p_{k+1}` at the last evaluated iterate.
    pub p_next: &'a mut [f64],
    /// AD evaluations (chunk pairs) performed.
    pub ad_evaluations: usize,
    /// Scratch for the stage constraints: `X_i`, `φ(X_i)`, `Dφ(X_i)` (n + d + d·n).
    pub stage_scratch: Vec<f64>,
}

impl<A: DiscreteAction, F: DiscreteForce, C: Constraint> NonlinearSystem
    for StepSystem<'_, A, F, C>
{
    fn dim(&self) -> usize {
        self.func.shape.unknowns()
    }

    fn residual_scale(&self) -> f64 {
        let n = self.func.shape.n;
        max_norm(self.p0)
            .max(max_norm(
                &self.parts.grad_rows[..n.min(self.parts.grad_rows.len())],
            ))
            .max(constraint_term_scale(self.q0, self.dphi0))
    }

    fn unknown_scale(&self, z: &[f64]) -> f64 {
        max_norm(self.q0).max(max_norm(z)).max(f64::MIN_POSITIVE)
    }

    fn evaluate(&mut self, z: &[f64], r: &mut [f64], jac: &mut [f64]) {
        let sh = self.func.shape;
        let (n, sn, m) = (sh.n, sh.s * sh.n, sh.unknowns());
        if sh.stages > 0 {
            let stage = &mut self.func.stage_multipliers;
            stage.clear();
            stage.extend_from_slice(&z[sn + sh.d..]);
        }
        self.points.clear();
        self.points.extend_from_slice(self.q0);
        self.points.extend_from_slice(&z[..sn]);
        ad::partial_hessian(&self.func, self.points, 0..sn, n..sn + n, self.parts);
        self.ad_evaluations += self.parts.evaluations;
        let parts = &*self.parts;
        let nf = sh.force_outputs();
        let lambda = &z[sn..sn + sh.d];
        // Momentum-balance and stage equations.
        for i in 0..sn {
            let force = if nf > 0 { parts.values[1 + i] } else { 0.0 };
            r[i] = parts.grad_rows[i] + force;
            let row = &mut jac[i * m..(i + 1) * m];
            let hess = &parts.hess[i * sn..(i + 1) * sn];
            for (j, (entry, second)) in row.iter_mut().zip(hess).enumerate() {
                let dforce = if nf > 0 {
                    parts.jac_cols[(1 + i) * sn + j]
                } else {
                    0.0
                };
                *entry = second + dforce;
            }
            row[sn..].fill(0.0);
        }
        for i in 0..n {
            r[i] += self.p0[i];
            for (c, l) in lambda.iter().enumerate() {
                let g = self.dphi0[c * n + i];
                r[i] -= self.func.h * g * l;
                jac[i * m + sn + c] = -self.func.h * g;
            }
        }
        // Constraint equations φ(Q_s) = 0.
        for c in 0..sh.d {
            let out = 1 + nf + c;
            r[sn + c] = parts.values[out];
            let row = &mut jac[(sn + c) * m..(sn + c + 1) * m];
            row[..sn].copy_from_slice(&parts.jac_cols[out * sn..(out + 1) * sn]);
            row[sn..].fill(0.0);
        }
        // p_{k+1} = ∂L_d/∂Q_s + F_s.
        for a in 0..n {
            let force = if nf > 0 {
                parts.values[1 + sn + a]
            } else {
                0.0
            };
            self.p_next[a] = parts.jac_cols[sn - n + a] + force;
        }
        if sh.stages > 0 {
            self.stage_rows(&z[..sn], r, jac);
        }
    }
}

impl<A: DiscreteAction, F: DiscreteForce, C: Constraint> StepSystem<'_, A, F, C> {
    /// The stage constraints' rows `φ(X_i) = 0` and the columns of their multipliers `Λ_i`:
    /// `−h ∂φ(X_i)/∂Q_b` in the row of `Q_b` (`Q₀` by translation invariance, see the module
    /// documentation).
    fn stage_rows(&mut self, offsets: &[f64], r: &mut [f64], jac: &mut [f64]) {
        let sh = self.func.shape;
        let (n, d, sn, m, h) = (sh.n, sh.d, sh.s * sh.n, sh.unknowns(), self.func.h);
        let nf = sh.force_outputs();
        self.stage_scratch.resize(n + d + d * n, 0.0);
        for i in 0..sh.stages {
            let (x, rest) = self.stage_scratch.split_at_mut(n);
            let (phi, dphi) = rest.split_at_mut(d);
            self.func.action.stage_point(i, self.q0, offsets, x);
            constraint_jacobian(self.func.constraint, x, phi, dphi);
            for c in 0..d {
                let out = 1 + nf + d * (1 + i) + c;
                let derivs = &self.parts.jac_cols[out * sn..(out + 1) * sn];
                let col = sn + d * (1 + i) + c;
                for a in 0..n {
                    let later: f64 = (0..sh.s).map(|j| derivs[j * n + a]).sum();
                    jac[a * m + col] = -h * (dphi[c * n + a] - later);
                }
                for row in n..sn {
                    jac[row * m + col] = -h * derivs[row - n];
                }
                let row = sn + d * (1 + i) + c;
                r[row] = self.parts.values[out];
                let entries = &mut jac[row * m..(row + 1) * m];
                entries[..sn].copy_from_slice(derivs);
                entries[sn..].fill(0.0);
            }
        }
    }
}

/// Size of the terms of the constraint rows `φ(q_{k+1}) = 0`, `‖q_k‖∞ ‖Dφ(q_k)‖_max` (for
/// `φ = ½(|q|² − l²)` about `l²`): with constraints the residual tolerance is relative to the
/// terms of both blocks, because `φ` can only be computed to `ε` times them — a scale from the
/// momenta alone (zero for a system at rest) could never be met.
pub(crate) fn constraint_term_scale(q0: &[f64], dphi0: &[f64]) -> f64 {
    if dphi0.is_empty() {
        0.0
    } else {
        max_norm(q0) * max_norm(dphi0)
    }
}
