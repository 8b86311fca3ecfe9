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
//! exactly (`ν = (Dφ M⁻¹ Dφᵀ)⁻¹ Dφ M⁻¹ p̃`) and a residual-only evaluation confirms it.
//!
//! When the Lagrangian declares itself separable ([`crate::mechanics::Structure::Separable`], a constant
//! mass matrix `M`), the projection takes that closed form directly, with no derivatives of `L`
//! at all: `w = M⁻¹p̃`, `uᶜ = M⁻¹Dφᶜᵀ`, `S = Dφ U` (d × d), `S ν = Dφ w`, `v = w − U ν`
//! ([HLW06] §VII.1.4). [`Rattle::with_closed_form`] switches it off (the Newton form is the
//! reference; a test checks both agree to round-off).
//!
//! [HLW06]: crate#references
//! [LMO08]: crate#references

use crate::numerics::ad::{self, HessianParts, MultiFunction};
use num_dual::{HyperDual64, HyperDualSVec64};

use crate::mechanics::constraint_jacobian;
use crate::mechanics::structure::InverseMass;
use crate::mechanics::{Constraint, Lagrangian};
use crate::numerics::dense::{max_norm, solve_in_place};
use crate::numerics::dual::SmallDual;
use crate::numerics::newton::{Convergence, NewtonOptions, NewtonReport};
use crate::numerics::scratch::{Buffer, NODE};
use crate::scalar::Scalar;

/// What an [`crate::integrator::Integrator`] applies to the momenta after each solved step.
///
/// The default [`NoProjection`] leaves them alone (plain SHAKE); [`Rattle`] projects them onto
/// the cotangent bundle of the constraint manifold.
pub trait MomentumProjection {
    /// `false` for the no-op projection, so the integrator can skip it.
    fn is_active(&self) -> bool {
        true
    }
    /// Replaces `p` at `(t, q)` by its projection, given `dphi = Dφ(q)` (row-major d × n, as the
    /// integrator computes it once per configuration); on failure `p` is left unchanged.
    fn project(
        &mut self,
        t: f64,
        q: &[f64],
        dphi: &[f64],
        p: &mut [f64],
    ) -> Result<ProjectionReport, ProjectionFailure>;
    /// The multipliers `ν` of the last successful projection (`p ← p − Dφ(q)ᵀν`, length d).
    fn multipliers(&self) -> &[f64];
    /// What the projection carries from one step to the next (its starting guess and last
    /// multipliers), for a checkpoint of the integrator
    /// ([`crate::integrator::IntegratorCheckpoint`]). Default: nothing.
    fn carried(&self) -> ProjectionCarry {
        ProjectionCarry::default()
    }
    /// Takes back what [`MomentumProjection::carried`] gave. Default: nothing to take.
    fn restore_carried(&mut self, _carry: &ProjectionCarry) {}
}

/// What a projection carries from one step to the next, as plain numbers.
#[derive(Debug, Clone, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ProjectionCarry {
    /// The velocities `v = FH(q, p)` of the last projection: the next one's starting guess.
    pub velocity: Vec<f64>,
    /// The multipliers `ν` of the last projection.
    pub multipliers: Vec<f64>,
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

/// No projection (the default of [`crate::integrator::Integrator`]): SHAKE momenta are reported as they are.
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
        _dphi: &[f64],
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
    /// Newton updates (KKT solves) over all projections.
    pub newton_iterations: usize,
    /// Full evaluations: residual and KKT matrix (one hyper-dual evaluation of `L` each).
    pub kkt_evaluations: usize,
    /// Residual-only evaluations after an update (one first-order dual evaluation of `L` each).
    pub residual_evaluations: usize,
    /// Projections by the closed form of a constant mass matrix (no evaluation of `L`).
    pub closed_form: usize,
}

