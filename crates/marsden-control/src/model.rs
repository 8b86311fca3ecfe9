//! The continuous ingredients of an optimal control problem, written once over [`Scalar`] so
//! that automatic differentiation reaches them: the controlled force `f(t, q, v, u)`, the
//! running cost `C(t, q, v, u)`, the final cost `Φ(q_N, p_N)` and the path inequalities
//! `g(t, q, v, u) ≤ 0`.
//!
//! The controls `u` (m components) are piecewise constant: `u_k` acts on `[t_k, t_{k+1}]`
//! ([OJM11] §3). Ready-made: [`InputMap`] (each control a generalised force on one coordinate,
//! the control-affine `f = B u` with `B` a selection matrix) and [`Effort`] (`C = ½ w |u|²`).
//!
//! [OJM11]: crate#references

use marsden::Scalar;

/// A generalised force that depends on the controls: `f(t, q, v, u) ∈ T*Q`.
pub trait ControlForce {
    /// The number of controls `m`.
    fn controls(&self) -> usize;
    /// Writes `f(t, q, v, u)` into `out` (length n); `u` has length [`ControlForce::controls`].
    fn force<S: Scalar>(&self, t: S, q: &[S], v: &[S], u: &[S], out: &mut [S]);
}

impl<F: ControlForce + ?Sized> ControlForce for &F {
    fn controls(&self) -> usize {
        (**self).controls()
    }
    fn force<S: Scalar>(&self, t: S, q: &[S], v: &[S], u: &[S], out: &mut [S]) {
        (**self).force(t, q, v, u, out)
    }
}

/// The running cost `C(t, q, v, u)` of `J = ∫ C dt + Φ`.
pub trait RunningCost {
    /// `C(t, q, v, u)`.
    fn cost<S: Scalar>(&self, t: S, q: &[S], v: &[S], u: &[S]) -> S;
}

impl<C: RunningCost + ?Sized> RunningCost for &C {
    fn cost<S: Scalar>(&self, t: S, q: &[S], v: &[S], u: &[S]) -> S {
        (**self).cost(t, q, v, u)
    }
}

/// The final cost `Φ(q_N, p_N)`, with `p_N` the forced discrete Legendre transform of the last
/// step.
pub trait FinalCost {
    /// `Φ(q, p)`.
    fn cost<S: Scalar>(&self, q: &[S], p: &[S]) -> S;
}

impl<P: FinalCost + ?Sized> FinalCost for &P {
    fn cost<S: Scalar>(&self, q: &[S], p: &[S]) -> S {
        (**self).cost(q, p)
    }
}

/// No final cost: `Φ = 0` (the default).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct NoFinalCost;

impl FinalCost for NoFinalCost {
    fn cost<S: Scalar>(&self, _q: &[S], _p: &[S]) -> S {
        S::from(0.0)
    }
}

/// Path inequalities `g(t, q, v, u) ≤ 0` (`count` of them), required along the trajectory:
/// the transcription imposes them at the points of each step where the controls act
/// ([`crate::transcription`]).
pub trait PathConstraint {
    /// The number of inequalities `n_g`.
    fn count(&self) -> usize;
    /// Writes `g(t, q, v, u)` into `out` (length [`PathConstraint::count`]).
    fn eval<S: Scalar>(&self, t: S, q: &[S], v: &[S], u: &[S], out: &mut [S]);
}

impl<G: PathConstraint + ?Sized> PathConstraint for &G {
    fn count(&self) -> usize {
        (**self).count()
    }
    fn eval<S: Scalar>(&self, t: S, q: &[S], v: &[S], u: &[S], out: &mut [S]) {
        (**self).eval(t, q, v, u, out)
    }
}

/// No path inequalities (the default).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct NoPath;

impl PathConstraint for NoPath {
    fn count(&self) -> usize {
        0
    }
    fn eval<S: Scalar>(&self, _t: S, _q: &[S], _v: &[S], _u: &[S], _out: &mut [S]) {}
}

/// Controls acting directly on coordinates: `f_i = Σ_{j : coordinate_j = i} u_j`, zero on the
/// other coordinates (a torque on a joint, a force on a cart).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct InputMap {
    /// The coordinate control `j` acts on.
    pub coordinates: Vec<usize>,
}

impl InputMap {
    /// Control `j` pushes coordinate `coordinates[j]`.
    pub fn new(coordinates: &[usize]) -> Self {
        Self {
            coordinates: coordinates.to_vec(),
        }
    }

    /// One control per coordinate, `f = u` (`n` controls).
    pub fn full(n: usize) -> Self {
        Self {
            coordinates: (0..n).collect(),
        }
    }
}

impl ControlForce for InputMap {
    fn controls(&self) -> usize {
        self.coordinates.len()
    }
    fn force<S: Scalar>(&self, _t: S, _q: &[S], _v: &[S], u: &[S], out: &mut [S]) {
        out.iter_mut().for_each(|f| *f = S::from(0.0));
        for (&i, &uj) in self.coordinates.iter().zip(u) {
            if let Some(f) = out.get_mut(i) {
                *f += uj;
            }
        }
    }
}

/// The control effort `C = ½ w |u|²`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Effort {
    /// The weight `w`.
    pub weight: f64,
}

impl Default for Effort {
    fn default() -> Self {
        Self { weight: 1.0 }
    }
}

impl RunningCost for Effort {
    fn cost<S: Scalar>(&self, _t: S, _q: &[S], _v: &[S], u: &[S]) -> S {
        u.iter().fold(S::from(0.0), |s, &x| s + x * x) * (0.5 * self.weight)
    }
}
