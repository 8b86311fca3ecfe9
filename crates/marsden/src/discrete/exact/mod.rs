//! The exact discrete Lagrangian `L_d^E(q₀, q₁, h) = ∫₀ʰ L(q₀₁(t), q̇₀₁(t)) dt`.
//!
//! Concept of the notes (MW01): *correspondence between discrete and continuous mechanics* ([MW01] §1.6). Along the
//! solution `q₀₁` of the Euler–Lagrange boundary value problem `q₀₁(0) = q₀`, `q₀₁(h) = q₁`,
//! the action is Hamilton's principal function, and its discrete Legendre transforms are the
//! continuous ones at the ends:
//!
//! ```text
//!     −D₁L_d^E(q₀, q₁) = FL(q₀, q̇₀₁(0)),        D₂L_d^E(q₀, q₁) = FL(q₁, q̇₀₁(h)),
//! ```
//!
//! so the discrete Hamiltonian map of `L_d^E` is the exact flow. Any other `L_d` is a
//! variational integrator of order `r` when `L_d − L_d^E = O(h^{r+1})` ([MW01] §2.3, variational
//! error analysis): [`local_error`] measures that difference.
//!
//! Here `L_d^E` is computed: the boundary value problem is solved by shooting ([`shooting`]) with
//! an extrapolation integrator of the Euler–Lagrange equations ([`flow`]) that carries the action
//! along. [`ExactDiscreteLagrangian`] is a [`DiscreteLagrangian`], so the ordinary
//! [`crate::integrator::Integrator`] steps it. Its derivatives are not obtained by differentiating through
//! the shooting: at a dual-number argument it returns the second-order Taylor polynomial of
//! `L_d^E` built from the transforms above (gradient `(−p₀, p₁)`) and the Hessian
//!
//! ```text
//!     D₁₁ = −∂p₀/∂q₀ = −L_vq(q₀,v₀) + L_vv(q₀,v₀) B⁻¹A,     D₁₂ = −L_vv(q₀,v₀) B⁻¹,
//!     D₂₂ =  ∂p₁/∂q₁ =  L_vq(q₁,v₁) + L_vv(q₁,v₁) D B⁻¹,
//! ```
//!
//! with the flow's Jacobian `∂(q, v)(h)/∂(q₀, v₀) = [[A, B], [C, D]]` (central differences).
//! The value and gradient are exact to the shooting's accuracy (round-off level); the Hessian
//! only steers Newton's method. A failed boundary value problem evaluates to NaN, which the
//! integrator reports as [`crate::error::StepError::NonFinite`]; call
//! [`ExactDiscreteLagrangian::boundary_value`] for the typed error.
//!
//! [MW01]: crate#references

pub mod flow;
pub mod shooting;

use crate::error::SetupError;
use std::sync::Mutex;

pub use flow::{EulerLagrangeFlow, FlowEnd, FlowOptions};
pub use shooting::BoundaryValue;

use crate::discrete::DiscreteLagrangian;
use crate::error::Error;
use crate::mechanics::Lagrangian;
use crate::mechanics::LagrangianJet;
use crate::numerics::dense::{Lu, max_norm};
use crate::scalar::Scalar;

/// `L_d^E` of a Lagrangian by shooting.
///
/// ```
/// use marsden::discrete::exact::ExactDiscreteLagrangian;
/// use marsden::systems::HarmonicOscillator;
///
/// let exact = ExactDiscreteLagrangian::new(HarmonicOscillator::default());
/// let h: f64 = 0.1;
/// // Hamilton's principal function of the unit oscillator along q(t) = cos t: −sin(2h)/4 (R3).
/// let ld = exact.value(0.0, h, &[1.0], &[h.cos()])?;
/// assert!((ld + (2.0 * h).sin() / 4.0).abs() < 1e-16);
/// # Ok::<(), marsden::Error>(())
/// ```
#[derive(Debug)]
pub struct ExactDiscreteLagrangian<L> {
    flow: EulerLagrangeFlow<L>,
    /// Last solved problem `(h, q₀, q₁, v₀)`: a warm start for nearby evaluations.
    last: Mutex<Option<WarmStart>>,
}

/// A solved shooting problem `(h, q₀, q₁, v₀)`.
type WarmStart = (f64, Vec<f64>, Vec<f64>, Vec<f64>);

impl<L: Lagrangian + Clone> Clone for ExactDiscreteLagrangian<L> {
    fn clone(&self) -> Self {
        Self {
            flow: self.flow.clone(),
            last: Mutex::new(None),
        }
    }
}

/// `L_d^E` and its derivatives at one point.
#[derive(Debug, Clone, PartialEq)]
pub struct ExactJet {
    /// `L_d^E(q₀, q₁)`.
    pub value: f64,
    /// `(D₁L_d^E, D₂L_d^E) = (−p₀, p₁)`, length 2n.
    pub gradient: Vec<f64>,
    /// The Hessian in `(q₀, q₁)`, row-major 2n × 2n (empty unless asked for).
    pub hessian: Vec<f64>,
    /// The boundary value solution behind it.
    pub solution: BoundaryValue,
}