/// The RATTLE projection for the Lagrangian `L` and the constraints `C` (see the module docs).
///
/// Newton's method on `(v, ν)`: a full evaluation gives the residual and the KKT matrix; after
/// each update the residual alone is re-evaluated (gradient only, cheaper), so a Lagrangian
/// quadratic in `v` costs one full and one residual evaluation per projection. It stops when
/// `‖R‖∞ ≤ tol_R · max(1, ‖p‖∞)` or when the update is at round-off, like [`crate::numerics::newton`].
///
/// ```
/// use marsden::holonomic::Rattle;
/// use marsden::systems::SphericalPendulum;
///
/// let pendulum = SphericalPendulum::default(); // |q| = 1, unit mass
/// let mut rattle = Rattle::new(pendulum, pendulum);
/// let q = [0.0, 0.0, -1.0];
/// let mut p = [0.3, 0.0, 0.5]; // the radial part 0.5 must go
/// rattle.project_at(0.0, &q, &mut p).unwrap();
/// assert!(p[2].abs() < 1e-15 && (p[0] - 0.3).abs() < 1e-15);
/// ```
#[derive(Debug, Clone)]
pub struct Rattle<L, C> {
    lagrangian: L,
    constraint: C,
    options: NewtonOptions,
    ws: Workspace,
    statistics: ProjectionStatistics,
    /// `M⁻¹` of a separable Lagrangian: the projection's closed form.
    closed_form: Option<InverseMass>,
}

#[derive(Debug, Clone, Default)]
struct Workspace {
    parts: HessianParts,

    phi: Vec<f64>,
    /// `Dφ(q)` when [`Rattle::project_at`] computes it.
    g: Vec<f64>,
    /// Newton unknowns `(v, ν)`, residual, KKT matrix (row-major), update.
    z: Vec<f64>,
    r: Vec<f64>,
    kkt: Vec<f64>,
    dz: Vec<f64>,
    /// `∂L/∂v` from a residual-only evaluation.
    grad: Vec<f64>,
    /// `ν` of the last successful projection.
    nu: Vec<f64>,
    /// `v = FH(q, p)` of the last successful projection (and the next starting guess).
    v: Vec<f64>,
    /// Closed form: `U = M⁻¹Dφᵀ` (d columns of length n, stored by column) and the solve's
    /// scratch.
    u: Vec<f64>,
    scratch: Vec<f64>,
}

impl<L: Lagrangian, C: Constraint> Rattle<L, C> {
    /// The projection for `L` and `φ`, with default Newton options.
    pub fn new(lagrangian: L, constraint: C) -> Self {
        let closed_form = InverseMass::of(&lagrangian.structure());
        Self {
            lagrangian,
            constraint,
            options: NewtonOptions::default(),
            ws: Workspace::default(),
            statistics: ProjectionStatistics::default(),
            closed_form,
        }
    }

    /// Whether to use the closed form of a separable Lagrangian (default: whenever it declares
    /// a constant, invertible mass matrix); `false` forces the Newton form, the reference.
    pub fn with_closed_form(mut self, enabled: bool) -> Self {
        self.closed_form = if enabled {
            InverseMass::of(&self.lagrangian.structure())
        } else {
            None
        };
        self
    }

    /// Sets the Newton options (the residual tolerance is relative to `max(1, ‖p‖∞)`).
    pub fn with_options(mut self, options: NewtonOptions) -> Self {
        self.options = options;
        self
    }

    /// Projects `p` at `(t, q)`, computing `Dφ(q)` itself (for use outside an integrator).
    pub fn project_at(
        &mut self,
        t: f64,
        q: &[f64],
        p: &mut [f64],
    ) -> Result<ProjectionReport, ProjectionFailure> {
        let d = self.constraint.count();
        let mut g = std::mem::take(&mut self.ws.g);
        g.resize(d * q.len(), 0.0);
        self.ws.phi.resize(d, 0.0);
        if d > 0 {
            constraint_jacobian(&self.constraint, q, &mut self.ws.phi, &mut g);
        }
        let result = self.project(t, q, &g, p);
        self.ws.g = g;
        result
    }

