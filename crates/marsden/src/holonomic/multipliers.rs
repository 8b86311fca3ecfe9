//! The multipliers `λ` of a constrained state: the constraint forces the state itself implies.
//!
//! Differentiating the hidden constraint `Dφ(q) v = 0` once more along the constrained
//! Euler–Lagrange equations `W a = f(t, q, v) − Dφ(q)ᵀλ` ([`crate::holonomic`]; `W = ∂²L/∂v²`,
//! `f = ∂L/∂q − ∂²L/∂v∂q v − ∂²L/∂v∂t`) gives `Dφ a + D²φ(v, v) = 0`, hence
//!
//! ```text
//!     (Dφ W⁻¹ Dφᵀ) λ = Dφ a_free + D²φ(q)(v, v),      a_free = W⁻¹ f,
//! ```
//!
//! the index reduction of [HLW06] §VII.1 (eq. 1.11). Evaluated at the states of a run it
//! inherits their accuracy: `λ` at the method's order, at every stored state including the
//! first. (The step's own multipliers are those of a quadrature of the constraint force,
//! [`crate::Integrator::end_multipliers`]; for RATTLE they approximate `λ(t)` only at order 1.)
//!
//! [HLW06]: crate#references

use crate::error::{Error, SetupError};
use crate::mechanics::{Constraint, Lagrangian, LagrangianJet, acceleration, constraint_jacobian};
use crate::numerics::ad::{self, MultiFunction};
use crate::numerics::dense::Lu;
use crate::scalar::Scalar;

/// One component `φ_c` of a constraint, as a scalar function for second derivatives.
struct Component<'a, C>(&'a C, usize, usize);

impl<C: Constraint> MultiFunction for Component<'_, C> {
    fn inputs(&self) -> usize {
        self.2
    }
    fn outputs(&self) -> usize {
        self.0.count()
    }
    fn eval<S: Scalar>(&self, x: &[S], out: &mut [S]) {
        self.0.constraint(x, out);
        out.swap(0, self.1);
    }
}

/// The multipliers `λ` (length d) implied by the state `(t, q, v)` on `T N`.
///
/// # Errors
/// [`SetupError::SingularLagrangian`] if `W` is singular, [`SetupError::SingularConstraintMass`]
/// if `Dφ W⁻¹ Dφᵀ` is.
pub fn multipliers_at<L: Lagrangian, C: Constraint>(
    lagrangian: &L,
    constraint: &C,
    t: f64,
    q: &[f64],
    v: &[f64],
) -> Result<Vec<f64>, Error> {
    let (n, d) = (q.len(), constraint.count());
    if d == 0 {
        return Ok(Vec::new());
    }
    let mut free = vec![0.0; n];
    acceleration(lagrangian, t, q, v, &mut free)?;
    let (mut phi, mut g) = (vec![0.0; d], vec![0.0; d * n]);
    constraint_jacobian(constraint, q, &mut phi, &mut g);
    // W⁻¹ Dφᵀ, column by column.
    let jet = LagrangianJet::at(lagrangian, t, q, v);
    let mut w = Lu::new();
    w.factor(&jet.d2l_dv2, n).map_err(|e| {
        Error::Setup(SetupError::SingularLagrangian {
            t,
            q: q.to_vec(),
            v: v.to_vec(),
            pivot: e.pivot,
            scale: crate::numerics::dense::max_norm(&jet.d2l_dv2),
        })
    })?;
    let mut scratch = Vec::with_capacity(n);
    let mut columns = g.clone();
    for column in columns.chunks_exact_mut(n) {
        w.solve(column, &mut scratch);
    }
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let mut matrix = vec![0.0; d * d];
    let mut rhs = vec![0.0; d];
    for c in 0..d {
        let row = &g[c * n..(c + 1) * n];
        for e in 0..d {
            matrix[c * d + e] = dot(row, &columns[e * n..(e + 1) * n]);
        }
        rhs[c] = dot(row, &free) + ad::directional_second(&Component(constraint, c, n), q, v, v);
    }
    let mut lu = Lu::new();
    lu.factor(&matrix, d).map_err(|e| {
        Error::Setup(SetupError::SingularConstraintMass {
            t,
            q: q.to_vec(),
            pivot: e.pivot,
        })
    })?;
    lu.solve(&mut rhs, &mut scratch);
    Ok(rhs)
}
