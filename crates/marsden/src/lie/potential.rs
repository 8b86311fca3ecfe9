//! Potentials and external loads of rigid bodies, and the body moment by automatic
//! differentiation.
//!
//! A potential `U(t, R₁ … R_m, x₁ … x_m)` is written once, generic over [`Scalar`] (the
//! attitudes as 9 numbers each, row-major `R11 … R33`, so an expression in `R11 … R33, x, y, z, t`
//! implements it). The step needs its **body moment**, the left-trivialised derivative of `−U`:
//! along `R exp(εξ^)`,
//!
//! ```text
//! d/dε U(R exp(εξ^))|₀ = tr[(∂U/∂R)ᵀ R ξ^] = −M · ξ,    M^ = (∂U/∂R)ᵀR − Rᵀ(∂U/∂R)
//! ```
//!
//! ([LLM07] eq. (9); for `U = mgl e₃·(R e₃)`, `M = mgl (Rᵀe₃) × e₃`). [`Loads::evaluate`] gets `M`
//! and `∂U/∂x` in one forward-mode pass ([`crate::numerics::ad::jacobian`]) of `U` at
//! `R_i(I + ξ_i^)`, `x_i + δx_i` seeded in `ξ` and `δx` (the first-order terms of `R exp(εξ^)`),
//! so no potential differentiates itself by hand.
//!
//! [LLM07]: crate#references

use super::so3::{Mat3, Vec3, vee};
use crate::numerics::ad::{MultiFunction, jacobian};
use crate::numerics::scratch::Buffer;
use crate::scalar::Scalar;

/// Inline capacity of the buffers of the perturbed configuration (12 numbers per body: two bodies
/// stay on the stack).
const INLINE: usize = 24;

/// A potential `U(t, R, x)` of `m` rigid bodies, generic over the scalar type.
pub trait RigidPotential {
    /// Whether `U` is identically zero (then no derivative is taken). Default `false`.
    const ZERO: bool = false;

    /// `U(t, R, x)`: `rotations` holds 9 entries per body (row-major `R11 … R33`), `positions`
    /// 3 per body (the centre of mass of a free body; zero for a body with a fixed point).
    fn value<S: Scalar>(&self, t: S, rotations: &[S], positions: &[S]) -> S;

    /// The partial derivatives `∂U/∂R` (9 per body, row-major, `R`'s entries taken as
    /// independent) and `∂U/∂x` (3 per body) in closed form, written into `d_rotations` and
    /// `d_positions` (which arrive zeroed); `false` (the default) if the potential has none,
    /// and the body moment is then taken by automatic differentiation of [`Self::value`].
    fn gradient(
        &self,
        _t: f64,
        _rotations: &[f64],
        _positions: &[f64],
        _d_rotations: &mut [f64],
        _d_positions: &mut [f64],
    ) -> bool {
        false
    }
}

/// `U = 0`: free rigid bodies (Euler's equations).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct NoPotential;

impl RigidPotential for NoPotential {
    const ZERO: bool = true;

    fn value<S: Scalar>(&self, _t: S, _rotations: &[S], _positions: &[S]) -> S {
        S::from(0.0)
    }
}

/// Uniform gravity along `−e₃`: `U = Σᵢ g e₃·(Rᵢ cᵢ) + Σᵢ g mᵢ e₃·xᵢ`, with `cᵢ = mᵢXᵢ` the first
/// moment of body `i` about its fixed point (the mass times the body-frame position of its centre
/// of mass; zero for a free body, whose `x` is its centre of mass).
#[derive(Debug, Clone, PartialEq)]
pub struct UniformGravity {
    /// The acceleration of gravity `g`.
    pub g: f64,
    /// `mᵢXᵢ` per body (body frame).
    pub first_moments: Vec<[f64; 3]>,
    /// `mᵢ` per free body (0 for a body with a fixed point).
    pub masses: Vec<f64>,
}

impl UniformGravity {
    /// The heavy top of one body: `U = mgl e₃·(R e₃)` (centre of mass at `l e₃` in the body).
    pub fn top(mgl: f64) -> Self {
        Self {
            g: 1.0,
            first_moments: vec![[0.0, 0.0, mgl]],
            masses: vec![0.0],
        }
    }
}

impl RigidPotential for UniformGravity {
    fn value<S: Scalar>(&self, _t: S, rotations: &[S], positions: &[S]) -> S {
        let mut u = S::from(0.0);
        for (i, c) in self.first_moments.iter().enumerate() {
            // e₃·(R c) is the third row of R times c.
            let row = &rotations[9 * i + 6..9 * i + 9];
            u += row[0] * c[0] + row[1] * c[1] + row[2] * c[2];
        }
        for (i, m) in self.masses.iter().enumerate() {
            if *m != 0.0 {
                u += positions[3 * i + 2] * *m;
            }
        }
        u * self.g
    }