    /// The Lagrangian whose Legendre transform the projection inverts.
    pub fn lagrangian(&self) -> &L {
        &self.lagrangian
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

    /// Sizes the buffers; starts from the last velocity (if any) and `ν = 0`.
    fn start(&mut self, n: usize, d: usize) {
        let ws = &mut self.ws;
        let m = n + d;
        ws.z.clear();
        if ws.v.len() == n {
            ws.z.extend_from_slice(&ws.v);
        } else {
            ws.z.resize(n, 0.0);
        }
        ws.z.resize(m, 0.0);
        ws.r.resize(m, 0.0);
        ws.kkt.resize(m * m, 0.0);
        ws.dz.resize(m, 0.0);
        ws.grad.resize(n, 0.0);
    }

    /// Newton's method on `(v, ν)`; see the type's docs.
    fn solve(
        &mut self,
        t: f64,
        q: &[f64],
        g: &[f64],
        p: &[f64],
    ) -> Result<ProjectionReport, ProjectionFailure> {
        let (n, m) = (q.len(), self.ws.z.len());
        let scale = max_norm(p).max(1.0);
        let mut convergence = Convergence::new(&self.options);
        let velocity_lagrangian = InVelocity {
            lagrangian: &self.lagrangian,
            t,
            q,
        };
        let ws = &mut self.ws;
        let stats = &mut self.statistics;
        let mut iterations = 0;
        loop {
            full_evaluation(&velocity_lagrangian, g, p, ws);
            stats.kkt_evaluations += 1;
            let residual = max_norm(&ws.r);
            let failure = ProjectionFailure {
                iterations,
                residual,
            };
            let report = NewtonReport {
                iterations,
                residual,
                ..NewtonReport::default()
            };
            if convergence.check(&report, scale).map_err(|_| failure)? {
                return Ok(ProjectionReport {
                    iterations,
                    residual,
                });
            }

            ws.dz.iter_mut().zip(&ws.r).for_each(|(d, r)| *d = -r);
            // The KKT matrix is rebuilt by every full evaluation: solve it in place.
            solve_in_place(&mut ws.kkt, &mut ws.dz, m).map_err(|_| failure)?;
            ws.z.iter_mut().zip(&ws.dz).for_each(|(z, d)| *z += d);
            iterations += 1;
            stats.newton_iterations += 1;
            convergence.record_update(max_norm(&ws.dz), max_norm(&ws.z).max(1.0));
            residual_evaluation(&velocity_lagrangian, g, p, n, ws);
            stats.residual_evaluations += 1;
            let residual = max_norm(&ws.r);
            if residual.is_finite() && convergence.converged(residual, scale) {
                return Ok(ProjectionReport {
                    iterations,
                    residual,
                });
            }
        }
    }

    /// The closed form for a constant mass matrix (see the module docs): `(v, ν)` into `ws.z`;
    /// the residual reported is the hidden constraint `‖Dφ v‖∞`.
    fn solve_closed_form(
        &mut self,
        inverse_mass: &InverseMass,
        g: &[f64],
        p: &[f64],
    ) -> Result<ProjectionReport, ProjectionFailure> {
        let ws = &mut self.ws;
        let n = p.len();
        let d = ws.z.len() - n;
        let failure = ProjectionFailure {
            iterations: 0,
            residual: f64::NAN,
        };
        // U = M⁻¹Dφᵀ, column by column; w = M⁻¹p̃.
        ws.u.clear();
        ws.u.extend_from_slice(&g[..d * n]);
        for column in ws.u.chunks_exact_mut(n) {
            inverse_mass.apply(column, &mut ws.scratch);
        }
        let (v, nu) = ws.z.split_at_mut(n);
        v.copy_from_slice(p);
        inverse_mass.apply(v, &mut ws.scratch);
        // S ν = Dφ w, with S = Dφ U (row-major d × d, in the KKT buffer).
        let dot = |row: usize, x: &[f64]| -> f64 {
            g[row * n..(row + 1) * n]
                .iter()
                .zip(x)
                .map(|(a, b)| a * b)
                .sum()
        };
        let s = &mut ws.kkt[..d * d];
        for a in 0..d {
            nu[a] = dot(a, v);
            for c in 0..d {
                s[a * d + c] = dot(a, &ws.u[c * n..(c + 1) * n]);
            }
        }
        solve_in_place(s, nu, d).map_err(|_| failure)?;
        for (c, column) in ws.u.chunks_exact(n).enumerate() {
            v.iter_mut()
                .zip(column)
                .for_each(|(vi, ui)| *vi -= nu[c] * ui);
        }
        let residual = (0..d).fold(0.0_f64, |m, a| m.max(dot(a, v).abs()));
        self.statistics.closed_form += 1;
        if !residual.is_finite() {
            return Err(ProjectionFailure {
                iterations: 0,
                residual,
            });
        }
        Ok(ProjectionReport {
            iterations: 0,
            residual,
        })
    }

    /// `p ← p − Dφᵀν`, and keeps `ν` and `v`.
    fn accept(&mut self, n: usize, d: usize, g: &[f64], p: &mut [f64]) {
        let ws = &mut self.ws;
        let (v, nu) = ws.z.split_at(n);
        for (i, pi) in p.iter_mut().enumerate() {
            *pi -= (0..d).map(|c| g[c * n + i] * nu[c]).sum::<f64>();
        }
        ws.nu.clear();
        ws.nu.extend_from_slice(nu);
        ws.v.clear();
        ws.v.extend_from_slice(v);
        self.statistics.projections += 1;
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
        dphi: &[f64],
        p: &mut [f64],
    ) -> Result<ProjectionReport, ProjectionFailure> {
        let (n, d) = (q.len(), self.constraint.count());
        if d == 0 {
            return Ok(ProjectionReport::default());
        }
        if dphi.len() != d * n {
            return Err(ProjectionFailure {
                iterations: 0,
                residual: f64::NAN,
            });
        }
        self.start(n, d);
        let report = match self.closed_form.take() {
            Some(inverse_mass) => {
                let report = self.solve_closed_form(&inverse_mass, dphi, p);
                self.closed_form = Some(inverse_mass);
                report?
            }
            None => self.solve(t, q, dphi, p)?,
        };
        self.accept(n, d, dphi, p);
        Ok(report)
    }

    fn multipliers(&self) -> &[f64] {
        &self.ws.nu
    }

    fn carried(&self) -> ProjectionCarry {
        ProjectionCarry {
            velocity: self.ws.v.clone(),
            multipliers: self.ws.nu.clone(),
        }
    }

    fn restore_carried(&mut self, carry: &ProjectionCarry) {
        self.ws.v.clone_from(&carry.velocity);
        self.ws.nu.clone_from(&carry.multipliers);
    }
}

/// `v ↦ L(t, q, v)` at fixed `(t, q)`.
struct InVelocity<'a, L> {
    lagrangian: &'a L,
    t: f64,
    q: &'a [f64],
}

