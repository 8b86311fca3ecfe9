//! Initial data on the constraint manifold: checks, rank, and explicit projections.
//!
//! A constrained run must start on `T*N`: `φ(q₀) = 0` and `Dφ(q₀)·v₀ = 0`, with `Dφ(q₀)` of full
//! row rank so that the multipliers are determined ([HLW06] §VII.1: the index-3 DAE needs
//! `Dφ M⁻¹ Dφᵀ` invertible). [`check_initial`] verifies all three and names the residual;
//! nothing here moves data unless asked: [`project_position`] and [`project_momentum`] (and
//! [`crate::mechanics::Initial::project_onto`]) are explicit, opt-in projections.
//!
//! [HLW06]: crate#references

use crate::error::Error;
use crate::error::{SetupError, StepError, StepFailure};
use crate::mechanics;
use crate::mechanics::constraint_jacobian;
use crate::mechanics::{Constraint, Initial, Lagrangian};
use crate::numerics::dense::{Lu, max_norm};

use super::{MomentumProjection, Rattle};

/// Default tolerance of [`check_initial`]: `1e-12`, relative (see there for the scaling).
pub const DEFAULT_TOLERANCE: f64 = 1e-12;

/// A singular value of `Dφ` counts as zero below `RANK_TOLERANCE · σ_max` (`1e-10`): constraints
/// that close to dependent make the step's Newton matrix numerically singular anyway.
pub const RANK_TOLERANCE: f64 = 1e-10;

/// The numerical rank of `Dφ(q)` from its singular values.
#[derive(Debug, Clone, PartialEq)]
pub struct ConstraintRank {
    /// Number of constraints `d`.
    pub count: usize,
    /// Number of singular values above `threshold`.
    pub rank: usize,
    /// Singular values of `Dφ(q)`, largest first (`min(d, n)` of them).
    pub singular_values: Vec<f64>,
    /// `RANK_TOLERANCE · σ_max`.
    pub threshold: f64,
}

impl ConstraintRank {
    /// `Ok` if `Dφ` has full row rank, else [`crate::error::SetupError::RedundantConstraints`].
    pub fn full_rank(self, q: &[f64]) -> Result<(), Error> {
        if self.rank == self.count {
            Ok(())
        } else {
            Err(Error::Setup(SetupError::RedundantConstraints {
                count: self.count,
                rank: self.rank,
                singular_values: self.singular_values,
                threshold: self.threshold,
                q: q.to_vec(),
            }))
        }
    }
}

/// `φ(q)` and `Dφ(q)` (row-major d × n).
fn evaluate<C: Constraint>(c: &C, q: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let d = c.count();
    let mut phi = vec![0.0; d];
    let mut g = vec![0.0; d * q.len()];
    if d > 0 {
        constraint_jacobian(c, q, &mut phi, &mut g);
    }
    (phi, g)
}

/// The numerical rank of `Dφ(q)` by a singular value decomposition.
pub fn constraint_rank<C: Constraint>(c: &C, q: &[f64]) -> ConstraintRank {
    let (d, n) = (c.count(), q.len());
    let (_, g) = evaluate(c, q);
    let mut singular_values: Vec<f64> = if d == 0 || n == 0 {
        Vec::new()
    } else {
        nalgebra::DMatrix::from_row_slice(d, n, &g)
            .singular_values()
            .iter()
            .copied()
            .collect()
    };
    singular_values.sort_by(|a, b| b.total_cmp(a));
    let threshold = RANK_TOLERANCE * singular_values.first().copied().unwrap_or(0.0);
    let rank = singular_values
        .iter()
        .filter(|&&s| s > threshold && s > 0.0)
        .count();
    ConstraintRank {
        count: d,
        rank,
        singular_values,
        threshold,
    }
}

/// Index and value of the entry of largest magnitude.
fn worst(x: &[f64]) -> (usize, f64) {
    x.iter().enumerate().fold((0, 0.0), |best, (i, &v)| {
        if v.abs() > best.1.abs() || v.is_nan() {
            (i, v)
        } else {
            best
        }
    })
}

