//! The discrete flow maps as plain functions ([MW01] §1.3, §1.5; seed: *discrete Lagrangian
//! map*, *discrete Hamiltonian map*):
//!
//! * the discrete Lagrangian map `F_{L_d}: (q_{k−1}, q_k) ↦ (q_k, q_{k+1})`, defined by the DEL
//!   equations `D₂L_d(q_{k−1}, q_k) + D₁L_d(q_k, q_{k+1}) = 0`;
//! * the discrete Hamiltonian map `F̃_{L_d}: (q_k, p_k) ↦ (q_{k+1}, p_{k+1})`, defined by
//!   `p_k = −D₁L_d(q_k, q_{k+1})`, `p_{k+1} = D₂L_d(q_k, q_{k+1})`.
//!
//! They are related by `F̃_{L_d} = F⁺L_d ∘ (F⁻L_d)⁻¹`, which is how [`two_step_map`] is computed:
//! `p_k = D₂L_d(q_{k−1}, q_k)` (momentum matching), then one Hamiltonian step. For runs, use an
//! [`Integrator`], which keeps its buffers and predictor between steps.
//!
//! [MW01]: crate#references

use crate::discrete::DiscreteLagrangian;
use crate::discrete::legendre::legendre_plus;
use crate::error::Error;
use crate::integrator::Integrator;
use crate::mechanics::State;
use crate::numerics::newton::NewtonOptions;

/// `(q_{k+1}, p_{k+1}) = F̃_{L_d}(q_k, p_k)` for the step from `t` to `t + h`.
pub fn discrete_hamiltonian_map<D: DiscreteLagrangian>(
    ld: &D,
    t: f64,
    h: f64,
    q: &[f64],
    p: &[f64],
    options: &NewtonOptions,
) -> Result<(Vec<f64>, Vec<f64>), Error> {
    let mut integrator = Integrator::new(ld).with_options(*options)?;
    let mut state = State {
        t,
        q: q.to_vec(),
        p: p.to_vec(),
    };
    integrator.step(&mut state, h)?;
    Ok((state.q, state.p))
}

/// `q_{k+1}` such that `(q_k, q_{k+1}) = F_{L_d}(q_{k−1}, q_k)`, for steps of size `h` with
/// `q_{k−1}` at time `t_prev`.
pub fn two_step_map<D: DiscreteLagrangian>(
    ld: &D,
    t_prev: f64,
    h: f64,
    q_prev: &[f64],
    q: &[f64],
    options: &NewtonOptions,
) -> Result<Vec<f64>, Error> {
    let mut p = vec![0.0; ld.dof()];
    legendre_plus(ld, t_prev, h, q_prev, q, &mut p);
    let mut integrator = Integrator::new(ld).with_options(*options)?;
    // Predict with the last displacement.
    let v: Vec<f64> = q.iter().zip(q_prev).map(|(a, b)| (a - b) / h).collect();
    integrator.set_velocity_hint(&v);
    let mut state = State {
        t: t_prev + h,
        q: q.to_vec(),
        p,
    };
    integrator.step(&mut state, h)?;
    Ok(state.q)
}
