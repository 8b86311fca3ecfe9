//! Joints: holonomic constraints between two bodies, or a body and the ground.
//!
//! A joint names two sides (a body index, or `None` for the ground), a point in each side's
//! frame (the space frame for the ground) and, for some kinds, an axis in each frame. Its rows
//! `g(R₀, x₀, R₁, x₁) = 0` ([LMO08] §2, [CLLM11] for the 3D pendulum):
//!
//! | kind | rows | constraint |
//! |---|---|---|
//! | spherical | 3 | `x₀ + R₀s₀ = x₁ + R₁s₁` (the two points coincide) |
//! | revolute | 5 | spherical, and `(R₀a₀)·(R₁u₁) = (R₀a₀)·(R₁u₂) = 0` (`u₁, u₂ ⊥ a₁`: the axes stay aligned) |
//! | prismatic | 5 | the relative attitude locked, and `(p₁ − p₀)·(R₀w₁) = (p₁ − p₀)·(R₀w₂) = 0` (`w ⊥ a₀`: slide along `a₀`) |
//! | fixed | 6 | the relative attitude locked, and spherical |
//! | distance | 1 | `½(|p₁ − p₀|² − ℓ²) = 0` |
//!
//! The relative attitude `R₀ᵀR₁ = C` is locked by three rows `(R₀e₂)·(R₁c₃)`, `(R₀e₃)·(R₁c₁)`,
//! `(R₀e₁)·(R₁c₂)` with `c_j = Cᵀe_j` (at `R₁ = R₀C` each is `e_i·e_j = 0`, and their gradients
//! are independent there). Every row is a component or a dot product of [`Tracked`] vectors, so
//! its gradient follows by the product rule.
//!
//! [LMO08]: crate#references
//! [CLLM11]: crate#references

use super::frames::{Row, RowGradient, Side, Tracked, perpendiculars};
use crate::error::{Error, InputError};
use crate::lie::so3::{Mat3, Vec3};

/// The kind of a joint, with what it needs beyond its two points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum JointKind {
    /// A ball joint: the two points coincide (3 rows).
    Spherical,
    /// A hinge: the points coincide and the axes (one in each frame, unit) stay aligned (5 rows).
    Revolute {
        /// The axis in each side's frame.
        axes: [Vec3; 2],
    },
    /// A slider along the axis of side 0 (unit, side 0's frame), the relative attitude locked at
    /// `reference = R₀ᵀR₁` (5 rows).
    Prismatic {
        /// The sliding axis in side 0's frame.
        axis: Vec3,
        /// The locked relative attitude `R₀ᵀR₁`.
        reference: Mat3,
    },
    /// A weld: the points coincide and the relative attitude is locked at `reference` (6 rows).
    Fixed {
        /// The locked relative attitude `R₀ᵀR₁`.
        reference: Mat3,
    },
    /// A massless rod of length `length` between the two points (1 row).
    Distance {
        /// The distance `ℓ > 0`.
        length: f64,
    },
}

impl JointKind {
    /// The number of constraint rows.
    pub fn rows(&self) -> usize {
        match self {
            Self::Spherical => 3,
            Self::Revolute { .. } | Self::Prismatic { .. } => 5,
            Self::Fixed { .. } => 6,
            Self::Distance { .. } => 1,
        }
    }

    /// The kind's name as problem files write it.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Spherical => "spherical",
            Self::Revolute { .. } => "revolute",
            Self::Prismatic { .. } => "prismatic",
            Self::Fixed { .. } => "fixed",
            Self::Distance { .. } => "distance",
        }
    }
}

/// A joint between side 0 and side 1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Joint {
    /// The body of each side (`None`: the ground).
    pub bodies: [Option<usize>; 2],
    /// The joint point in each side's frame (the body frame, about its reference point; the
    /// space frame for the ground).
    pub points: [Vec3; 2],
    /// The kind.
    pub kind: JointKind,
}

