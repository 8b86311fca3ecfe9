//! Explicit symplectic splitting methods for separable `H = T(p) + V(t, q)` — the partitioned
//! Runge–Kutta methods of Störmer–Verlet type ([HLW06] §II.2, §II.5; [HLW03]).
//!
//! A method is a list of stages `(bᵢ, aᵢ)`; each stage is a *kick* followed by a *drift*,
//!
//! ```text
//!     p ← p − bᵢ h ∇V(τ, q),      q ← q + aᵢ h ∇T(p),      τ ← τ + aᵢ h,
//! ```
//!
//! each the exact flow of a Hamiltonian (`V` or `T`) and hence symplectic, so the composition is
//! symplectic ([HLW06] §II.5). Built in:
//!
//! | method | stages `(b, a)` | order |
//! |---|---|---|
//! | [`Splitting::stormer_verlet`] (velocity form) | `(½, 1), (½, 0)` | 2 |
//! | [`Splitting::symplectic_euler`] (momentum first) | `(1, 1)` | 1 |
//!
//! Velocity Störmer–Verlet is the trapezoid variational integrator of `L = ½vᵀMv − V`
//! ([conventions](crate#conventions), equivalences; R2). The step map's Jacobian is the product of
//! the stages' Jacobians `[[I, 0], [−bh∇²V, I]]` and `[[I, ah∇²T], [0, I]]`, with the Hessians by
//! AD.
//!
//! [HLW06]: crate#references
//! [HLW03]: crate#references

use super::{HamiltonianMethod, Separable};
use crate::error::Error;
use crate::error::{InputError, StepError, StepFailure};
use crate::integrator::StepReport;
use crate::mechanics::State;
use crate::numerics::ad::{self, HessianParts, MultiFunction};
use crate::scalar::Scalar;

/// A splitting (partitioned RK) method for a [`Separable`] Hamiltonian.
#[derive(Debug, Clone, PartialEq)]
pub struct Splitting {
    name: String,
    stages: Vec<(f64, f64)>,
}

impl Splitting {
    /// Velocity Störmer–Verlet: half kick, drift, half kick (order 2).
    pub fn stormer_verlet() -> Self {
        Self {
            name: "Störmer–Verlet".into(),
            stages: vec![(0.5, 1.0), (0.5, 0.0)],
        }
    }

    /// Symplectic Euler, momentum first: `p₁ = p₀ − h∇V(q₀)`, `q₁ = q₀ + h∇T(p₁)` (order 1).
    pub fn symplectic_euler() -> Self {
        Self {
            name: "symplectic Euler".into(),
            stages: vec![(1.0, 1.0)],
        }
    }

    /// A custom method from its stages `(bᵢ, aᵢ)`; consistency requires `Σbᵢ = Σaᵢ = 1`.
    pub fn new(name: &str, stages: Vec<(f64, f64)>) -> Result<Self, Error> {
        let (sb, sa) = stages
            .iter()
            .fold((0.0, 0.0), |(sb, sa), (b, a)| (sb + b, sa + a));
        for (sum, what) in [
            (sb, "sum of kick coefficients"),
            (sa, "sum of drift coefficients"),
        ] {
            if (sum - 1.0).abs() > 1e-14 {
                return Err(Error::Input(InputError::InvalidOption {
                    name: what,
                    value: sum,
                    reason: "must be 1 for a consistent splitting",
                }));
            }
        }
        Ok(Self {
            name: name.into(),
            stages,
        })
    }

    /// The stages `(bᵢ, aᵢ)`.
    pub fn stages(&self) -> &[(f64, f64)] {
        &self.stages
    }
}

/// `T(p)` for the AD drivers.
struct Kinetic<'a, H>(&'a H);
impl<H: Separable> MultiFunction for Kinetic<'_, H> {
    fn inputs(&self) -> usize {
        self.0.dof()
    }
    fn outputs(&self) -> usize {
        1
    }
    fn eval<S: Scalar>(&self, p: &[S], out: &mut [S]) {
        out[0] = self.0.kinetic(p);
    }
}

