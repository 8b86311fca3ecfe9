//! A set of joints: its rows, their gradients, and the banded matrices the step solves with.
//!
//! The rows of all joints are stacked in the order the joints are given; row `k` involves at most
//! two bodies. The step needs, with `G` the rows' gradients at one configuration and `H` at
//! another (left-trivialised: `∂g/∂ξ_b` and `∂g/∂x_b` per body `b`),
//!
//! * `Gᵀλ` per body (a moment and a force), and `G·(ω, v)` (the rows' rates);
//! * `A = H W Gᵀ` with a weight `W_b = diag(W_b^ξ, w_b^x I)` per body: `A_kl` is nonzero only
//!   when rows `k` and `l` share a body.
//!
//! With the joints of a chain listed along it, rows sharing a body are close in the order, so
//! `A` is banded ([`Banded`], half-bandwidth [`JointSet::bandwidth`]: the largest `|k − l|` over
//! rows sharing a body) and the solve costs `O(rows · b²)`: linear in the length of a chain.
//! For any other order the band is wider, up to dense: still exact, only slower.

use super::frames::{RowGradient, Side};
use super::joint::Joint;
use crate::error::{Error, InputError};
use crate::lie::body::RigidBody;
use crate::lie::so3::{Mat3, Vec3};
use crate::numerics::banded::Banded;

/// The weight of one body in `H W Gᵀ`: `W^ξ` on its rotation, `w^x` on its translation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyWeight {
    /// `W^ξ` (3 × 3).
    pub rotation: Mat3,
    /// `w^x` (zero for a body with a fixed point).
    pub translation: f64,
}

/// The rows of a joint set at one configuration.
#[derive(Debug, Default, PartialEq)]
pub struct JointRows {
    /// `g_k`.
    pub values: Vec<f64>,
    /// `∂g_k/∂(ξ₀, δx₀, ξ₁, δx₁)` of row `k`'s two sides.
    pub gradients: Vec<RowGradient>,
}

/// `clone_from` field by field, so that the step's saved copy reuses its buffers (the derived
/// one would allocate both vectors per step: 520 KB for a chain of 1000 links).
impl Clone for JointRows {
    fn clone(&self) -> Self {
        Self {
            values: self.values.clone(),
            gradients: self.gradients.clone(),
        }
    }

    fn clone_from(&mut self, source: &Self) {
        self.values.clone_from(&source.values);
        self.gradients.clone_from(&source.gradients);
    }
}

impl JointRows {
    /// Rows of `rows` constraints, zeroed.
    pub fn new(rows: usize) -> Self {
        Self {
            values: vec![0.0; rows],
            gradients: vec![RowGradient::zeros(); rows],
        }
    }
}

/// The joints of a multibody system, with the bookkeeping of their rows.
#[derive(Debug, Clone, PartialEq)]
pub struct JointSet {
    joints: Vec<Joint>,
    /// The first row of each joint, and the total at the end.
    offsets: Vec<usize>,
    /// The joint of each row.
    row_joint: Vec<usize>,
    /// For each body, the `(row, side)` pairs that involve it.
    body_rows: Vec<Vec<(usize, usize)>>,
    bandwidth: usize,
}

impl JointSet {
    /// The joints of a system of `bodies` bodies.
    ///
    /// # Errors
    /// [`InputError::InvalidOption`] when a joint names a body index `≥ bodies`.
    pub fn new(joints: Vec<Joint>, bodies: usize) -> Result<Self, Error> {
        let mut offsets = vec![0];
        let mut row_joint = Vec::new();
        let mut body_rows = vec![Vec::new(); bodies];
        for (j, joint) in joints.iter().enumerate() {
            let first = row_joint.len();
            for row in first..first + joint.kind.rows() {
                row_joint.push(j);
                for (side, body) in joint.bodies.iter().enumerate() {
                    let Some(b) = *body else { continue };
                    let list: &mut Vec<_> =
                        body_rows
                            .get_mut(b)
                            .ok_or(Error::Input(InputError::InvalidOption {
                                name: "joint body",
                                value: b as f64,
                                reason: "names a body index beyond the system's bodies",
                            }))?;
                    list.push((row, side));
                }
            }
            offsets.push(row_joint.len());
        }
        let bandwidth = body_rows
            .iter()
            .map(|rows| {
                let lo = rows.iter().map(|r| r.0).min().unwrap_or(0);
                let hi = rows.iter().map(|r| r.0).max().unwrap_or(0);
                hi - lo
            })
            .max()
            .unwrap_or(0);
        Ok(Self {
            joints,
            offsets,
            row_joint,
            body_rows,
            bandwidth,
        })
    }

