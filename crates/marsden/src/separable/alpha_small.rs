//! The separable α step for small systems with a diagonal mass: sizes known at compile time.
//!
//! The equations, the Newton iteration and its stopping tests are those of the parent module
//! ([`crate::separable::alpha`]; exact Newton, a fresh Jacobian per update, as there for `n` below
//! [`super::REUSE_MIN_DOF`]):
//!
//! ```text
//!     R(Δ)    = p_k − M Δ/h − h(1−α) ∇V(q_α),      q_α = q_k + αΔ,
//!     p_{k+1} = M Δ/h − hα ∇V(q_α),
//!     A       = M/h + hα(1−α) ∇²V(q_α),            Δ ← Δ + A⁻¹R,
//! ```
//!
//! with every quantity in a stack array of length `N ≤ 4` and `A` solved in place: no vectors,
//! no band storage in the loop. The parent dispatches here once per step on `n`; the same
//! arithmetic in the same order makes both paths agree to round-off (test
//! `separable_fast_path.rs`).

use super::step::{Frame, Mass, SeparableWorkspace, node};
use crate::mechanics::Lagrangian;
use crate::numerics::dense::{max_norm, packed_index, solve_fixed};
use crate::numerics::newton::{Convergence, NewtonFailure, NewtonOptions, NewtonReport};

/// The step for `n ≤ 4` with a diagonal mass; `None` for other systems.
pub(super) fn solve_alpha_small<L: Lagrangian>(
    l: &L,
    alpha: f64,
    frame: Frame<'_>,
    z: &mut [f64],
    p_next: &mut [f64],
    options: &NewtonOptions,
    ws: &mut SeparableWorkspace,
) -> Option<Result<NewtonReport, NewtonFailure>> {
    match frame.q0.len() {
        1 => solve::<L, 1>(l, alpha, frame, z, p_next, options, ws),
        2 => solve::<L, 2>(l, alpha, frame, z, p_next, options, ws),
        3 => solve::<L, 3>(l, alpha, frame, z, p_next, options, ws),
        4 => solve::<L, 4>(l, alpha, frame, z, p_next, options, ws),
        _ => None,
    }
}

/// One iterate: residual `R`, `p_{k+1}`, `‖R‖∞` and the size of the residual's terms.
struct Iterate<const N: usize> {
    residual: [f64; N],
    p_next: [f64; N],
    norm: f64,
    scale: f64,
}

/// The α-rule data of one step.
struct Step<'a, L, const N: usize> {
    l: &'a L,
    alpha: f64,
    frame: Frame<'a>,
    mass: [f64; N],
}

impl<L: Lagrangian, const N: usize> Step<'_, L, N> {
    fn node(&self, delta: &[f64; N]) -> [f64; N] {
        let mut q = [0.0; N];
        node(self.alpha, self.frame.q0, delta, &mut q);
        q
    }

    /// `R(Δ)` and `p_{k+1}` at `delta` (one gradient of `V`).
    #[inline(always)]
    fn evaluate(&self, delta: &[f64; N], scratch: &mut Vec<f64>) -> Iterate<N> {
        let Frame { t0, h, p0, .. } = self.frame;
        let mut g = [0.0; N];
        self.l
            .potential_gradient(t0 + self.alpha * h, &self.node(delta), &mut g, scratch);
        let inv_h = 1.0 / h;
        let (w0, w1) = (h * (1.0 - self.alpha), h * self.alpha);
        let mv: [f64; N] = std::array::from_fn(|i| self.mass[i] * (delta[i] * inv_h));
        let d_q0: [f64; N] = std::array::from_fn(|i| -mv[i] - w0 * g[i]);
        let residual: [f64; N] = std::array::from_fn(|i| d_q0[i] + p0[i]);
        let norm =
            residual.iter().fold(
                0.0_f64,
                |m, r| {
                    if r.is_nan() { f64::NAN } else { m.max(r.abs()) }
                },
            );
        let scale = (0..N).fold(0.0_f64, |m, i| m.max(d_q0[i].abs()).max(p0[i].abs()));
        Iterate {
            residual,
            p_next: std::array::from_fn(|i| mv[i] - w1 * g[i]),
            norm,
            scale,
        }
    }

    /// `A = M/h + hα(1−α)∇²V` at `delta` (one Hessian of `V`: its packed upper triangle if
    /// [`Lagrangian::potential_hessian_packed`] gives it, else through the band storage of the
    /// workspace, which [`Lagrangian::potential_hessian`] fills).
    fn jacobian(&self, delta: &[f64; N], ws: &mut SeparableWorkspace) -> [[f64; N]; N] {
        let Frame { t0, h, .. } = self.frame;
        let (t, q) = (t0 + self.alpha * h, self.node(delta));
        let mut packed = [0.0; 10];
        let packed = &mut packed[..N * (N + 1) / 2];
        if self.l.potential_hessian_packed(t, &q, packed) {
            return self.matrix(|i, j| packed[packed_index(N, i.min(j), i.max(j))]);
        }
        ws.hess.reshape(N, N - 1);
        self.l.potential_hessian(t, &q, &mut ws.hess);
        self.matrix(|i, j| ws.hess.get(i, j))
    }

    /// `M/h + hα(1−α) H` for the entries `hess(i, j)` of `H = ∇²V`.
    #[inline(always)]
    fn matrix(&self, hess: impl Fn(usize, usize) -> f64) -> [[f64; N]; N] {
        let h = self.frame.h;
        let c = h * self.alpha * (1.0 - self.alpha);
        let inv_h = 1.0 / h;
        std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                let m = if i == j { self.mass[i] } else { 0.0 };
                m * inv_h + c * hess(i, j)
            })
        })
    }
}

fn solve<L: Lagrangian, const N: usize>(
    l: &L,
    alpha: f64,
    frame: Frame<'_>,
    z: &mut [f64],
    p_next: &mut [f64],
    options: &NewtonOptions,
    ws: &mut SeparableWorkspace,
) -> Option<Result<NewtonReport, NewtonFailure>> {
    let Some(Some(Mass::Diagonal(d))) = &ws.mass else {
        return None;
    };
    let mass: [f64; N] = d.as_slice().try_into().ok()?;
    let step = Step {
        l,
        alpha,
        frame,
        mass,
    };
    let mut delta: [f64; N] = z.get(..N)?.try_into().ok()?;
    let q_scale = max_norm(frame.q0).max(f64::MIN_POSITIVE);
    let mut report = NewtonReport::default();
    let mut convergence = Convergence::new(options);
    loop {
        let it = step.evaluate(&delta, &mut ws.scratch);
        report.evaluations += 1;
        report.residual = it.norm;
        match convergence.check(&report, it.scale) {
            Ok(false) => {}
            Ok(true) => {
                z[..N].copy_from_slice(&delta);
                p_next.copy_from_slice(&it.p_next);
                return Some(Ok(report));
            }
            Err(failure) => return Some(Err(failure)),
        }
        let mut a = step.jacobian(&delta, ws);
        report.factorizations += 1;
        let mut update = it.residual;
        if let Err(s) = solve_fixed(&mut a, &mut update) {
            return Some(Err(NewtonFailure::Singular {
                iteration: report.iterations,
                pivot: s.pivot,
            }));
        }
        report.iterations += 1;
        let size = max_norm(&update);
        delta.iter_mut().zip(&update).for_each(|(d, u)| *d += u);
        let znorm = delta.iter().fold(q_scale, |m, d| m.max(d.abs()));
        convergence.record_update(size, znorm);
    }
}
