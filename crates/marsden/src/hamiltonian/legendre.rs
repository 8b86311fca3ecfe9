//! The Legendre correspondence both ways, as adapters that are themselves generic over the
//! scalar: [`LegendreHamiltonian`] (`H` from `L`) and [`HamiltonianLagrangian`] (`L` from `H`).
//!
//! Concept of the notes (MW01): *Legendre transforms*. For a hyperregular `L` the fibre derivative `FL(q, v) =
//! (q, ∂L/∂v)` is a diffeomorphism with inverse `FH`, and ([MW01] §1.4, [MR99] §7.4)
//!
//! ```text
//!     H(t, q, p) = ⟨p, v⟩ − L(t, q, v),   v = FH(q, p)  solves  ∂L/∂v(t, q, v) = p,
//!     L(t, q, v) = ⟨p, v⟩ − H(t, q, p),   p = FL(q, v)  solves  ∂H/∂p(t, q, p) = v.
//! ```
//!
//! Both are the same construction `f*(w) = ⟨w, y⟩ − f(y)` at `∂f/∂y = w` (the fibre-wise
//! Legendre transform), implemented once. The inner solve is Newton's method in `f64`. To make the
//! result differentiable by the caller's dual numbers, the `f64` root `y₀` is then corrected by
//! one chord step *in the caller's scalar type*: `y = y₀ − M⁻¹(∂f/∂y(y₀) − w)` with
//! `M = ∂²f/∂y²(y₀)` and `∂f/∂y` by nested AD ([`crate::numerics::ad::nested_gradient`]). The error of `y`
//! is then `O(ε²)` in the dual parts, and since `∂f*/∂y = 0` at the root, the error of
//! `f*` is `O(ε⁴)`: value, gradient, Hessian and third derivatives of the adapter are exact.
//! Consequently `∂H/∂p = v = FH(q, p)` and `∂H/∂q = −∂L/∂q`, as the theory says.
//!
//! If the inner solve fails (a singular `∂²f/∂y²`: the system is not regular there), the generic
//! evaluation returns NaN, which the integrators report as a non-finite step; use
//! [`LegendreHamiltonian::try_value`] for a typed error.
//!
//! [MW01]: crate#references
//! [MR99]: crate#references

use super::Hamiltonian;
use crate::error::Error;
use crate::error::SetupError;
use crate::mechanics::Lagrangian;
use crate::numerics::ad::{self, HessianParts, MultiFunction};
use crate::numerics::dense::{Lu, max_norm};
use crate::scalar::Scalar;

/// A function `f(t, x, y)` whose fibre-wise Legendre transform in `y` is taken.
trait Fibre {
    fn dof(&self) -> usize;
    fn eval<S: Scalar>(&self, t: S, x: &[S], y: &[S]) -> S;
}

struct LFibre<'a, L>(&'a L);
impl<L: Lagrangian> Fibre for LFibre<'_, L> {
    fn dof(&self) -> usize {
        self.0.dof()
    }
    fn eval<S: Scalar>(&self, t: S, q: &[S], v: &[S]) -> S {
        self.0.lagrangian(t, q, v)
    }
}

struct HFibre<'a, H>(&'a H);
impl<H: Hamiltonian> Fibre for HFibre<'_, H> {
    fn dof(&self) -> usize {
        self.0.dof()
    }
    fn eval<S: Scalar>(&self, t: S, q: &[S], p: &[S]) -> S {
        self.0.hamiltonian(t, q, p)
    }
}

/// `f` as a function of `z = (t, x, y)` for the AD drivers.
struct FibreFn<'a, F>(&'a F);
impl<F: Fibre> MultiFunction for FibreFn<'_, F> {
    fn inputs(&self) -> usize {
        2 * self.0.dof() + 1
    }
    fn outputs(&self) -> usize {
        1
    }
    fn eval<S: Scalar>(&self, z: &[S], out: &mut [S]) {
        let n = self.0.dof();
        out[0] = self.0.eval(z[0], &z[1..=n], &z[n + 1..]);
    }
}

/// Short vectors of the adapters (not a hot path: the inner Newton solve dominates).
type Buf<S> = Vec<S>;

/// Newton's method for `∂f/∂y(t, x, y) = w` in `f64`, with backtracking.
struct FibreNewton<'a, F> {
    f: &'a F,
    w: &'a [f64],
    /// `(t, x, y)`.
    z: Vec<f64>,
    parts: HessianParts,
    /// `w − ∂f/∂y` at `z`.
    r: Vec<f64>,
}