/// `V(t, q)` for the AD drivers.
struct Potential<'a, H>(&'a H, f64);
impl<H: Separable> MultiFunction for Potential<'_, H> {
    fn inputs(&self) -> usize {
        self.0.dof()
    }
    fn outputs(&self) -> usize {
        1
    }
    fn eval<S: Scalar>(&self, q: &[S], out: &mut [S]) {
        out[0] = self.0.potential(S::from(self.1), q);
    }
}

/// Gradient (and, with `hess`, Hessian) of a scalar function of n variables.
fn derivatives<F: MultiFunction>(
    f: &F,
    x: &[f64],
    grad: &mut [f64],
    hess: Option<&mut HessianParts>,
) {
    let n = x.len();
    match hess {
        None => {
            ad::jacobian(f, x, 0..n, &mut [0.0], grad);
        }
        Some(parts) => {
            ad::partial_hessian(f, x, 0..n, 0..n, parts);
            grad.copy_from_slice(&parts.grad_rows);
        }
    }
}

impl Splitting {
    /// Runs the stages; with `jac`, accumulates the Jacobian (row-major 2n × 2n).
    fn run<H: Separable>(&self, ham: &H, state: &mut State, h: f64, mut jac: Option<&mut [f64]>) {
        let n = Separable::dof(ham);
        let m = 2 * n;
        if let Some(j) = jac.as_deref_mut() {
            (0..m * m).for_each(|k| j[k] = f64::from(u8::from(k / m == k % m)));
        }
        let (mut g, mut parts) = (vec![0.0; n], HessianParts::default());
        let mut tau = state.t;
        for &(b, a) in &self.stages {
            if b != 0.0 {
                let want = jac.is_some().then_some(&mut parts);
                derivatives(&Potential(ham, tau), &state.q, &mut g, want);
                state
                    .p
                    .iter_mut()
                    .zip(&g)
                    .for_each(|(p, gi)| *p -= b * h * gi);
                if let Some(j) = jac.as_deref_mut() {
                    shear(j, n, n, 0, -b * h, &parts.hess);
                }
            }
            if a != 0.0 {
                let want = jac.is_some().then_some(&mut parts);
                derivatives(&Kinetic(ham), &state.p, &mut g, want);
                state
                    .q
                    .iter_mut()
                    .zip(&g)
                    .for_each(|(q, gi)| *q += a * h * gi);
                if let Some(j) = jac.as_deref_mut() {
                    shear(j, n, 0, n, a * h, &parts.hess);
                }
                tau += a * h;
            }
        }
        state.t += h;
    }
}

/// `rows[target] += c · K · rows[source]` for the n-row blocks of a 2n × 2n Jacobian.
fn shear(jac: &mut [f64], n: usize, target: usize, source: usize, c: f64, k: &[f64]) {
    let m = 2 * n;
    let src: Vec<f64> = jac[source * m..(source + n) * m].to_vec();
    for i in 0..n {
        for col in 0..m {
            let s: f64 = (0..n).map(|l| k[i * n + l] * src[l * m + col]).sum();
            jac[(target + i) * m + col] += c * s;
        }
    }
}

impl<H: Separable> HamiltonianMethod<H> for Splitting {
    fn name(&self) -> String {
        self.name.clone()
    }

    fn is_symplectic(&self) -> bool {
        true
    }

    fn step(&mut self, ham: &H, state: &mut State, h: f64) -> Result<StepReport, Error> {
        let mut next = state.clone();
        self.run(ham, &mut next, h, None);
        finish(state, next)
    }

    fn step_with_jacobian(
        &mut self,
        ham: &H,
        state: &mut State,
        h: f64,
        jac: &mut [f64],
    ) -> Result<StepReport, Error> {
        let mut next = state.clone();
        self.run(ham, &mut next, h, Some(jac));
        finish(state, next)
    }
}

/// Accepts an explicit step if it is finite.
pub(super) fn finish(state: &mut State, next: State) -> Result<StepReport, Error> {
    if next.q.iter().chain(&next.p).all(|x| x.is_finite()) {
        *state = next;
        Ok(StepReport::default())
    } else {
        Err(Error::Step(StepFailure {
            step: 0,
            t: state.t,
            cause: StepError::NonFinite {
                what: "the new state",
            },
        }))
    }
}