impl<L: Lagrangian> ExactDiscreteLagrangian<L> {
    /// `L_d^E` of `lagrangian` with the default flow options (tolerance 1e-14).
    pub fn new(lagrangian: L) -> Self {
        Self::with_flow(EulerLagrangeFlow::new(lagrangian))
    }

    /// `L_d^E` computed with a configured flow.
    pub fn with_flow(flow: EulerLagrangeFlow<L>) -> Self {
        Self {
            flow,
            last: Mutex::new(None),
        }
    }

    /// The Euler–Lagrange flow used for shooting.
    pub fn flow(&self) -> &EulerLagrangeFlow<L> {
        &self.flow
    }

    /// Solves the boundary value problem `q(t₀) = q₀`, `q(t₀ + h) = q₁`.
    ///
    /// # Errors
    /// [`crate::error::SetupError::ShootingDidNotConverge`] (e.g. beyond the first conjugate
    /// time), and the flow's errors ([`EulerLagrangeFlow::advance`]).
    pub fn boundary_value(
        &self,
        t0: f64,
        h: f64,
        q0: &[f64],
        q1: &[f64],
    ) -> Result<BoundaryValue, Error> {
        Error::check_len("q0", q0, self.flow.lagrangian().dof())?;
        Error::check_len("q1", q1, q0.len())?;
        let guess = self.guess(h, q0, q1);
        let solution = shooting::solve(&self.flow, t0, h, q0, q1, &guess)?;
        if let Ok(mut last) = self.last.lock() {
            *last = Some((h, q0.to_vec(), q1.to_vec(), solution.v0.clone()));
        }
        Ok(solution)
    }

    /// The warm start: the last solution's `v₀` if its ends are close, else `(q₁ − q₀)/h`.
    fn guess(&self, h: f64, q0: &[f64], q1: &[f64]) -> Vec<f64> {
        let chord: Vec<f64> = q0.iter().zip(q1).map(|(a, b)| (b - a) / h).collect();
        let Ok(last) = self.last.lock() else {
            return chord;
        };
        match last.as_ref() {
            Some((hl, a, b, v)) if *hl == h && a.len() == q0.len() => {
                let distance = max_norm(&diff(a, q0)).max(max_norm(&diff(b, q1)));
                let size = max_norm(&diff(a, b)).max(1e-12);
                if distance <= 0.1 * size {
                    v.clone()
                } else {
                    chord
                }
            }
            _ => chord,
        }
    }

    /// `L_d^E(q₀, q₁, h)`.
    pub fn value(&self, t0: f64, h: f64, q0: &[f64], q1: &[f64]) -> Result<f64, Error> {
        Ok(self.boundary_value(t0, h, q0, q1)?.action)
    }

    /// The discrete Legendre transforms `(p₀, p₁) = (−D₁L_d^E, D₂L_d^E) = (FL(q₀, v₀), FL(q₁, v₁))`.
    pub fn momenta(
        &self,
        t0: f64,
        h: f64,
        q0: &[f64],
        q1: &[f64],
    ) -> Result<(Vec<f64>, Vec<f64>), Error> {
        let bv = self.boundary_value(t0, h, q0, q1)?;
        let l = self.flow.lagrangian();
        let (mut p0, mut p1) = (vec![0.0; q0.len()], vec![0.0; q0.len()]);
        crate::mechanics::momentum(l, t0, q0, &bv.v0, &mut p0);
        crate::mechanics::momentum(l, t0 + h, q1, &bv.v1, &mut p1);
        Ok((p0, p1))
    }

    /// Value, gradient and (if `hessian`) Hessian of `L_d^E` at `(q₀, q₁)`.
    pub fn jet(
        &self,
        t0: f64,
        h: f64,
        q0: &[f64],
        q1: &[f64],
        hessian: bool,
    ) -> Result<ExactJet, Error> {
        let n = q0.len();
        let solution = self.boundary_value(t0, h, q0, q1)?;
        let l = self.flow.lagrangian();
        let start = LagrangianJet::at(l, t0, q0, &solution.v0);
        let end = LagrangianJet::at(l, t0 + h, q1, &solution.v1);
        let gradient: Vec<f64> = start
            .dl_dv
            .iter()
            .map(|p| -p)
            .chain(end.dl_dv.iter().copied())
            .collect();
        let hessian = if hessian {
            self.hessian(t0, h, q0, &solution, &start, &end)?
        } else {
            Vec::new()
        };
        debug_assert_eq!(gradient.len(), 2 * n);
        Ok(ExactJet {
            value: solution.action,
            gradient,
            hessian,
            solution,
        })
    }