impl<F: Fibre> FibreNewton<'_, F> {
    /// Evaluates derivatives at `z`; returns the residual max-norm (∞ if not finite).
    fn evaluate(&mut self) -> f64 {
        let n = self.f.dof();
        let ys = n + 1..2 * n + 1;
        ad::partial_hessian(&FibreFn(self.f), &self.z, ys.clone(), ys, &mut self.parts);
        for (i, ri) in self.r.iter_mut().enumerate() {
            *ri = self.w[i] - self.parts.grad_rows[i];
        }
        if self.r.iter().all(|x| x.is_finite()) {
            max_norm(&self.r)
        } else {
            f64::INFINITY
        }
    }
}

/// Solves `∂f/∂y(t, x, y) = w` for `y` in `f64` by Newton's method from `y = 0`, halving steps
/// that do not decrease the residual (so that e.g. a relativistic `|v| < c` is never left);
/// returns `y` and `M⁻¹ = (∂²f/∂y²)⁻¹` (row-major).
fn solve_fibre<F: Fibre>(
    f: &F,
    t: f64,
    x: &[f64],
    w: &[f64],
) -> Result<(Vec<f64>, Vec<f64>), Error> {
    const MAX_ITERATIONS: usize = 100;
    let n = f.dof();
    let tol = 1e-14 * max_norm(w).max(1.0);
    let z = std::iter::once(t)
        .chain(x.iter().copied())
        .chain(std::iter::repeat_n(0.0, n));
    let mut newton = FibreNewton {
        f,
        w,
        z: z.collect(),
        parts: HessianParts::default(),
        r: vec![0.0; n],
    };
    let (mut lu, mut scratch) = (Lu::new(), Vec::with_capacity(n));
    let mut residual = newton.evaluate();
    // `y = 0` may be where `∂²f/∂y²` is singular though the solution is regular (H = p⁴/4:
    // ∂²H/∂p² = 0 at rest only): start from `y = w` then, exact for a unit mass.
    if lu.factor(&newton.parts.hess, n).is_err() && w.iter().any(|x| *x != 0.0) {
        newton.z[n + 1..].copy_from_slice(w);
        residual = newton.evaluate();
    }
    let failure = |residual| {
        Error::Setup(SetupError::InverseLegendre {
            t,
            iterations: MAX_ITERATIONS,
            residual,
        })
    };
    for _ in 0..MAX_ITERATIONS {
        let factored = lu.factor(&newton.parts.hess, n);
        if factored.is_ok() && residual <= tol {
            return Ok((newton.z[n + 1..].to_vec(), inverse(&lu, n)));
        }
        factored.map_err(|_| failure(residual))?;
        let mut d = newton.r.clone();
        lu.solve(&mut d, &mut scratch);
        let y0 = newton.z[n + 1..].to_vec();
        let (mut alpha, previous) = (1.0, residual);
        loop {
            for ((y, a), di) in newton.z[n + 1..].iter_mut().zip(&y0).zip(&d) {
                *y = a + alpha * di;
            }
            residual = newton.evaluate();
            if residual < previous || alpha < 1e-10 {
                break;
            }
            alpha *= 0.5;
        }
        // At round-off the residual stops decreasing: accept if it is within 1e3 tolerances.
        let decreased = residual < previous;
        if !decreased && previous < 1e3 * tol {
            newton.z[n + 1..].copy_from_slice(&y0);
            newton.evaluate();
            lu.factor(&newton.parts.hess, n)
                .map_err(|_| failure(previous))?;
            return Ok((y0, inverse(&lu, n)));
        }
    }
    Err(failure(residual))
}

fn inverse(lu: &Lu, n: usize) -> Vec<f64> {
    let mut inv = vec![0.0; n * n];
    let (mut e, mut scratch) = (vec![0.0; n], Vec::with_capacity(n));
    for j in 0..n {
        e.fill(0.0);
        e[j] = 1.0;
        lu.solve(&mut e, &mut scratch);
        (0..n).for_each(|i| inv[i * n + j] = e[i]);
    }
    inv
}

