//! The RATTLE momentum projection onto the cotangent bundle of the constraint manifold.
//!
//! After the SHAKE solve of a step the momenta `p̃ = D₂L_d + f_d⁺` satisfy the position
//! constraint only; the projection replaces them by `p = p̃ − Dφ(q)ᵀν` with `ν ∈ ℝ^d` chosen so
//! that the *hidden* velocity constraint `Dφ(q) · FH(t, q, p) = 0` holds ([HLW06] §VII.1,
//! [LMO08] §3; module docs of [`crate::holonomic`]). With `v = FH(t, q, p)` the unknowns
//! `(v, ν)` solve the saddle-point system
//!
//! ```text
//!     ∂L/∂v(t, q, v) + Dφ(q)ᵀν = p̃,        Dφ(q) v = 0,
//! ```
//!
//! by Newton's method with the KKT matrix `[[∂²L/∂v², Dφᵀ], [Dφ, 0]]`; for a Lagrangian
//! quadratic in `v` (constant or position-dependent mass matrix) one Newton update solves it
//! exactly (`ν = (Dφ M⁻¹ Dφᵀ)⁻¹ Dφ M⁻¹ p̃`) and a second evaluation confirms the residual.
//!
//! [HLW06]: Hairer, Lubich, Wanner, *Geometric Numerical Integration* (2006). [LMO08]:
//! Leyendecker, Marsden, Ortiz, ZAMM 88 (2008).

use smallvec::SmallVec;

use crate::ad::{self, HessianParts, MultiFunction};
use crate::linalg::max_norm;
use crate::newton::{self, NewtonFailure, NewtonOptions, NewtonWorkspace, NonlinearSystem};
use crate::step::constraint_jacobian;
use crate::{Constraint, Lagrangian, Scalar};

/// What an [`crate::Integrator`] applies to the momenta after each solved step.
///
/// The default [`NoProjection`] leaves them alone (plain SHAKE); [`Rattle`] projects them onto
/// the cotangent bundle of the constraint manifold.
pub trait MomentumProjection {
    /// `false` for the no-op projection, so the integrator can skip it.
    fn is_active(&self) -> bool {
        true
    }
    /// Replaces `p` at `(t, q)` by its projection; on failure `p` is left unchanged.
    fn project(
        &mut self,
        t: f64,
        q: &[f64],
        p: &mut [f64],
    ) -> Result<ProjectionReport, ProjectionFailure>;
    /// The multipliers `ν` of the last successful projection (`p ← p − Dφ(q)ᵀν`, length d).
    fn multipliers(&self) -> &[f64];
}

/// How a projection went.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ProjectionReport {
    /// Newton updates applied.
    pub iterations: usize,
    /// Final residual of the projection equations (max-norm).
    pub residual: f64,
}

/// Why a projection failed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProjectionFailure {
    /// Newton updates applied before the failure.
    pub iterations: usize,
    /// Residual (max-norm) at the last iterate.
    pub residual: f64,
}

/// No projection (the default of [`crate::Integrator`]): SHAKE momenta are reported as they are.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct NoProjection;

impl MomentumProjection for NoProjection {
    fn is_active(&self) -> bool {
        false
    }
    fn project(
        &mut self,
        _t: f64,
        _q: &[f64],
        _p: &mut [f64],
    ) -> Result<ProjectionReport, ProjectionFailure> {
        Ok(ProjectionReport::default())
    }
    fn multipliers(&self) -> &[f64] {
        &[]
    }
}

/// Work counters of a [`Rattle`] projection.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ProjectionStatistics {
    /// Successful projections.
    pub projections: usize,
    /// Newton updates over all projections.
    pub newton_iterations: usize,
    /// Evaluations of the KKT system (one hyper-dual evaluation of `L` each).
    pub evaluations: usize,
}

/// The RATTLE projection for the Lagrangian `L` and the constraints `C` (see the module docs).
///
/// ```
/// use marsden::holonomic::{MomentumProjection, Rattle};
/// use marsden::systems::SphericalPendulum;
///
/// let pendulum = SphericalPendulum::default(); // |q| = 1, unit mass
/// let mut rattle = Rattle::new(pendulum, pendulum);
/// let q = [0.0, 0.0, -1.0];
/// let mut p = [0.3, 0.0, 0.5]; // the radial part 0.5 must go
/// rattle.project(0.0, &q, &mut p).unwrap();
/// assert!(p[2].abs() < 1e-15 && (p[0] - 0.3).abs() < 1e-15);
/// ```
#[derive(Debug, Clone)]
pub struct Rattle<L, C> {
    lagrangian: L,
    constraint: C,
    options: NewtonOptions,
    ws: Workspace,
    statistics: ProjectionStatistics,
}

#[derive(Debug, Clone, Default)]
struct Workspace {
    newton: NewtonWorkspace,
    parts: HessianParts,
    phi: Vec<f64>,
    /// `Dφ(q)`, row-major d × n.
    g: Vec<f64>,
    /// Newton unknowns `(v, ν)`.
    z: Vec<f64>,
    /// `ν` of the last successful projection.
    nu: Vec<f64>,
    /// `v = FH(q, p)` of the last successful projection (and the next starting guess).
    v: Vec<f64>,
}

impl<L: Lagrangian, C: Constraint> Rattle<L, C> {
    /// The projection for `L` and `φ`, with default Newton options.
    pub fn new(lagrangian: L, constraint: C) -> Self {
        Self {
            lagrangian,
            constraint,
            options: NewtonOptions::default(),
            ws: Workspace::default(),
            statistics: ProjectionStatistics::default(),
        }
    }