    fn hessian(
        &self,
        t0: f64,
        h: f64,
        q0: &[f64],
        bv: &BoundaryValue,
        start: &LagrangianJet,
        end: &LagrangianJet,
    ) -> Result<Vec<f64>, Error> {
        let n = q0.len();
        let scale = max_norm(q0).max(1e-8);
        let (a, c) = shooting::flow_derivatives(&self.flow, t0, h, q0, &bv.v0, false, scale)?;
        let _ = c;
        let mut lu = Lu::new();
        lu.factor(&bv.b, n).map_err(|_| {
            Error::Setup(SetupError::ShootingDidNotConverge {
                h,
                iterations: bv.iterations,
                residual: f64::NAN,
            })
        })?;
        // X = B⁻¹ A and Y = B⁻¹ (column by column).
        let solve_columns = |m: Option<&[f64]>| -> Vec<f64> {
            let mut out = vec![0.0; n * n];
            let mut col = vec![0.0; n];
            let mut scratch = Vec::with_capacity(n);
            for j in 0..n {
                for i in 0..n {
                    col[i] = m.map_or(if i == j { 1.0 } else { 0.0 }, |m| m[i * n + j]);
                }
                lu.solve(&mut col, &mut scratch);
                (0..n).for_each(|i| out[i * n + j] = col[i]);
            }
            out
        };
        let (x, y) = (solve_columns(Some(&a)), solve_columns(None));
        let mul = |p: &[f64], q: &[f64]| -> Vec<f64> {
            let mut out = vec![0.0; n * n];
            for i in 0..n {
                for j in 0..n {
                    out[i * n + j] = (0..n).map(|k| p[i * n + k] * q[k * n + j]).sum();
                }
            }
            out
        };
        let (mvx, mvy, dy) = (
            mul(&start.d2l_dv2, &x),
            mul(&start.d2l_dv2, &y),
            mul(&bv.d, &y),
        );
        let d22 = mul(&end.d2l_dv2, &dy);
        let mut hess = vec![0.0; 4 * n * n];
        let m = 2 * n;
        for i in 0..n {
            for j in 0..n {
                hess[i * m + j] = -start.d2l_dvdq[i * n + j] + mvx[i * n + j];
                hess[i * m + n + j] = -mvy[i * n + j];
                hess[(n + j) * m + i] = -mvy[i * n + j];
                hess[(n + i) * m + n + j] = end.d2l_dvdq[i * n + j] + d22[i * n + j];
            }
        }
        symmetrize(&mut hess, m);
        Ok(hess)
    }
}

fn diff(a: &[f64], b: &[f64]) -> Vec<f64> {
    a.iter().zip(b).map(|(x, y)| x - y).collect()
}

/// Replaces the diagonal blocks' small asymmetry (from differences) by the symmetric part.
fn symmetrize(h: &mut [f64], m: usize) {
    for i in 0..m {
        for j in i + 1..m {
            let s = 0.5 * (h[i * m + j] + h[j * m + i]);
            h[i * m + j] = s;
            h[j * m + i] = s;
        }
    }
}

/// `L_d(q₀, q₁) − L_d^E(q₀, q₁)`: the local (variational) error of a discrete Lagrangian
/// ([MW01] §2.3). `L_d` has order `r` when this is `O(h^{r+1})` along solutions.
///
/// [MW01]: crate#references
pub fn local_error<D: DiscreteLagrangian, L: Lagrangian>(
    ld: &D,
    exact: &ExactDiscreteLagrangian<L>,
    t0: f64,
    h: f64,
    q0: &[f64],
    q1: &[f64],
) -> Result<f64, Error> {
    Ok(ld.discrete_lagrangian(t0, h, q0, q1) - exact.value(t0, h, q0, q1)?)
}

impl<L: Lagrangian> DiscreteLagrangian for ExactDiscreteLagrangian<L> {
    fn dof(&self) -> usize {
        self.flow.lagrangian().dof()
    }

    /// At `f64`: the value. At dual numbers: the second-order Taylor polynomial of `L_d^E`
    /// around the real parts (exact first and second derivatives, see the module docs); NaN
    /// if the boundary value problem fails.
    fn discrete_lagrangian<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], q1: &[S]) -> S {
        let re = |x: &[S]| -> Vec<f64> { x.iter().map(|v| v.re()).collect() };
        let (a, b) = (re(q0), re(q1));
        let Ok(jet) = self.jet(t0, h, &a, &b, S::NDERIV >= 2) else {
            // NaN in the value *and every derivative*: `S::from(NaN)` alone has zero
            // derivatives, and a step's residual (made of derivatives) would read 0, i.e.
            // converged, on a boundary value problem that has no solution.
            return q0.iter().chain(q1).fold(S::from(f64::NAN), |s, x| {
                s + (*x - S::from(x.re())) * f64::NAN
            });
        };
        if S::NDERIV == 0 {
            return S::from(jet.value);
        }
        let delta: Vec<S> = q0.iter().chain(q1).map(|x| *x - S::from(x.re())).collect();
        let mut sum = S::from(jet.value);
        for (d, g) in delta.iter().zip(&jet.gradient) {
            sum += *d * *g;
        }
        let m = delta.len();
        if !jet.hessian.is_empty() {
            for i in 0..m {
                let mut row = S::from(0.0);
                for (d, hij) in delta.iter().zip(&jet.hessian[i * m..(i + 1) * m]) {
                    row += *d * *hij;
                }
                sum += delta[i] * row * 0.5;
            }
        }
        sum
    }
}