    fn gradient(
        &self,
        _t: f64,
        _rotations: &[f64],
        _positions: &[f64],
        d_rotations: &mut [f64],
        d_positions: &mut [f64],
    ) -> bool {
        for (i, c) in self.first_moments.iter().enumerate() {
            for (d, c) in d_rotations[9 * i + 6..9 * i + 9].iter_mut().zip(c) {
                *d = self.g * c;
            }
        }
        for (i, m) in self.masses.iter().enumerate() {
            d_positions[3 * i + 2] = self.g * m;
        }
        true
    }
}

/// External loads not derived from a potential: a body-frame torque `τᵢ` and a spatial force
/// `fᵢ` on each body, functions of `(t, R, x)`. They enter the step by the discrete
/// Lagrange–d'Alembert principle with the trapezoidal rule: `(h/2)τ` at each end of the step,
/// like `(h/2)M` ([LLM07] §4, [MW01] §3.2).
///
/// [MW01]: crate#references
/// [LLM07]: crate#references
pub trait ExternalLoads {
    /// Whether there are loads at all (skips their evaluation when not). Default `true`.
    const ACTIVE: bool = true;

    /// Whether these loads act (a type that may or may not hold loads says so at run time).
    /// Default [`Self::ACTIVE`].
    fn is_active(&self) -> bool {
        Self::ACTIVE
    }

    /// Writes `τᵢ` (3 per body, body frame) into `torques` and `fᵢ` (3 per body, space frame;
    /// ignored for a body with a fixed point) into `forces`; both arrive zeroed.
    fn loads(
        &self,
        t: f64,
        rotations: &[f64],
        positions: &[f64],
        torques: &mut [f64],
        forces: &mut [f64],
    );
}

/// No external loads.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct NoLoads;

impl ExternalLoads for NoLoads {
    const ACTIVE: bool = false;

    fn loads(&self, _: f64, _: &[f64], _: &[f64], _: &mut [f64], _: &mut [f64]) {}
}

/// The generalised forces at one configuration: `M_i + τ_i` (body frame) and `f_i − ∂U/∂x_i`
/// (space frame), 3 numbers per body each.
#[derive(Debug, PartialEq, Default)]
pub struct Loads {
    /// `M_i + τ_i` per body.
    pub moments: Vec<Vec3>,
    /// `f_i − ∂U/∂x_i` per body (zero for a body with a fixed point).
    pub forces: Vec<Vec3>,
    gradient: Vec<f64>,
    scratch: Vec<f64>,
}

/// `U` at `R_i(I + ξ_i^)`, `x_i + δx_i` as a function of `(ξ, δx)` (for AD at 0).
struct Perturbed<'a, U> {
    potential: &'a U,
    t: f64,
    rotations: &'a [f64],
    positions: &'a [f64],
    free: &'a [usize],
}

impl<U: RigidPotential> MultiFunction for Perturbed<'_, U> {
    fn inputs(&self) -> usize {
        self.rotations.len() / 3 + 3 * self.free.len()
    }

    fn outputs(&self) -> usize {
        1
    }

    fn eval<S: Scalar>(&self, z: &[S], out: &mut [S]) {
        let bodies = self.rotations.len() / 9;
        let zero = S::from(0.0);
        // Row j of R(I + ξ^) is r_j + r_j × ξ.
        let rotation = |k: usize| {
            let (body, entry) = (k / 9, k % 9);
            let (row, col) = (entry / 3, entry % 3);
            let r = &self.rotations[9 * body + 3 * row..9 * body + 3 * row + 3];
            let xi = &z[3 * body..3 * body + 3];
            let (a, b) = ((col + 1) % 3, (col + 2) % 3);
            xi[b] * r[a] - xi[a] * r[b] + r[col]
        };
        let mut rotations = Buffer::<S, INLINE>::empty();
        let rotations = rotations.from_fn(9 * bodies, zero, rotation);
        let position = |k: usize| S::from(self.positions[k]);
        let mut positions = Buffer::<S, INLINE>::empty();
        let positions = positions.from_fn(3 * bodies, zero, position);
        for (slot, &body) in self.free.iter().enumerate() {
            for a in 0..3 {
                positions[3 * body + a] += z[3 * bodies + 3 * slot + a];
            }
        }
        out[0] = self.potential.value(S::from(self.t), rotations, positions);
    }
}

/// `clone_from` reusing the buffers (the step saves its loads every step).
impl Clone for Loads {
    fn clone(&self) -> Self {
        Self {
            moments: self.moments.clone(),
            forces: self.forces.clone(),
            gradient: self.gradient.clone(),
            scratch: self.scratch.clone(),
        }
    }

    fn clone_from(&mut self, source: &Self) {
        self.moments.clone_from(&source.moments);
        self.forces.clone_from(&source.forces);
        self.gradient.clone_from(&source.gradient);
        self.scratch.clone_from(&source.scratch);
    }
}

