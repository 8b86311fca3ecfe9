//! Time-dependent inputs (controls) `u(t)` as forces.
//!
//! In optimal control of mechanical systems the controls enter the Lagrange–d'Alembert
//! principle as a force `f_L = u(t)` (or `B(q) u(t)`), and discrete mechanics and optimal control
//! (DMOC, Ober-Blöbaum, Junge & Marsden, *ESAIM: COCV* 17 (2011)) discretises them by the same
//! quadrature as `L`. Here `u` is any Rust closure of time; it is sampled at the rule's
//! quadrature times and contributes nothing to the Newton Jacobian.

use crate::mechanics::Force;
use crate::numerics::scratch::{Buffer, NODE};
use crate::scalar::Scalar;

/// A force given by a closure of time, `f_L(t, q, v) = u(t)`: `u(t, out)` writes the n
/// components.
///
/// ```
/// use marsden::{Force, forces::Control};
///
/// // A ramp on the first coordinate, nothing on the second.
/// let ramp = Control::new(|t: f64, u: &mut [f64]| {
///     u[0] = 0.5 * t;
///     u[1] = 0.0;
/// });
/// let mut f = [0.0; 2];
/// ramp.force(2.0, &[0.0; 2], &[0.0; 2], &mut f);
/// assert_eq!(f, [1.0, 0.0]);
/// ```
#[derive(Clone)]
pub struct Control<U> {
    input: U,
}

impl<U: Fn(f64, &mut [f64])> Control<U> {
    /// The control `u(t)`.
    pub fn new(input: U) -> Self {
        Self { input }
    }
}

impl<U> std::fmt::Debug for Control<U> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Control(..)")
    }
}

impl<U: Fn(f64, &mut [f64])> Force for Control<U> {
    #[inline]
    fn force<S: Scalar>(&self, t: S, _q: &[S], _v: &[S], out: &mut [S]) {
        let mut u = Buffer::<f64, NODE>::empty();
        let u = u.filled(out.len(), 0.0);
        (self.input)(t.re(), u);
        for (o, &ui) in out.iter_mut().zip(u.iter()) {
            *o = S::from(ui);
        }
    }
}