/// Checks initial data against the constraints, in this order:
///
/// 1. positions: `‖φ(q₀)‖∞ ≤ tol · max(1, ‖q₀‖∞ ‖Dφ(q₀)‖_max)` (the scale of `φ` near `q₀`),
///    else [`crate::error::SetupError::InitialPositionOffConstraint`];
/// 2. rank: `Dφ(q₀)` has full row rank ([`constraint_rank`]), else
///    [`crate::error::SetupError::RedundantConstraints`];
/// 3. velocities: `‖Dφ(q₀) v₀‖∞ ≤ tol · max(1, ‖Dφ(q₀)‖_max ‖v₀‖∞)`, else
///    [`crate::error::SetupError::InitialVelocityNotTangent`] (`what` names the input:
///    `"velocity v0"` or `"momentum p0"` when `v₀ = FH(q₀, p₀)`).
pub fn check_initial<C: Constraint>(
    c: &C,
    q: &[f64],
    v: &[f64],
    what: &'static str,
    tolerance: f64,
) -> Result<(), Error> {
    if c.count() == 0 {
        return Ok(());
    }
    let n = q.len();
    let (phi, g) = evaluate(c, q);
    let g_size = max_norm(&g);
    let (index, residual) = worst(&phi);
    let tol = tolerance * (max_norm(q) * g_size).max(1.0);
    if residual.is_nan() || residual.abs() > tol {
        return Err(Error::Setup(SetupError::InitialPositionOffConstraint {
            index,
            residual,
            tolerance: tol,
        }));
    }
    constraint_rank(c, q).full_rank(q)?;
    let gv: Vec<f64> = g
        .chunks_exact(n.max(1))
        .map(|row| row.iter().zip(v).map(|(a, b)| a * b).sum())
        .collect();
    let (index, residual) = worst(&gv);
    let tol = tolerance * (g_size * max_norm(v)).max(1.0);
    if residual.is_nan() || residual.abs() > tol {
        return Err(Error::Setup(SetupError::InitialVelocityNotTangent {
            what,
            index,
            residual,
            tolerance: tol,
        }));
    }
    Ok(())
}

/// Result of [`project_position`].
#[derive(Debug, Clone, PartialEq)]
pub struct PositionProjection {
    /// The projected positions, `φ(q) = 0` to round-off.
    pub q: Vec<f64>,
    /// Newton iterations used.
    pub iterations: usize,
    /// `‖φ(q)‖∞` at the result.
    pub residual: f64,
}

/// Projects `q` onto `φ(q) = 0` by Newton's method on the minimum-norm correction,
/// `q ← q − Dφ(q)ᵀ (Dφ(q) Dφ(q)ᵀ)⁻¹ φ(q)` (Gauss–Newton for the underdetermined system; each
/// correction is the shortest one that solves the linearised constraints, and for a sphere the
/// result is the nearest point). Converges to round-off, or fails with
/// [`crate::error::SetupError::PositionProjectionFailed`] after 50 iterations or when `Dφ Dφᵀ` is
/// singular (for instance when `φ(q) = 0` has no solution).
pub fn project_position<C: Constraint>(c: &C, q: &[f64]) -> Result<PositionProjection, Error> {
    project_in_metric(c, q, None)
}

/// Projects `q` onto `φ(q) = 0` in the metric of the mass matrix `W` (row-major n × n, e.g.
/// `∂²L/∂v²` at the initial state): `q ← q − W⁻¹Dφᵀ (Dφ W⁻¹ Dφᵀ)⁻¹ φ(q)`, the nearest point in
/// the kinetic-energy norm to first order (for a point mass on a sphere the same as
/// [`project_position`]). Fails as [`project_position`] does, and with
/// [`crate::error::SetupError::PositionProjectionFailed`] at iteration 0 if `W` is singular.
pub fn project_position_in_metric<C: Constraint>(
    c: &C,
    q: &[f64],
    mass: &[f64],
) -> Result<PositionProjection, Error> {
    let mut w = Lu::new();
    w.factor(mass, q.len()).map_err(|_| {
        Error::Setup(SetupError::PositionProjectionFailed {
            iterations: 0,
            index: 0,
            residual: f64::NAN,
        })
    })?;
    project_in_metric(c, q, Some(&w))
}