impl Loads {
    /// Zeroed loads of `bodies` bodies.
    pub fn new(bodies: usize) -> Self {
        Self {
            moments: vec![Vec3::zeros(); bodies],
            forces: vec![Vec3::zeros(); bodies],
            gradient: Vec::new(),
            scratch: Vec::new(),
        }
    }

    /// The loads at `(t, R, x)`: `M` and `∂U/∂x` by one AD pass over `U` (skipped when
    /// [`RigidPotential::ZERO`]), plus the external loads. `free` lists the free bodies.
    pub fn evaluate<U: RigidPotential, E: ExternalLoads>(
        &mut self,
        potential: &U,
        external: &E,
        config: Configuration<'_>,
    ) {
        let bodies = config.rotations.len() / 9;
        self.moments.iter_mut().for_each(|m| *m = Vec3::zeros());
        self.forces.iter_mut().for_each(|f| *f = Vec3::zeros());
        if !U::ZERO {
            self.differentiate(potential, &config, bodies);
        }
        if E::ACTIVE && external.is_active() {
            self.add_external(external, &config, bodies);
        }
    }

    fn differentiate<U: RigidPotential>(
        &mut self,
        potential: &U,
        config: &Configuration<'_>,
        bodies: usize,
    ) {
        if self.closed_form(potential, config, bodies) {
            return;
        }
        let f = Perturbed {
            potential,
            t: config.t,
            rotations: config.rotations,
            positions: config.positions,
            free: config.free,
        };
        let n = f.inputs();
        self.scratch.clear();
        self.scratch.resize(n, 0.0);
        self.gradient.resize(n, 0.0);
        let mut value = [0.0];
        jacobian(&f, &self.scratch, 0..n, &mut value, &mut self.gradient);
        for (i, m) in self.moments.iter_mut().enumerate() {
            *m = -Vec3::new(
                self.gradient[3 * i],
                self.gradient[3 * i + 1],
                self.gradient[3 * i + 2],
            );
        }
        for (slot, &body) in config.free.iter().enumerate() {
            let g = &self.gradient[3 * bodies + 3 * slot..3 * bodies + 3 * slot + 3];
            self.forces[body] = -Vec3::new(g[0], g[1], g[2]);
        }
    }

    /// The loads from `∂U/∂R` and `∂U/∂x` when the potential has them in closed form:
    /// `M^ = GᵀR − RᵀG` with `G = ∂U/∂R` (the left-trivialised derivative of the module doc),
    /// `f = −∂U/∂x`. `false` if it has not.
    fn closed_form<U: RigidPotential>(
        &mut self,
        potential: &U,
        config: &Configuration<'_>,
        bodies: usize,
    ) -> bool {
        // The AD path's buffers, reused: no allocation per step for any number of bodies.
        let (d_rotations, d_positions) = (&mut self.scratch, &mut self.gradient);
        d_rotations.clear();
        d_rotations.resize(9 * bodies, 0.0);
        d_positions.clear();
        d_positions.resize(3 * bodies, 0.0);
        let (t, rotations, positions) = (config.t, config.rotations, config.positions);
        if !potential.gradient(t, rotations, positions, d_rotations, d_positions) {
            return false;
        }
        for (i, m) in self.moments.iter_mut().enumerate() {
            let g = Mat3::from_row_slice(&d_rotations[9 * i..9 * i + 9]);
            let r = Mat3::from_row_slice(&rotations[9 * i..9 * i + 9]);
            *m = vee(&(g.transpose() * r - r.transpose() * g));
        }
        for &body in config.free {
            let g = &d_positions[3 * body..3 * body + 3];
            self.forces[body] = -Vec3::new(g[0], g[1], g[2]);
        }
        true
    }

    fn add_external<E: ExternalLoads>(
        &mut self,
        external: &E,
        config: &Configuration<'_>,
        bodies: usize,
    ) {
        let mut torques = Buffer::<f64, INLINE>::empty();
        let torques = torques.filled(3 * bodies, 0.0);
        let mut forces = Buffer::<f64, INLINE>::empty();
        let forces = forces.filled(3 * bodies, 0.0);
        external.loads(
            config.t,
            config.rotations,
            config.positions,
            torques,
            forces,
        );
        for i in 0..bodies {
            self.moments[i] += Vec3::new(torques[3 * i], torques[3 * i + 1], torques[3 * i + 2]);
        }
        for &body in config.free {
            let i = body;
            self.forces[i] += Vec3::new(forces[3 * i], forces[3 * i + 1], forces[3 * i + 2]);
        }
    }
}

/// A configuration of `m` bodies as flat slices, where the loads are evaluated.
#[derive(Debug, Clone, Copy)]
pub struct Configuration<'a> {
    /// Time.
    pub t: f64,
    /// 9 entries per body, row-major.
    pub rotations: &'a [f64],
    /// 3 per body.
    pub positions: &'a [f64],
    /// Indices of the free bodies (whose positions move).
    pub free: &'a [usize],
}