impl Joint {
    /// A joint, its axes normalised.
    ///
    /// # Errors
    /// [`InputError::InvalidOption`] for the ground on both sides, one body on both sides, a
    /// zero or non-finite axis, a non-positive distance, or a reference that is not a rotation.
    pub fn new(
        bodies: [Option<usize>; 2],
        points: [Vec3; 2],
        kind: JointKind,
    ) -> Result<Self, Error> {
        let invalid = |name, value, reason| {
            Err(Error::Input(InputError::InvalidOption {
                name,
                value,
                reason,
            }))
        };
        if bodies[0] == bodies[1] {
            return invalid(
                "joint bodies",
                f64::NAN,
                "a joint needs two different sides",
            );
        }
        Error::check_finite("joint points", points[0].as_slice())?;
        Error::check_finite("joint points", points[1].as_slice())?;
        let kind = match kind {
            JointKind::Revolute { axes } => JointKind::Revolute {
                axes: [unit(&axes[0])?, unit(&axes[1])?],
            },
            JointKind::Prismatic { axis, reference } => JointKind::Prismatic {
                axis: unit(&axis)?,
                reference: rotation(&reference)?,
            },
            JointKind::Fixed { reference } => JointKind::Fixed {
                reference: rotation(&reference)?,
            },
            JointKind::Distance { length } if !(length.is_finite() && length > 0.0) => {
                return invalid("joint length", length, "must be positive and finite");
            }
            other => other,
        };
        Ok(Self {
            bodies,
            points,
            kind,
        })
    }

    /// The joint's rows at the sides' configurations: `values[k]` and `gradients[k]` (with
    /// respect to `(ξ₀, δx₀, ξ₁, δx₁)`) for `k < self.kind.rows()`.
    pub fn evaluate(&self, sides: &[Side; 2], values: &mut [f64], gradients: &mut [RowGradient]) {
        let mut out = Rows {
            values,
            gradients,
            next: 0,
        };
        match self.kind {
            JointKind::Spherical => self.coincide(sides, &mut out),
            JointKind::Revolute { axes } => {
                self.coincide(sides, &mut out);
                let a0 = Tracked::direction(&sides[0], 0, &axes[0]);
                let (u1, u2) = perpendiculars(&axes[1]);
                for u in [u1, u2] {
                    out.push(a0.dot(&Tracked::direction(&sides[1], 1, &u)));
                }
            }
            JointKind::Prismatic { axis, reference } => {
                lock(sides, &reference, &mut out);
                let gap = self.gap(sides);
                let (w1, w2) = perpendiculars(&axis);
                for w in [w1, w2] {
                    out.push(gap.dot(&Tracked::direction(&sides[0], 0, &w)));
                }
            }
            JointKind::Fixed { reference } => {
                lock(sides, &reference, &mut out);
                self.coincide(sides, &mut out);
            }
            JointKind::Distance { length } => {
                let gap = self.gap(sides);
                let square = gap.dot(&gap);
                out.push(Row {
                    value: 0.5 * (square.value - length * length),
                    gradient: 0.5 * square.gradient,
                });
            }
        }
    }

    /// `p₁ − p₀`, the vector from side 0's joint point to side 1's.
    fn gap(&self, sides: &[Side; 2]) -> Tracked {
        let p0 = Tracked::point(&sides[0], 0, &self.points[0]);
        Tracked::point(&sides[1], 1, &self.points[1]).minus(&p0)
    }

    /// The three rows `p₁ − p₀ = 0`.
    fn coincide(&self, sides: &[Side; 2], out: &mut Rows<'_>) {
        let gap = self.gap(sides);
        for i in 0..3 {
            out.push(gap.component(i));
        }
    }
}

/// The three rows locking `R₀ᵀR₁ = C` (module docs).
fn lock(sides: &[Side; 2], reference: &Mat3, out: &mut Rows<'_>) {
    let axis = |j: usize| Vec3::ith(j, 1.0);
    let c = |j: usize| reference.transpose() * axis(j);
    for (i, j) in [(1, 2), (2, 0), (0, 1)] {
        let e = Tracked::direction(&sides[0], 0, &axis(i));
        out.push(e.dot(&Tracked::direction(&sides[1], 1, &c(j))));
    }
}

/// The rows written so far.
struct Rows<'a> {
    values: &'a mut [f64],
    gradients: &'a mut [RowGradient],
    next: usize,
}

impl Rows<'_> {
    fn push(&mut self, row: Row) {
        self.values[self.next] = row.value;
        self.gradients[self.next] = row.gradient;
        self.next += 1;
    }
}

/// `a / |a|`.
fn unit(a: &Vec3) -> Result<Vec3, Error> {
    let norm = a.norm();
    if !(norm.is_finite() && norm > 0.0) {
        return Err(Error::Input(InputError::InvalidOption {
            name: "joint axis",
            value: norm,
            reason: "an axis must be a finite, nonzero vector",
        }));
    }
    Ok(a / norm)
}

