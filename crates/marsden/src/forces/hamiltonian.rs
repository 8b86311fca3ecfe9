//! Hamiltonian forces `f_H(t, q, p)` and their Lagrangian form `f_L = f_H ∘ FL`.
//!
//! Concept of the notes (MW01): *forced Hamiltonian systems* and *Legendre transform with forces*. A Hamiltonian force
//! `f_H: T*Q → T*Q` enters only the momentum equation, `ṗ = −∂H/∂q + f_H(q, p)`, and it is the
//! same physical force as the Lagrangian force `f_L = f_H ∘ FL`, i.e.
//! `f_L(t, q, v) = f_H(t, q, ∂L/∂v(t, q, v))` ([MW01] §3.1). [`FromHamiltonian`] is that
//! composition: it computes the momenta by automatic differentiation *inside* the force, with
//! nested duals ([`crate::numerics::ad::nested_gradient`]), so the step's Newton Jacobian still gets the
//! exact derivatives of `f_H(q, FL(q, v))`. The reverse direction `f_H = f_L ∘ FH` needs the
//! inverse Legendre transform and is given at `f64` by [`hamiltonian_form`].
//!
//! [MW01]: crate#references

use crate::error::Error;
use crate::error::InputError;
use crate::mechanics;
use crate::mechanics::{Force, Lagrangian};
use crate::numerics::ad;
use crate::numerics::scratch::{Buffer, NODE};
use crate::scalar::Scalar;

/// A Hamiltonian force `f_H(t, q, p)`, written once over the scalar type.
///
/// ```
/// use marsden::{Scalar, forces::HamiltonianForce};
///
/// /// Momentum damping `f_H = −γ p`.
/// struct MomentumDamping(f64);
/// impl HamiltonianForce for MomentumDamping {
///     fn hamiltonian_force<S: Scalar>(&self, _t: S, _q: &[S], p: &[S], out: &mut [S]) {
///         for (o, &pi) in out.iter_mut().zip(p) {
///             *o = pi * (-self.0);
///         }
///     }
/// }
/// ```
pub trait HamiltonianForce {
    /// Writes `f_H(t, q, p)` into `out` (length n).
    fn hamiltonian_force<S: Scalar>(&self, t: S, q: &[S], p: &[S], out: &mut [S]);
    /// Checks that the force fits a system with `dof` coordinates (default: accepts all).
    fn validate(&self, _dof: usize) -> Result<(), Error> {
        Ok(())
    }
}

/// The Lagrangian force `f_L(t, q, v) = f_H(t, q, ∂L/∂v(t, q, v))` of a Hamiltonian force `f_H`
/// for the Lagrangian `L`.
///
/// ```
/// use marsden::{Force, Scalar, forces::{FromHamiltonian, HamiltonianForce}};
/// use marsden::systems::HarmonicOscillator;
///
/// struct MomentumDamping(f64);
/// impl HamiltonianForce for MomentumDamping {
///     fn hamiltonian_force<S: Scalar>(&self, _t: S, _q: &[S], p: &[S], out: &mut [S]) {
///         out[0] = p[0] * (-self.0);
///     }
/// }
/// // m = 2: p = 2v, so f_L = −γ·2v.
/// let osc = HarmonicOscillator { m: 2.0, k: 1.0 };
/// let f = FromHamiltonian::new(osc, MomentumDamping(0.1));
/// let mut out = [0.0_f64];
/// f.force(0.0, &[1.0], &[3.0], &mut out);
/// assert!((out[0] + 0.6).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FromHamiltonian<L, H> {
    /// The Lagrangian whose Legendre transform `FL` maps velocities to momenta.
    pub lagrangian: L,
    /// The Hamiltonian force.
    pub force: H,
}

impl<L: Lagrangian, H: HamiltonianForce> FromHamiltonian<L, H> {
    /// `f_L = f_H ∘ FL`.
    pub fn new(lagrangian: L, force: H) -> Self {
        Self { lagrangian, force }
    }
}

/// `L` as a function of `z = (t, q, v)`, for the nested-dual gradient in `v`.
struct OnTangentBundle<'a, L>(&'a L);

impl<L: Lagrangian> ad::MultiFunction for OnTangentBundle<'_, L> {
    const MAX_INPUTS: Option<usize> = crate::mechanics::lagrangian::times_dof(L::FIXED_DOF, 2, 1);
    fn inputs(&self) -> usize {
        2 * self.0.dof() + 1
    }
    fn outputs(&self) -> usize {
        1
    }
    #[inline]
    fn eval<S: Scalar>(&self, z: &[S], out: &mut [S]) {
        let n = self.0.dof();
        out[0] = self.0.lagrangian(z[0], &z[1..=n], &z[n + 1..]);
    }
}

/// `p = ∂L/∂v(t, q, v)` at any scalar type, by nested duals ([`ad::nested_gradient`]).
fn momenta<L: Lagrangian, S: Scalar>(l: &L, t: S, q: &[S], v: &[S], p: &mut [S]) {
    let n = q.len();
    let entry = |i: usize| match i {
        0 => t,
        i if i <= n => q[i - 1],
        i => v[i - n - 1],
    };
    let mut z = Buffer::<S, { 2 * NODE + 1 }>::empty();
    let z = z.from_fn(2 * n + 1, t, entry);
    ad::nested_gradient(&OnTangentBundle(l), z, n + 1..2 * n + 1, p);
}

impl<L: Lagrangian, H: HamiltonianForce> Force for FromHamiltonian<L, H> {
    #[inline]
    fn force<S: Scalar>(&self, t: S, q: &[S], v: &[S], out: &mut [S]) {
        let zero = S::from(0.0);
        let mut p = Buffer::<S, NODE>::empty();
        let p = p.filled(q.len(), zero);
        momenta(&self.lagrangian, t, q, v, p);
        self.force.hamiltonian_force(t, q, p, out);
    }

    fn validate(&self, dof: usize) -> Result<(), Error> {
        if self.lagrangian.dof() != dof {
            return Err(Error::Input(InputError::DimensionMismatch {
                what: "the Lagrangian of a Hamiltonian force",
                expected: dof,
                found: self.lagrangian.dof(),
            }));
        }
        self.force.validate(dof)
    }
}

/// The Hamiltonian force `f_H(t, q, p) = f_L(t, q, FH(t, q, p))` of a Lagrangian force, at a
/// phase-space point (the inverse Legendre transform is solved by Newton's method,
/// [`mechanics::velocity`]). Writes `f_H` into `out`.
pub fn hamiltonian_form<L: Lagrangian, F: Force>(
    lagrangian: &L,
    force: &F,
    t: f64,
    q: &[f64],
    p: &[f64],
    out: &mut [f64],
) -> Result<(), Error> {
    let mut v = vec![0.0; lagrangian.dof()];
    mechanics::velocity(lagrangian, t, q, p, &mut v)?;
    force.force(t, q, &v, out);
    Ok(())
}
