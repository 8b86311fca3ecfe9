//! A pendulum on a cart (the cart-pole) driven by a horizontal force on the cart.
//!
//! Coordinates `q = (x, θ)`: cart position and pendulum angle from the downward vertical; cart
//! mass `M`, bob mass `m` on a massless rod of length `l`, gravity `g`:
//!
//! ```text
//!     L = ½ (M + m) ẋ² + m l ẋ θ̇ cos θ + ½ m l² θ̇² + m g l cos θ,
//!     f_L(t) = (A cos(ω t + φ), 0)       (force on the cart only).
//! ```
//!
//! The drive is a time-dependent force (a control input `u(t)` enters the same way, see
//! [`crate::forces::Control`]). `L` does not depend on `x`, so the horizontal momentum
//! `p_x = ∂L/∂ẋ` changes only by the drive: `Δp_x = ∫ f_x dt`, and the forced discrete scheme
//! keeps the discrete version of that balance exactly, `p_{x,k+1} − p_{x,k} = (f_d⁻ + f_d⁺)_x`
//! (seed: *Noether's theorem with forces*). Defaults: the cart-pole of Barto, Sutton & Anderson,
//! IEEE SMC 13 (1983): `M = 1`, `m = 0.1`, `l = 0.5`, `g = 9.8`; drive `A = 1`, `ω = 3`, `φ = 0`.

use crate::mechanics::{Force, Lagrangian};
use crate::scalar::Scalar;

/// Cart-pole with a periodic horizontal force on the cart; it is both the [`Lagrangian`] and the
/// [`Force`] of the system.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PendulumOnCart {
    /// Cart mass `M` (default 1).
    pub cart_mass: f64,
    /// Bob mass `m` (default 0.1).
    pub bob_mass: f64,
    /// Rod length (default 0.5).
    pub l: f64,
    /// Gravity (default 9.8).
    pub g: f64,
    /// Amplitude of the horizontal force on the cart (default 1).
    pub amplitude: f64,
    /// Its angular frequency (default 3).
    pub omega: f64,
    /// Its phase (default 0).
    pub phase: f64,
}

impl Default for PendulumOnCart {
    fn default() -> Self {
        Self {
            cart_mass: 1.0,
            bob_mass: 0.1,
            l: 0.5,
            g: 9.8,
            amplitude: 1.0,
            omega: 3.0,
            phase: 0.0,
        }
    }
}

impl PendulumOnCart {
    /// Positions `(x_cart, x_bob, y_bob)` in the plane (y up).
    pub fn positions(&self, q: &[f64]) -> [f64; 3] {
        let (s, c) = q[1].sin_cos();
        [q[0], q[0] + self.l * s, -self.l * c]
    }

    /// The horizontal force on the cart at time `t`.
    pub fn drive(&self, t: f64) -> f64 {
        self.amplitude * (self.omega * t + self.phase).cos()
    }
}

impl Lagrangian for PendulumOnCart {
    const FIXED_DOF: Option<usize> = Some(2);
    fn dof(&self) -> usize {
        2
    }
    #[inline(always)]
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        let (big_m, m, l, g) = (self.cart_mass, self.bob_mass, self.l, self.g);
        let (xd, thd) = (v[0], v[1]);
        xd * xd * (0.5 * (big_m + m))
            + xd * thd * q[1].cos() * (m * l)
            + thd * thd * (0.5 * m * l * l)
            + q[1].cos() * (m * g * l)
    }
}

impl Force for PendulumOnCart {
    #[inline(always)]
    fn force<S: Scalar>(&self, t: S, _q: &[S], _v: &[S], out: &mut [S]) {
        out[0] = (t * self.omega + self.phase).cos() * self.amplitude;
        out[1] = S::from(0.0);
    }
    fn validate(&self, dof: usize) -> Result<(), crate::error::Error> {
        crate::error::Error::check_len("pendulum on cart force (dof)", &[0.0; 2], dof)
    }
}
