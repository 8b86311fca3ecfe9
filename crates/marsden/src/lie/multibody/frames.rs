//! Points and directions carried by the two sides of a joint, with their derivatives.
//!
//! A joint connects two *sides*, each a body or the ground. A body's configuration varies as
//! `R exp(ξ^)`, `x + δx` (left-trivialised, as in [`crate::lie::potential`]), so a point `s` and
//! a direction `u` fixed in the body vary as
//!
//! ```text
//! δ(x + R s) = δx − R ŝ ξ,        δ(R u) = −R û ξ,
//! ```
//!
//! and a joint's constraint rows are dot products and differences of such vectors. [`Tracked`]
//! carries a spatial vector with its 3 × 12 derivative with respect to `(ξ₀, δx₀, ξ₁, δx₁)`, the
//! variations of the joint's two sides, so each row's gradient is assembled by the product rule
//! and never written by hand ([LMO08] §2 writes the same rows for the null space method).
//!
//! [LMO08]: crate#references

use super::super::so3::{Mat3, Vec3, hat};
use nalgebra::{SMatrix, SVector};

/// The derivative of a spatial vector with respect to the two sides' variations
/// `(ξ₀, δx₀, ξ₁, δx₁)`.
pub type Derivative = SMatrix<f64, 3, 12>;

/// The gradient of one constraint row with respect to `(ξ₀, δx₀, ξ₁, δx₁)`.
pub type RowGradient = SVector<f64, 12>;

/// One constraint row at a configuration: its value and its gradient.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Row {
    /// The row's value (zero on the constraint).
    pub value: f64,
    /// Its gradient with respect to `(ξ₀, δx₀, ξ₁, δx₁)`.
    pub gradient: RowGradient,
}

/// One side of a joint at a configuration: the ground (`R = I`, `x = 0`, nothing varies) or a
/// body's attitude and position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Side {
    /// The attitude (identity for the ground).
    pub r: Mat3,
    /// The position of the body's reference point (its centre of mass, or the origin for a body
    /// turning about a fixed point and for the ground).
    pub x: Vec3,
    /// Whether the attitude varies (a body, not the ground).
    pub turns: bool,
    /// Whether the position varies (a free body).
    pub translates: bool,
}

impl Side {
    /// The ground: the space frame.
    pub fn ground() -> Self {
        Self {
            r: Mat3::identity(),
            x: Vec3::zeros(),
            turns: false,
            translates: false,
        }
    }
}

/// A spatial vector and its derivative with respect to the joint's two sides.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tracked {
    /// The vector.
    pub value: Vec3,
    /// Its derivative (3 × 12).
    pub derivative: Derivative,
}

impl Tracked {
    /// The point `x + R s` of side `index` (0 or 1), `s` in that side's frame.
    pub fn point(side: &Side, index: usize, s: &Vec3) -> Self {
        let mut derivative = Derivative::zeros();
        if side.turns {
            derivative
                .fixed_view_mut::<3, 3>(0, 6 * index)
                .copy_from(&(-side.r * hat(s)));
        }
        if side.translates {
            derivative
                .fixed_view_mut::<3, 3>(0, 6 * index + 3)
                .copy_from(&Mat3::identity());
        }
        Self {
            value: side.x + side.r * s,
            derivative,
        }
    }

    /// The direction `R u` of side `index`, `u` in that side's frame.
    pub fn direction(side: &Side, index: usize, u: &Vec3) -> Self {
        let mut derivative = Derivative::zeros();
        if side.turns {
            derivative
                .fixed_view_mut::<3, 3>(0, 6 * index)
                .copy_from(&(-side.r * hat(u)));
        }
        Self {
            value: side.r * u,
            derivative,
        }
    }

    /// `self − other`.
    pub fn minus(&self, other: &Self) -> Self {
        Self {
            value: self.value - other.value,
            derivative: self.derivative - other.derivative,
        }
    }

    /// Component `i` as a constraint row: its value and gradient.
    pub fn component(&self, i: usize) -> Row {
        Row {
            value: self.value[i],
            gradient: self.derivative.row(i).transpose(),
        }
    }

    /// `self · other` as a constraint row (the product rule).
    pub fn dot(&self, other: &Self) -> Row {
        Row {
            value: self.value.dot(&other.value),
            gradient: self.derivative.transpose() * other.value
                + other.derivative.transpose() * self.value,
        }
    }
}

/// Two unit vectors completing the unit vector `a` to a right-handed orthonormal basis
/// `(u₁, u₂, a)`: the directions a revolute joint's axis must stay perpendicular to.
pub fn perpendiculars(a: &Vec3) -> (Vec3, Vec3) {
    // The coordinate axis least aligned with `a` keeps the cross product well conditioned.
    let pick = if a.x.abs() <= a.y.abs() && a.x.abs() <= a.z.abs() {
        Vec3::x()
    } else if a.y.abs() <= a.z.abs() {
        Vec3::y()
    } else {
        Vec3::z()
    };
    let u1 = a.cross(&pick).normalize();
    let u2 = a.cross(&u1);
    (u1, u2)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lie::so3::exp;

    fn body(r: Mat3, x: Vec3) -> Side {
        Side {
            r,
            x,
            turns: true,
            translates: true,
        }
    }

    /// The derivative of a point against central differences along `R exp(εξ^)`, `x + εδx`.
    #[test]
    fn point_derivative_matches_finite_differences() {
        let r = exp(&Vec3::new(0.3, -0.7, 0.2));
        let x = Vec3::new(0.1, 0.2, -0.4);
        let s = Vec3::new(0.5, -0.25, 1.0);
        let tracked = Tracked::point(&body(r, x), 1, &s);
        let eps = 1e-6;
        for k in 0..6 {
            let mut d = [0.0; 6];
            d[k] = eps;
            let turn = |e: f64| exp(&(Vec3::new(d[0], d[1], d[2]) * e));
            let moved = |e: f64| {
                let side = body(r * turn(e), x + Vec3::new(d[3], d[4], d[5]) * e);
                side.x + side.r * s
            };
            let fd = (moved(1.0) - moved(-1.0)) / (2.0 * eps);
            let column = tracked.derivative.column(6 + k);
            assert!((fd - column).amax() < 1e-9, "column {k}: {fd} vs {column}");
        }
        assert_eq!(tracked.derivative.columns(0, 6).amax(), 0.0);
    }

    #[test]
    fn perpendiculars_complete_a_right_handed_basis() {
        for a in [
            Vec3::x(),
            Vec3::y(),
            Vec3::z(),
            Vec3::new(1.0, 2.0, -2.0) / 3.0,
        ] {
            let (u1, u2) = perpendiculars(&a);
            assert!(u1.dot(&a).abs() < 1e-15 && u2.dot(&a).abs() < 1e-15);
            assert!((u1.cross(&u2) - a).amax() < 1e-15);
        }
    }
}