    /// Sets the Newton options (the residual tolerance is relative to `max(1, ‖p‖∞)`).
    pub fn with_options(mut self, options: NewtonOptions) -> Self {
        self.options = options;
        self
    }

    /// The velocities `v = FH(t, q, p)` of the last successful projection; they satisfy
    /// `Dφ(q) v = 0` to the solver tolerance.
    pub fn velocity(&self) -> &[f64] {
        &self.ws.v
    }

    /// Work counters so far.
    pub fn statistics(&self) -> &ProjectionStatistics {
        &self.statistics
    }

    fn start(&mut self, n: usize, d: usize) {
        let ws = &mut self.ws;
        ws.phi.resize(d, 0.0);
        ws.g.resize(d * n, 0.0);
        ws.z.clear();
        if ws.v.len() == n {
            ws.z.extend_from_slice(&ws.v);
        } else {
            ws.z.resize(n, 0.0);
        }
        ws.z.resize(n + d, 0.0);
    }

    /// `p ← p − Dφᵀν`, and keeps `ν` and `v`.
    fn accept(&mut self, n: usize, d: usize, p: &mut [f64]) {
        let ws = &mut self.ws;
        let (v, nu) = ws.z.split_at(n);
        for (i, pi) in p.iter_mut().enumerate() {
            *pi -= (0..d).map(|c| ws.g[c * n + i] * nu[c]).sum::<f64>();
        }
        ws.nu.clear();
        ws.nu.extend_from_slice(nu);
        ws.v.clear();
        ws.v.extend_from_slice(v);
    }
}

impl<L: Lagrangian, C: Constraint> MomentumProjection for Rattle<L, C> {
    fn is_active(&self) -> bool {
        self.constraint.count() > 0
    }

    fn project(
        &mut self,
        t: f64,
        q: &[f64],
        p: &mut [f64],
    ) -> Result<ProjectionReport, ProjectionFailure> {
        let (n, d) = (q.len(), self.constraint.count());
        if d == 0 {
            return Ok(ProjectionReport::default());
        }
        self.start(n, d);
        let ws = &mut self.ws;
        constraint_jacobian(&self.constraint, q, &mut ws.phi, &mut ws.g);
        let mut system = KktSystem {
            velocity_lagrangian: InVelocity {
                lagrangian: &self.lagrangian,
                t,
                q,
            },
            p,
            g: &ws.g,
            d,
            parts: &mut ws.parts,
        };
        let result = newton::solve(&mut system, &mut ws.z, &self.options, &mut ws.newton);
        let stats = &mut self.statistics;
        match result {
            Ok(report) => {
                stats.projections += 1;
                stats.newton_iterations += report.iterations;
                stats.evaluations += report.evaluations;
                self.accept(n, d, p);
                Ok(ProjectionReport {
                    iterations: report.iterations,
                    residual: report.residual,
                })
            }
            Err(NewtonFailure::NotConverged(r) | NewtonFailure::NonFinite(r)) => {
                Err(ProjectionFailure {
                    iterations: r.iterations,
                    residual: r.residual,
                })
            }
            Err(NewtonFailure::Singular { iteration, .. }) => Err(ProjectionFailure {
                iterations: iteration,
                residual: max_norm(ws.newton.residual()),
            }),
        }
    }

    fn multipliers(&self) -> &[f64] {
        &self.ws.nu
    }
}

/// `v ↦ L(t, q, v)` at fixed `(t, q)`.
struct InVelocity<'a, L> {
    lagrangian: &'a L,
    t: f64,
    q: &'a [f64],
}

impl<L: Lagrangian> MultiFunction for InVelocity<'_, L> {
    fn inputs(&self) -> usize {
        self.q.len()
    }
    fn outputs(&self) -> usize {
        1
    }
    #[inline]
    fn eval<S: Scalar>(&self, v: &[S], out: &mut [S]) {
        let q: SmallVec<[S; 16]> = self.q.iter().map(|&x| S::from(x)).collect();
        out[0] = self.lagrangian.lagrangian(S::from(self.t), &q, v);
    }
}

/// `R(v, ν) = (∂L/∂v − p + Dφᵀν, Dφ v)` with its KKT Jacobian.
struct KktSystem<'a, L> {
    velocity_lagrangian: InVelocity<'a, L>,
    p: &'a [f64],
    g: &'a [f64],
    d: usize,
    parts: &'a mut HessianParts,
}

impl<L: Lagrangian> NonlinearSystem for KktSystem<'_, L> {
    fn dim(&self) -> usize {
        self.p.len() + self.d
    }

    fn residual_scale(&self) -> f64 {
        max_norm(self.p)
    }

    fn evaluate(&mut self, z: &[f64], r: &mut [f64], jac: &mut [f64]) {
        let (n, d) = (self.p.len(), self.d);
        let m = n + d;
        let (v, nu) = z.split_at(n);
        ad::partial_hessian(&self.velocity_lagrangian, v, 0..n, 0..n, self.parts);
        let (g, parts) = (self.g, &*self.parts);
        for i in 0..n {
            let row = &mut jac[i * m..(i + 1) * m];
            row[..n].copy_from_slice(&parts.hess[i * n..(i + 1) * n]);
            let mut ri = parts.grad_rows[i] - self.p[i];
            for c in 0..d {
                row[n + c] = g[c * n + i];
                ri += g[c * n + i] * nu[c];
            }
            r[i] = ri;
        }
        for c in 0..d {
            let gc = &g[c * n..(c + 1) * n];
            let row = &mut jac[(n + c) * m..(n + c + 1) * m];
            row[..n].copy_from_slice(gc);
            row[n..].fill(0.0);
            r[n + c] = gc.iter().zip(v).map(|(a, b)| a * b).sum();
        }
    }
}