/// `f*(t, x, w) = ⟨w, y⟩ − f(t, x, y)` at `∂f/∂y = w`, in the scalar `S` (see the module docs).
fn conjugate<S: Scalar, F: Fibre>(f: &F, t: S, x: &[S], w: &[S]) -> S {
    let n = f.dof();
    let x_re: Buf<f64> = x.iter().map(|v| v.re()).collect();
    let w_re: Buf<f64> = w.iter().map(|v| v.re()).collect();
    let Ok((y0, minv)) = solve_fibre(f, t.re(), &x_re, &w_re) else {
        // NaN in every derivative part too (0·NaN = NaN; the sum carries every seeded
        // direction), so derivatives are not silently zero.
        let all = x.iter().chain(w).fold(t, |acc, &v| acc + v);
        return all * f64::NAN;
    };
    // One chord step in S: y = y₀ − M⁻¹(∂f/∂y(y₀) − w).
    let z: Buf<S> = std::iter::once(t)
        .chain(x.iter().copied())
        .chain(y0.iter().map(|&v| S::from(v)))
        .collect();
    let mut g: Buf<S> = (0..n).map(|_| S::from(0.0)).collect();
    ad::nested_gradient(&FibreFn(f), &z, n + 1..2 * n + 1, &mut g);
    let y: Buf<S> = (0..n)
        .map(|i| {
            (0..n).fold(S::from(y0[i]), |acc, j| {
                acc - (g[j] - w[j]) * minv[i * n + j]
            })
        })
        .collect();
    let pairing = w
        .iter()
        .zip(&y)
        .fold(S::from(0.0), |acc, (&a, &b)| acc + a * b);
    pairing - f.eval(t, x, &y)
}

/// The Hamiltonian of a hyperregular Lagrangian, `H(t, q, p) = ⟨p, v⟩ − L(t, q, v)` with
/// `v = FH(t, q, p)` (see the module docs for how it stays differentiable).
///
/// ```
/// use marsden::hamiltonian::{Hamiltonian, LegendreHamiltonian};
/// use marsden::systems::Pendulum;
///
/// let h = LegendreHamiltonian::new(Pendulum::default());
/// // H = p²/2 − cos q for unit mass, length and gravity.
/// let value: f64 = h.hamiltonian(0.0, &[0.3], &[1.2]);
/// assert!((value - (0.72 - 0.3_f64.cos())).abs() < 1e-14);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LegendreHamiltonian<L> {
    /// The Lagrangian.
    pub lagrangian: L,
}

impl<L: Lagrangian> LegendreHamiltonian<L> {
    /// `H` built from `lagrangian`.
    pub fn new(lagrangian: L) -> Self {
        Self { lagrangian }
    }

    /// `H(t, q, p)` in `f64`, with a typed error if `FH` cannot be computed.
    pub fn try_value(&self, t: f64, q: &[f64], p: &[f64]) -> Result<f64, Error> {
        let (v, _) = solve_fibre(&LFibre(&self.lagrangian), t, q, p)?;
        let pv: f64 = p.iter().zip(&v).map(|(a, b)| a * b).sum();
        Ok(pv - self.lagrangian.lagrangian(t, q, &v))
    }
}

impl<L: Lagrangian> Hamiltonian for LegendreHamiltonian<L> {
    fn dof(&self) -> usize {
        self.lagrangian.dof()
    }
    fn hamiltonian<S: Scalar>(&self, t: S, q: &[S], p: &[S]) -> S {
        conjugate(&LFibre(&self.lagrangian), t, q, p)
    }
}

/// The Lagrangian of a hyperregular Hamiltonian, `L(t, q, v) = ⟨p, v⟩ − H(t, q, p)` with
/// `p = FL(t, q, v)` solving `∂H/∂p = v`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HamiltonianLagrangian<H> {
    /// The Hamiltonian.
    pub hamiltonian: H,
}

impl<H: Hamiltonian> HamiltonianLagrangian<H> {
    /// `L` built from `hamiltonian`.
    pub fn new(hamiltonian: H) -> Self {
        Self { hamiltonian }
    }
}

impl<H: Hamiltonian> Lagrangian for HamiltonianLagrangian<H> {
    fn dof(&self) -> usize {
        self.hamiltonian.dof()
    }
    fn lagrangian<S: Scalar>(&self, t: S, q: &[S], v: &[S]) -> S {
        conjugate(&HFibre(&self.hamiltonian), t, q, v)
    }

    /// `v = ∂H/∂p(t, q, p)`: the inverse Legendre transform of this `L` is `FH` itself.
    fn velocity_guess(&self, t: f64, q: &[f64], p: &[f64], v: &mut [f64]) {
        let jet = super::jet::PhaseJet::at(&self.hamiltonian, t, q, p);
        let n = q.len();
        if jet.grad.len() == 2 * n && jet.grad[n..].iter().all(|x| x.is_finite()) {
            v.copy_from_slice(&jet.grad[n..]);
        }
    }
}