impl<L: Lagrangian> MultiFunction for InVelocity<'_, L> {
    const MAX_INPUTS: Option<usize> = crate::mechanics::lagrangian::times_dof(L::FIXED_DOF, 1, 0);
    fn inputs(&self) -> usize {
        self.q.len()
    }
    fn outputs(&self) -> usize {
        1
    }
    #[inline]
    fn eval<S: Scalar>(&self, v: &[S], out: &mut [S]) {
        let zero = S::from(0.0);
        let mut q = Buffer::<S, NODE>::empty();
        let q = q.from_fn(self.q.len(), zero, |i| S::from(self.q[i]));
        out[0] = self.lagrangian.lagrangian(S::from(self.t), q, v);
    }
}

/// `∂L/∂v` into `ws.grad` and `∂²L/∂v²` into `ws.parts.hess` at `v = ws.z[..n]`, by one
/// hyper-dual evaluation: statically sized for `n ≤ 4` (as [`crate::integrator::small::unconstrained`]), by the chunked
/// driver otherwise.
fn velocity_jet<L: Lagrangian>(f: &InVelocity<'_, L>, n: usize, ws: &mut Workspace) {
    match n {
        1 => small_velocity_jet::<1, HyperDual64, L>(f, ws),
        2 => small_velocity_jet::<2, HyperDualSVec64<2, 2>, L>(f, ws),
        3 => small_velocity_jet::<3, HyperDualSVec64<3, 3>, L>(f, ws),
        4 => small_velocity_jet::<4, HyperDualSVec64<4, 4>, L>(f, ws),
        _ => {
            ad::partial_hessian(f, &ws.z[..n], 0..n, 0..n, &mut ws.parts);
            ws.grad.copy_from_slice(&ws.parts.grad_rows);
        }
    }
}

