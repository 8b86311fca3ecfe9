//! Lie group actions on configuration space, given by their infinitesimal generators.
//!
//! Concept of the notes (MW01): *the Lagrangian momentum map*, *Hamiltonian momentum maps*. A left action
//! `Φ: G × Q → Q` of a Lie group with Lie algebra `𝔤` has, for every `ξ ∈ 𝔤`, the infinitesimal
//! generator
//!
//! ```text
//!     ξ_Q(q) = d/dε|₀ Φ(exp(εξ), q),
//! ```
//!
//! and it lifts to the tangent and cotangent bundles ([MW01] §1.3.3, [MR99] §11.4):
//!
//! ```text
//!     ξ_TQ(q, v)  = (ξ_Q(q),  Dξ_Q(q)·v),          (tangent lift)
//!     ξ_T*Q(q, p) = (ξ_Q(q), −Dξ_Q(q)ᵀ·p).         (cotangent lift)
//! ```
//!
//! A [`GroupAction`] is written once over [`Scalar`] (like a Lagrangian), so the lifts are
//! computed here by automatic differentiation of the generator. Everything is expressed in a
//! fixed basis `e₀ … e_{m−1}` of `𝔤` (`m` = [`GroupAction::algebra_dim`]); `𝔤*` uses the dual
//! basis, so a momentum map is a vector of `m` numbers.
//!
//! [MW01]: crate#references
//! [MR99]: crate#references

use crate::error::Error;
use crate::error::{InputError, StepError, StepFailure};
use crate::numerics::ad::{self, MultiFunction};
use crate::numerics::dense::Lu;
use crate::scalar::Scalar;

/// A Lie group action on `Q = ℝⁿ`, given by its infinitesimal generators `ξ_Q(q)`.
///
/// Implement it for your own symmetry (the generator must be generic over [`Scalar`], so it is a
/// trait rather than a closure):
///
/// ```
/// use marsden::{Scalar, symmetry::GroupAction};
///
/// /// Screw motion along z of one particle in ℝ³: rotation about z coupled with translation
/// /// along z at pitch `c`, ξ_Q(q) = (−y, x, c).
/// struct Screw { pitch: f64 }
///
/// impl GroupAction for Screw {
///     fn name(&self) -> String { format!("screw motion (pitch {})", self.pitch) }
///     fn dof(&self) -> usize { 3 }
///     fn algebra_dim(&self) -> usize { 1 }
///     fn generator<S: Scalar>(&self, _a: usize, q: &[S], out: &mut [S]) {
///         out[0] = -q[1];
///         out[1] = q[0];
///         out[2] = S::from(self.pitch);
///     }
/// }
/// ```
pub trait GroupAction {
    /// A short name used in reports and errors, e.g. `"rotations SO(3) of 2 particles"`.
    fn name(&self) -> String;

    /// Dimension `n` of the configuration space acted on (the number of components of every
    /// generator `ξ_Q(q)`).
    fn dof(&self) -> usize;

    /// Dimension `m` of the Lie algebra `𝔤` (number of basis generators; components of `J`).
    fn algebra_dim(&self) -> usize;

    /// Writes the infinitesimal generator `(e_a)_Q(q)` of basis element `a < m` into `out`
    /// (length n). Every component must be written.
    fn generator<S: Scalar>(&self, a: usize, q: &[S], out: &mut [S]);
}

/// A group action whose finite transformations are known: `Φ_g(q)` for `g = exp(ξ)`, and the
/// coadjoint action needed for equivariance (`J ∘ Φ_g^{T*Q} = Ad*_{g⁻¹} ∘ J`, seed:
/// *equivariance*).
pub trait FiniteAction: GroupAction {
    /// Writes `Φ_g(q)` for `g = exp(Σ_a ξ_a e_a)` (exponential coordinates, length m) into `out`.
    fn act<S: Scalar>(&self, xi: &[f64], q: &[S], out: &mut [S]);

    /// Writes `Ad*_{g⁻¹} μ` for `g = exp(ξ)` and `μ ∈ 𝔤*` (dual-basis coordinates) into `out`.
    fn coadjoint(&self, xi: &[f64], mu: &[f64], out: &mut [f64]);
}

/// Checks that `action` fits a system with `dof` degrees of freedom and that its generators are
/// finite and fully written at `q`.
///
/// Errors: [`crate::error::InputError::SymmetryDimension`] if `action.dof() ≠ dof` (generators
/// with the wrong number of components), [`crate::error::InputError::InvalidGenerator`] for a
/// non-finite or unwritten component
/// (each output is pre-filled with NaN, so a component the generator forgets stays NaN).
pub fn validate<G: GroupAction>(action: &G, dof: usize, q: &[f64]) -> Result<(), Error> {
    if action.dof() != dof || q.len() != dof {
        return Err(Error::Input(InputError::SymmetryDimension {
            symmetry: action.name(),
            expected: dof,
            found: action.dof(),
        }));
    }
    let mut xi = vec![f64::NAN; dof];
    for a in 0..action.algebra_dim() {
        xi.fill(f64::NAN);
        action.generator(a, q, &mut xi);
        if let Some(component) = xi.iter().position(|x| !x.is_finite()) {
            return Err(Error::Input(InputError::InvalidGenerator {
                symmetry: action.name(),
                generator: a,
                component,
                value: xi[component],
                q: q.to_vec(),
            }));
        }
    }
    Ok(())
}

