//! The explicit midpoint rule (Runge's second-order method) on Hamilton's equations,
//!
//! ```text
//!     z_½ = z₀ + (h/2) X_H(t₀, z₀),      z₁ = z₀ + h X_H(t₀ + h/2, z_½),
//! ```
//!
//! of order 2 but **not** symplectic ([HLW06] §VI.4: no explicit RK method is): its energy
//! drifts (reference case R10: max |ΔH| grows linearly on Kepler) and the symplecticity defect
//! `‖DFᵀJDF − J‖` of its step map is `O(h³)`, not round-off. It is here as the comparison map
//! that lets the certificate of [`crate::analysis::certificate`] fail. Jacobian by the chain rule:
//! `DF = I + h DX_H(z_½)(I + (h/2) DX_H(z₀))`.
//!
//! [HLW06]: crate#references

use super::splitting::finish;
use super::{Hamiltonian, HamiltonianMethod, PhaseJet};
use crate::error::Error;
use crate::integrator::StepReport;
use crate::mechanics::State;

/// Explicit midpoint rule (RK2) for a [`Hamiltonian`]: order 2, not symplectic.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ExplicitMidpoint;

impl ExplicitMidpoint {
    /// One step; with `jac`, also the step map's Jacobian.
    fn run<H: Hamiltonian>(ham: &H, state: &State, h: f64, jac: Option<&mut [f64]>) -> State {
        let n = ham.dof();
        let m = 2 * n;
        let z0: Vec<f64> = state.q.iter().chain(&state.p).copied().collect();
        let mut k = vec![0.0; m];
        let mut jet0 = PhaseJet::default();
        jet0.eval(ham, state.t, &z0);
        jet0.vector_field(&mut k);
        let zh: Vec<f64> = z0.iter().zip(&k).map(|(z, k)| z + 0.5 * h * k).collect();
        let mut jet1 = PhaseJet::default();
        jet1.eval(ham, state.t + 0.5 * h, &zh);
        jet1.vector_field(&mut k);
        if let Some(jac) = jac {
            let (mut d0, mut d1) = (vec![0.0; m * m], vec![0.0; m * m]);
            jet0.vector_field_jacobian(&mut d0);
            jet1.vector_field_jacobian(&mut d1);
            for i in 0..m {
                for j in 0..m {
                    let inner = |l: usize| f64::from(u8::from(l == j)) + 0.5 * h * d0[l * m + j];
                    let s: f64 = (0..m).map(|l| d1[i * m + l] * inner(l)).sum();
                    jac[i * m + j] = f64::from(u8::from(i == j)) + h * s;
                }
            }
        }
        let z1: Vec<f64> = z0.iter().zip(&k).map(|(z, k)| z + h * k).collect();
        State {
            t: state.t + h,
            q: z1[..n].to_vec(),
            p: z1[n..].to_vec(),
        }
    }
}

impl<H: Hamiltonian> HamiltonianMethod<H> for ExplicitMidpoint {
    fn name(&self) -> String {
        "explicit midpoint (RK2)".into()
    }

    fn is_symplectic(&self) -> bool {
        false
    }

    fn step(&mut self, ham: &H, state: &mut State, h: f64) -> Result<StepReport, Error> {
        let next = Self::run(ham, state, h, None);
        finish(state, next)
    }

    fn step_with_jacobian(
        &mut self,
        ham: &H,
        state: &mut State,
        h: f64,
        jac: &mut [f64],
    ) -> Result<StepReport, Error> {
        let next = Self::run(ham, state, h, Some(jac));
        finish(state, next)
    }
}