/// A relative attitude, checked and re-orthonormalised.
fn rotation(r: &Mat3) -> Result<Mat3, Error> {
    crate::lie::so3::attitude("the joint's relative attitude", &crate::lie::so3::rows(r))
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

    /// Every row's gradient against central differences, for every kind.
    #[test]
    fn row_gradients_match_finite_differences() {
        let r0 = exp(&Vec3::new(0.3, -0.7, 0.2));
        let r1 = exp(&Vec3::new(-0.1, 0.4, 0.9));
        let (x0, x1) = (Vec3::new(0.1, 0.2, -0.4), Vec3::new(-0.3, 0.5, 0.2));
        let points = [Vec3::new(0.0, 0.0, -0.5), Vec3::new(0.1, 0.0, 0.5)];
        let kinds = [
            JointKind::Spherical,
            JointKind::Revolute {
                axes: [Vec3::y(), Vec3::new(0.0, 0.6, 0.8)],
            },
            JointKind::Prismatic {
                axis: Vec3::x(),
                reference: exp(&Vec3::new(0.2, 0.1, 0.0)),
            },
            JointKind::Fixed {
                reference: exp(&Vec3::new(0.0, 0.3, -0.2)),
            },
            JointKind::Distance { length: 0.7 },
        ];
        for kind in kinds {
            let joint = Joint::new([Some(0), Some(1)], points, kind).unwrap();
            let n = kind.rows();
            let rows = |d: &[f64; 12], e: f64| {
                let turn = |k: usize| exp(&(Vec3::new(d[k], d[k + 1], d[k + 2]) * e));
                let shift = |k: usize| Vec3::new(d[k], d[k + 1], d[k + 2]) * e;
                let sides = [
                    body(r0 * turn(0), x0 + shift(3)),
                    body(r1 * turn(6), x1 + shift(9)),
                ];
                let mut values = [0.0; 6];
                let mut gradients = [RowGradient::zeros(); 6];
                joint.evaluate(&sides, &mut values, &mut gradients);
                (values, gradients)
            };
            let (_, gradients) = rows(&[0.0; 12], 0.0);
            for c in 0..12 {
                let mut d = [0.0; 12];
                d[c] = 1e-6;
                let (plus, _) = rows(&d, 1.0);
                let (minus, _) = rows(&d, -1.0);
                for k in 0..n {
                    let fd = (plus[k] - minus[k]) / 2e-6;
                    assert!(
                        (fd - gradients[k][c]).abs() < 1e-8,
                        "{} row {k} column {c}",
                        kind.name()
                    );
                }
            }
        }
    }

    /// At the locked attitude and coinciding points, a fixed joint's rows vanish.
    #[test]
    fn a_fixed_joint_holds_at_its_reference() {
        let r0 = exp(&Vec3::new(0.3, -0.7, 0.2));
        let c = exp(&Vec3::new(0.0, 0.3, -0.2));
        let r1 = r0 * c;
        let points = [Vec3::new(0.0, 0.0, -0.5), Vec3::new(0.1, 0.0, 0.5)];
        let x0 = Vec3::new(0.1, 0.2, -0.4);
        let x1 = x0 + r0 * points[0] - r1 * points[1];
        let joint = Joint::new(
            [Some(0), Some(1)],
            points,
            JointKind::Fixed { reference: c },
        )
        .unwrap();
        let mut values = [1.0; 6];
        let mut gradients = [RowGradient::zeros(); 6];
        joint.evaluate(&[body(r0, x0), body(r1, x1)], &mut values, &mut gradients);
        assert!(values.iter().all(|v| v.abs() < 1e-15), "{values:?}");
    }

    #[test]
    fn bad_joints_are_refused() {
        let p = [Vec3::zeros(); 2];
        assert!(Joint::new([Some(0), Some(0)], p, JointKind::Spherical).is_err());
        assert!(Joint::new([None, None], p, JointKind::Spherical).is_err());
        let zero = JointKind::Revolute {
            axes: [Vec3::zeros(), Vec3::x()],
        };
        assert!(Joint::new([None, Some(0)], p, zero).is_err());
        assert!(Joint::new([None, Some(0)], p, JointKind::Distance { length: 0.0 }).is_err());
    }
}