/// All generators at `q`, row-major `m × n`: row `a` is `(e_a)_Q(q)`.
pub fn generators<G: GroupAction>(action: &G, q: &[f64], out: &mut Vec<f64>) {
    let n = q.len();
    out.clear();
    out.resize(action.algebra_dim() * n, 0.0);
    for (a, row) in out
        .chunks_exact_mut(n.max(1))
        .enumerate()
        .take(action.algebra_dim())
    {
        action.generator(a, q, row);
    }
}

/// One generator as a vector function of `q`, for the AD drivers.
struct Generator<'a, G> {
    action: &'a G,
    a: usize,
}

impl<G: GroupAction> MultiFunction for Generator<'_, G> {
    fn inputs(&self) -> usize {
        self.action.dof()
    }
    fn outputs(&self) -> usize {
        self.action.dof()
    }
    fn eval<S: Scalar>(&self, x: &[S], out: &mut [S]) {
        self.action.generator(self.a, x, out);
    }
}

/// `ξ_Q(q)` and its Jacobian `Dξ_Q(q)` (row-major n × n) for basis element `a`, by AD.
pub fn generator_jacobian<G: GroupAction>(
    action: &G,
    a: usize,
    q: &[f64],
    xi: &mut [f64],
    jac: &mut [f64],
) {
    let n = q.len();
    ad::jacobian(&Generator { action, a }, q, 0..n, xi, jac);
}

/// Tangent lift `ξ_TQ(q, v) = (ξ_Q(q), Dξ_Q(q)·v)` of basis element `a`, by AD.
pub fn tangent_lift<G: GroupAction>(
    action: &G,
    a: usize,
    q: &[f64],
    v: &[f64],
    dq: &mut [f64],
    dv: &mut [f64],
) {
    let n = q.len();
    let mut jac = vec![0.0; n * n];
    generator_jacobian(action, a, q, dq, &mut jac);
    for (i, out) in dv.iter_mut().enumerate().take(n) {
        *out = (0..n).map(|j| jac[i * n + j] * v[j]).sum();
    }
}

/// Cotangent lift `ξ_T*Q(q, p) = (ξ_Q(q), −Dξ_Q(q)ᵀ·p)` of basis element `a`, by AD.
///
/// It is the Hamiltonian vector field of `J_H·e_a = ⟨p, ξ_Q(q)⟩` (seed: *Hamiltonian momentum
/// maps*).
pub fn cotangent_lift<G: GroupAction>(
    action: &G,
    a: usize,
    q: &[f64],
    p: &[f64],
    dq: &mut [f64],
    dp: &mut [f64],
) {
    let n = q.len();
    let mut jac = vec![0.0; n * n];
    generator_jacobian(action, a, q, dq, &mut jac);
    for (j, out) in dp.iter_mut().enumerate().take(n) {
        *out = -(0..n).map(|i| jac[i * n + j] * p[i]).sum::<f64>();
    }
}

/// The finite action as a vector function of `q`, for the AD drivers.
struct Finite<'a, G> {
    action: &'a G,
    xi: &'a [f64],
}

impl<G: FiniteAction> MultiFunction for Finite<'_, G> {
    fn inputs(&self) -> usize {
        self.action.dof()
    }
    fn outputs(&self) -> usize {
        self.action.dof()
    }
    fn eval<S: Scalar>(&self, x: &[S], out: &mut [S]) {
        self.action.act(self.xi, x, out);
    }
}

/// Cotangent lift of the finite action: `Φ_g^{T*Q}(q, p) = (Φ_g(q), DΦ_g(q)⁻ᵀ p)`, with the
/// derivative `DΦ_g(q)` by AD (seed: *Hamiltonian momentum maps*, cotangent lift).
///
/// Errors with [`crate::error::StepError::SingularJacobian`] if `DΦ_g(q)` is not invertible
/// (not a group action).
pub fn act_cotangent<G: FiniteAction>(
    action: &G,
    xi: &[f64],
    q: &[f64],
    p: &[f64],
    gq: &mut [f64],
    gp: &mut [f64],
) -> Result<(), Error> {
    let n = q.len();
    let mut jac = vec![0.0; n * n];
    ad::jacobian(&Finite { action, xi }, q, 0..n, gq, &mut jac);
    // Solve DΦᵀ p' = p.
    let transposed: Vec<f64> = (0..n * n).map(|k| jac[(k % n) * n + k / n]).collect();
    let mut lu = Lu::new();
    lu.factor(&transposed, n).map_err(|e| {
        Error::Step(StepFailure {
            step: 0,
            t: 0.0,
            cause: StepError::SingularJacobian {
                iteration: 0,
                pivot: e.pivot,
            },
        })
    })?;
    gp.copy_from_slice(p);
    lu.solve(gp, &mut Vec::with_capacity(n));
    Ok(())
}

/// Tangent lift of the finite action: `Φ_g^{TQ}(q, v) = (Φ_g(q), DΦ_g(q)·v)`, by AD.
pub fn act_tangent<G: FiniteAction>(
    action: &G,
    xi: &[f64],
    q: &[f64],
    v: &[f64],
    gq: &mut [f64],
    gv: &mut [f64],
) {
    let n = q.len();
    let mut jac = vec![0.0; n * n];
    ad::jacobian(&Finite { action, xi }, q, 0..n, gq, &mut jac);
    for (i, out) in gv.iter_mut().enumerate().take(n) {
        *out = (0..n).map(|j| jac[i * n + j] * v[j]).sum();
    }
}