fn small_velocity_jet<const N: usize, D: SmallDual<N>, L: Lagrangian>(
    f: &InVelocity<'_, L>,
    ws: &mut Workspace,
) {
    let v: [D; N] = std::array::from_fn(|i| D::seeded(ws.z[i], Some((i, 1.0)), Some(i)));
    let q: [D; N] = std::array::from_fn(|i| D::from(f.q[i]));
    let l = f.lagrangian.lagrangian(D::from(f.t), &q, &v);
    ws.parts.hess.resize(N * N, 0.0);
    for i in 0..N {
        ws.grad[i] = l.eps1(i);
        for j in 0..N {
            ws.parts.hess[i * N + j] = l.eps12(i, j);
        }
    }
}

/// Residual `R(v, ν) = (∂L/∂v − p + Dφᵀν, Dφ v)` and its KKT matrix
/// `[[∂²L/∂v², Dφᵀ], [Dφ, 0]]` at `ws.z`, by one hyper-dual evaluation.
fn full_evaluation<L: Lagrangian>(f: &InVelocity<'_, L>, g: &[f64], p: &[f64], ws: &mut Workspace) {
    let (n, m) = (p.len(), ws.z.len());
    let d = m - n;
    velocity_jet(f, n, ws);
    for i in 0..n {
        let row = &mut ws.kkt[i * m..(i + 1) * m];
        row[..n].copy_from_slice(&ws.parts.hess[i * n..(i + 1) * n]);
        for c in 0..d {
            row[n + c] = g[c * n + i];
        }
    }
    for c in 0..d {
        let row = &mut ws.kkt[(n + c) * m..(n + c + 1) * m];
        row[..n].copy_from_slice(&g[c * n..(c + 1) * n]);
        row[n..].fill(0.0);
    }
    assemble_residual(g, p, n, ws);
}

/// The residual alone at `ws.z`, by one first-order dual evaluation (`∂L/∂v` only).
fn residual_evaluation<L: Lagrangian>(
    f: &InVelocity<'_, L>,
    g: &[f64],
    p: &[f64],
    n: usize,
    ws: &mut Workspace,
) {
    if n <= 4 {
        // The static hyper-dual jet is cheaper than the chunked first-order driver here.
        velocity_jet(f, n, ws);
    } else {
        let mut value = [0.0];
        ad::jacobian(f, &ws.z[..n], 0..n, &mut value, &mut ws.grad);
    }
    assemble_residual(g, p, n, ws);
}

/// `R` from `∂L/∂v` in `ws.grad`.
fn assemble_residual(g: &[f64], p: &[f64], n: usize, ws: &mut Workspace) {
    let d = ws.z.len() - n;
    let (v, nu) = ws.z.split_at(n);
    for i in 0..n {
        let constraint_force: f64 = (0..d).map(|c| g[c * n + i] * nu[c]).sum();
        ws.r[i] = ws.grad[i] - p[i] + constraint_force;
    }
    for c in 0..d {
        ws.r[n + c] = g[c * n..(c + 1) * n]
            .iter()
            .zip(v)
            .map(|(a, b)| a * b)
            .sum();
    }
}