    /// The joints.
    pub fn joints(&self) -> &[Joint] {
        &self.joints
    }

    /// The total number of rows.
    pub fn rows(&self) -> usize {
        self.row_joint.len()
    }

    /// The rows of joint `j`.
    pub fn joint_rows(&self, j: usize) -> std::ops::Range<usize> {
        self.offsets[j]..self.offsets[j + 1]
    }

    /// The joint that row `k` belongs to.
    pub fn joint_of_row(&self, k: usize) -> usize {
        self.row_joint[k]
    }

    /// The half-bandwidth of `H W Gᵀ` (module docs).
    pub fn bandwidth(&self) -> usize {
        self.bandwidth
    }

    /// The rows at the configuration `(R, x)` (flat, as [`crate::lie::state::RigidState`]).
    pub fn evaluate(
        &self,
        bodies: &[RigidBody],
        rotations: &[f64],
        positions: &[f64],
        out: &mut JointRows,
    ) {
        let side = |b: Option<usize>| match b {
            None => Side::ground(),
            Some(b) => Side {
                r: Mat3::from_row_slice(&rotations[9 * b..9 * b + 9]),
                x: Vec3::from_column_slice(&positions[3 * b..3 * b + 3]),
                turns: true,
                translates: bodies[b].mass.is_some(),
            },
        };
        for (j, joint) in self.joints.iter().enumerate() {
            let sides = [side(joint.bodies[0]), side(joint.bodies[1])];
            let rows = self.joint_rows(j);
            joint.evaluate(
                &sides,
                &mut out.values[rows.clone()],
                &mut out.gradients[rows],
            );
        }
    }

    /// Adds `Σ_k λ_k ∂g_k/∂ξ_b` to `moments[b]` and `Σ_k λ_k ∂g_k/∂x_b` to `forces[b]`.
    pub fn add_transpose(
        &self,
        rows: &JointRows,
        lambda: &[f64],
        moments: &mut [Vec3],
        forces: &mut [Vec3],
    ) {
        for (b, list) in self.body_rows.iter().enumerate() {
            for &(k, side) in list {
                let g = &rows.gradients[k];
                moments[b] += lambda[k] * g.fixed_rows::<3>(6 * side);
                forces[b] += lambda[k] * g.fixed_rows::<3>(6 * side + 3);
            }
        }
    }

    /// The rates `out_k = Σ_b ∂g_k/∂ξ_b · ω_b + ∂g_k/∂x_b · v_b`.
    pub fn rates(&self, rows: &JointRows, omega: &[Vec3], velocity: &[Vec3], out: &mut [f64]) {
        out.fill(0.0);
        for (b, list) in self.body_rows.iter().enumerate() {
            for &(k, side) in list {
                let g = &rows.gradients[k];
                out[k] += g.fixed_rows::<3>(6 * side).dot(&omega[b])
                    + g.fixed_rows::<3>(6 * side + 3).dot(&velocity[b]);
            }
        }
    }

    /// `a = scale · H W Gᵀ` (module docs), with `left = H`, `right = G`; `a` is reshaped.
    pub fn assemble(
        &self,
        left: &JointRows,
        right: &JointRows,
        weights: &[BodyWeight],
        scale: f64,
        a: &mut Banded,
    ) {
        a.reshape(self.rows(), self.bandwidth);
        for (b, list) in self.body_rows.iter().enumerate() {
            let w = &weights[b];
            for &(k, sk) in list {
                let hk = &left.gradients[k];
                let turned = w.rotation.transpose() * hk.fixed_rows::<3>(6 * sk);
                let moved = w.translation * hk.fixed_rows::<3>(6 * sk + 3);
                for &(l, sl) in list {
                    let gl = &right.gradients[l];
                    let entry = turned.dot(&gl.fixed_rows::<3>(6 * sl))
                        + moved.dot(&gl.fixed_rows::<3>(6 * sl + 3));
                    a.add(k, l, scale * entry);
                }
            }
        }
    }
}