/// Gauss–Newton for `φ(q) = 0` with corrections `W⁻¹Dφᵀy` (`W = I` without a metric).
fn project_in_metric<C: Constraint>(
    c: &C,
    q: &[f64],
    metric: Option<&Lu>,
) -> Result<PositionProjection, Error> {
    const MAX_ITERATIONS: usize = 50;
    let (d, n) = (c.count(), q.len());
    let mut q = q.to_vec();
    let mut lu = Lu::new();
    let mut gram = vec![0.0; d * d];
    let mut scratch = Vec::with_capacity(d);
    let (mut last_update, mut previous) = (f64::INFINITY, f64::INFINITY);
    for iterations in 0..=MAX_ITERATIONS {
        let (phi, g) = evaluate(c, &q);
        // W⁻¹Dφᵀ, row by row (the rows of Dφ are the columns of Dφᵀ).
        let mut wg = g.clone();
        if let Some(w) = metric {
            let mut work = Vec::with_capacity(n);
            wg.chunks_exact_mut(n.max(1))
                .for_each(|row| w.solve(row, &mut work));
        }
        let (index, residual) = worst(&phi);
        let scale = (max_norm(&q) * max_norm(&g)).max(1.0);
        // At round-off: tiny residual, a round-off-sized update, or a stalled small residual.
        let converged = residual.abs() <= 4.0 * f64::EPSILON * scale
            || last_update <= 4.0 * f64::EPSILON * max_norm(&q).max(1.0)
            || (residual.abs() >= previous && residual.abs() <= 1e-12 * scale);
        previous = residual.abs();
        if converged && residual.is_finite() {
            return Ok(PositionProjection {
                q,
                iterations,
                residual: residual.abs(),
            });
        }
        let failure = Error::Setup(SetupError::PositionProjectionFailed {
            iterations,
            index,
            residual,
        });
        if iterations == MAX_ITERATIONS || !residual.is_finite() {
            return Err(failure);
        }
        for a in 0..d {
            for b in 0..d {
                gram[a * d + b] = (0..n).map(|j| g[a * n + j] * wg[b * n + j]).sum();
            }
        }
        lu.factor(&gram, d).map_err(|_| failure)?;
        let mut y = phi;
        lu.solve(&mut y, &mut scratch);
        let delta: Vec<f64> = (0..n)
            .map(|j| (0..d).map(|a| wg[a * n + j] * y[a]).sum::<f64>())
            .collect();
        q.iter_mut().zip(&delta).for_each(|(qi, di)| *qi -= di);
        last_update = max_norm(&delta);
    }
    Err(Error::Setup(SetupError::PositionProjectionFailed {
        iterations: MAX_ITERATIONS,
        index: 0,
        residual: f64::NAN,
    }))
}

/// Projects momenta `p` at `(t, q)` onto the cotangent space of the constraint manifold:
/// `p ← p − Dφ(q)ᵀν` with `Dφ(q)·FH(t, q, p) = 0` (the RATTLE projection, [`Rattle`]). Returns
/// the multipliers `ν`.
pub fn project_momentum<L: Lagrangian, C: Constraint>(
    lagrangian: &L,
    constraint: &C,
    t: f64,
    q: &[f64],
    p: &mut [f64],
) -> Result<Vec<f64>, Error> {
    let mut rattle = Rattle::new(lagrangian, constraint);
    project_with(&mut rattle, t, q, p)?;
    Ok(rattle.multipliers().to_vec())
}

fn project_with<L: Lagrangian, C: Constraint>(
    rattle: &mut Rattle<L, C>,
    t: f64,
    q: &[f64],
    p: &mut [f64],
) -> Result<(), Error> {
    rattle.project_at(t, q, p).map(|_| ()).map_err(|f| {
        Error::Step(StepFailure {
            step: 0,
            t,
            cause: StepError::MomentumProjectionFailed {
                iterations: f.iterations,
                residual: f.residual,
            },
        })
    })
}

impl Initial {
    /// Moves initial data onto the constraint manifold, explicitly: `q₀` by
    /// [`project_position_in_metric`] in the mass metric `∂²L/∂v²` at the given data (at `v = 0`
    /// for given momenta), then the momenta by the RATTLE projection at `q₀` ([`project_momentum`]); given velocities
    /// are mapped to momenta by `FL`, projected, and mapped back (the impulsive-constraint
    /// projection, orthogonal in the kinetic-energy metric).
    pub fn project_onto<L: Lagrangian, C: Constraint>(
        self,
        lagrangian: &L,
        constraint: &C,
        t: f64,
    ) -> Result<Initial, Error> {
        let n = lagrangian.dof();
        match self {
            Initial::Velocity { q, v } => {
                Error::check_len("q0", &q, n)?;
                Error::check_len("v0", &v, n)?;
                let mass = mechanics::LagrangianJet::at(lagrangian, t, &q, &v).d2l_dv2;
                let q = project_position_in_metric(constraint, &q, &mass)?.q;
                let mut p = vec![0.0; n];
                mechanics::momentum(lagrangian, t, &q, &v, &mut p);
                let mut rattle = Rattle::new(lagrangian, constraint);
                project_with(&mut rattle, t, &q, &mut p)?;
                let v = if constraint.count() > 0 {
                    rattle.velocity().to_vec()
                } else {
                    v
                };
                Ok(Initial::Velocity { q, v })
            }
            Initial::Momentum { q, mut p } => {
                Error::check_len("q0", &q, n)?;
                Error::check_len("p0", &p, n)?;
                let rest = vec![0.0; n];
                let mass = mechanics::LagrangianJet::at(lagrangian, t, &q, &rest).d2l_dv2;
                let q = project_position_in_metric(constraint, &q, &mass)?.q;
                project_momentum(lagrangian, constraint, t, &q, &mut p)?;
                Ok(Initial::Momentum { q, p })
            }
        }
    }
}
