//! The Legendre transform and its inverse as the event detector uses them: once per step
//! (`v_k = FL⁻¹(q_k, p_k)`) and at each point of a step's interpolant where an event is being
//! located (`p = FL(q, v)`), with the mass matrix of a separable Lagrangian read and factored
//! once so that a step costs no allocation.

use crate::error::Error;
use crate::mechanics::{self, Lagrangian, MassMatrix, structure};
use crate::numerics::dense::Lu;

/// How `v = FL⁻¹(q, p)` is computed.
#[derive(Debug, Clone)]
enum Inverse {
    /// `L = ½vᵀMv − V` with `M` diagonal: `v_i = p_i / m_i`.
    Diagonal(Vec<f64>),
    /// `L = ½vᵀMv − V` with `M` dense (kept as the declared [`MassMatrix::Dense`]): one LU
    /// factorisation, kept.
    Dense { mass: MassMatrix, lu: Lu },
    /// Any regular Lagrangian: Newton's method on `∂L/∂v = p` from the previous velocities
    /// ([`mechanics::velocity`]).
    General,
}

/// `FL` and `FL⁻¹` of one Lagrangian.
#[derive(Debug, Clone)]
pub(super) struct LegendreMaps<'l, L> {
    lagrangian: &'l L,
    inverse: Inverse,
    scratch: Vec<f64>,
}

impl<'l, L: Lagrangian> LegendreMaps<'l, L> {
    /// Reads the declared structure of `lagrangian`; a singular declared mass matrix is refused
    /// here (with the error [`structure::velocity`] gives).
    pub(super) fn new(lagrangian: &'l L) -> Result<Self, Error> {
        let n = lagrangian.dof();
        let inverse = match structure::separable_mass(lagrangian) {
            Some(mass) => {
                // The check of regularity, with the typed error of the core.
                let (zero, mut v) = (vec![0.0; n], vec![0.0; n]);
                structure::velocity(&mass, 0.0, &zero, &zero, &mut v)?;
                match mass {
                    MassMatrix::Diagonal(d) => Inverse::Diagonal(d),
                    MassMatrix::Dense(dense) => {
                        let mut lu = Lu::new();
                        // Cannot fail: `structure::velocity` just factored the same matrix.
                        let _ = lu.factor(&dense, n);
                        let mass = MassMatrix::Dense(dense);
                        Inverse::Dense { mass, lu }
                    }
                }
            }
            None => Inverse::General,
        };
        Ok(Self {
            lagrangian,
            inverse,
            scratch: Vec::with_capacity(n),
        })
    }

    /// `v = FL⁻¹(t, q, p)`; `v` holds a guess on entry (used by the general inverse only).
    pub(super) fn velocity(
        &mut self,
        t: f64,
        q: &[f64],
        p: &[f64],
        v: &mut [f64],
    ) -> Result<(), Error> {
        match &self.inverse {
            Inverse::Diagonal(d) => {
                for ((vi, pi), m) in v.iter_mut().zip(p).zip(d) {
                    *vi = pi / m;
                }
            }
            Inverse::Dense { lu, .. } => {
                v.copy_from_slice(p);
                lu.solve(v, &mut self.scratch);
            }
            Inverse::General => mechanics::velocity(self.lagrangian, t, q, p, v)?,
        }
        Ok(())
    }

    /// `p = FL(t, q, v) = ∂L/∂v`.
    pub(super) fn momentum(&self, t: f64, q: &[f64], v: &[f64], p: &mut [f64]) {
        match &self.inverse {
            Inverse::Diagonal(d) => {
                for ((pi, vi), m) in p.iter_mut().zip(v).zip(d) {
                    *pi = m * vi;
                }
            }
            Inverse::Dense { mass, .. } => {
                structure::momentum(mass, v, p);
            }
            Inverse::General => mechanics::momentum(self.lagrangian, t, q, v, p),
        }
    }
}
