//! An accurate integrator of the (forced) Euler–Lagrange equations and of the action along
//! the solution: Gragg–Bulirsch–Stoer extrapolation.
//!
//! The first-order system `q̇ = v`, `v̇ = a(t, q, v)`, `Ṡ = L(t, q, v)` with the accelerations of
//! the forced Euler–Lagrange equations `∂²L/∂v² a = ∂L/∂q + f − ∂²L/∂v∂q v − ∂²L/∂v∂t`
//! ([`crate::mechanics::jet`]) is advanced over a substep `H` by Gragg's modified midpoint rule with
//! `n_j = 2, 4, 6, …` steps and Aitken–Neville extrapolation in `(H/n_j)²` (Hairer, Nørsett,
//! Wanner, *Solving ODEs I*, §II.9). Row `j` of the tableau has order `2j`; a substep is accepted
//! when two successive diagonal entries agree to `tolerance · max(1, |y|)` and is otherwise
//! halved, so the result is converged to about round-off on any smooth motion. Few rows
//! (order 8) and more substeps keep the extrapolation's amplification of round-off small. This is a
//! reference integrator (for the exact discrete Lagrangian, and as the reference of order
//! studies), not a structure-preserving one.

use crate::error::{InputError, SetupError};
use std::sync::atomic::{AtomicU64, Ordering};

use crate::error::Error;
use crate::mechanics::LagrangianJet;
use crate::mechanics::structure::InverseMass;
use crate::mechanics::{Force, Lagrangian, NoForce};
use crate::numerics::dense::{Lu, max_norm};

/// Options of the extrapolation integrator.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlowOptions {
    /// Acceptance tolerance of a substep, relative to `max(1, |y|)` (default and smallest
    /// accepted: 1e-15, near round-off).
    pub tolerance: f64,
    /// Substeps a call starts with (default 1; more are made by halving when needed).
    pub substeps: usize,
    /// Most rows of the extrapolation tableau (default 4: order 8, then halving). More rows
    /// take longer substeps but amplify round-off: on the oscillator over h = 0.5 the action
    /// is off by ~2e-16 with 4 rows and by up to 5e-15 with 8–12.
    pub max_rows: usize,
    /// Most successive halvings of a substep before giving up (default 30).
    pub max_halvings: usize,
}

impl Default for FlowOptions {
    fn default() -> Self {
        Self {
            tolerance: 1e-15,
            substeps: 1,
            max_rows: 4,
            max_halvings: 30,
        }
    }
}

impl FlowOptions {
    /// Checks the options' ranges.
    pub fn validate(&self) -> Result<(), Error> {
        let invalid = |name, value: f64, reason| {
            Error::Input(InputError::InvalidOption {
                name,
                value,
                reason,
            })
        };
        if !(self.tolerance >= 1e-15 && self.tolerance < 1.0) {
            return Err(invalid(
                "flow tolerance",
                self.tolerance,
                "must be in [1e-15, 1)",
            ));
        }
        if self.substeps == 0 {
            return Err(invalid("flow substeps", 0.0, "must be at least 1"));
        }
        if !(3..=20).contains(&self.max_rows) {
            return Err(invalid(
                "flow max_rows",
                self.max_rows as f64,
                "must be in 3..=20",
            ));
        }
        Ok(())
    }
}

/// The Euler–Lagrange flow of `L` with an optional force `f_L`, with the action integral.
#[derive(Debug)]
pub struct EulerLagrangeFlow<L, F = NoForce> {
    lagrangian: L,
    force: F,
    options: FlowOptions,
    /// `M⁻¹` of a separable `L`: accelerations `M⁻¹(∂L/∂q + f)` without second derivatives.
    inverse_mass: Option<InverseMass>,
    /// Bits of the last accepted substep length (a warm start for the controller).
    last_substep: AtomicU64,
}

impl<L: Clone, F: Clone> Clone for EulerLagrangeFlow<L, F> {
    fn clone(&self) -> Self {
        Self {
            lagrangian: self.lagrangian.clone(),
            force: self.force.clone(),
            options: self.options,
            inverse_mass: self.inverse_mass.clone(),
            last_substep: AtomicU64::new(self.last_substep.load(Ordering::Relaxed)),
        }
    }
}

/// The end of a flow: positions, velocities and the action `∫ L dt` along the way.
#[derive(Debug, Clone, PartialEq)]
pub struct FlowEnd {
    /// `q(t₀ + h)`.
    pub q: Vec<f64>,
    /// `v(t₀ + h)`.
    pub v: Vec<f64>,
    /// `∫_{t₀}^{t₀+h} L dt`.
    pub action: f64,
}

impl<L: Lagrangian> EulerLagrangeFlow<L> {
    /// The unforced flow of `lagrangian` with default options.
    pub fn new(lagrangian: L) -> Self {
        let inverse_mass = InverseMass::of(&lagrangian.structure());
        Self {
            lagrangian,
            force: NoForce,
            options: FlowOptions::default(),
            inverse_mass,
            last_substep: AtomicU64::new(0),
        }
    }
}

impl<L: Lagrangian, F: Force> EulerLagrangeFlow<L, F> {
    /// Adds an external force `f_L(t, q, v)` (Lagrange–d'Alembert).
    pub fn with_force<F2: Force>(self, force: F2) -> EulerLagrangeFlow<L, F2> {
        EulerLagrangeFlow {
            lagrangian: self.lagrangian,
            force,
            options: self.options,
            inverse_mass: self.inverse_mass,
            last_substep: self.last_substep,
        }
    }

    /// Sets the options (validated).
    pub fn with_options(mut self, options: FlowOptions) -> Result<Self, Error> {
        options.validate()?;
        self.options = options;
        Ok(self)
    }

    /// The Lagrangian.
    pub fn lagrangian(&self) -> &L {
        &self.lagrangian
    }

    /// The options.
    pub fn options(&self) -> &FlowOptions {
        &self.options
    }

    /// Flows `(q₀, v₀)` from `t₀` over `h` (either sign).
    ///
    /// Substeps are chosen by a simple controller: start from the last accepted substep, halve
    /// on rejection, double after a substep accepted before the last row.
    ///
    /// # Errors
    /// [`crate::error::SetupError::SingularLagrangian`] where `∂²L/∂v²` is singular,
    /// [`crate::error::SetupError::FlowDidNotConverge`] if a substep cannot be accepted after
    /// `max_halvings` successive halvings.
    pub fn advance(&self, t0: f64, h: f64, q0: &[f64], v0: &[f64]) -> Result<FlowEnd, Error> {
        let n = q0.len();
        let mut y: Vec<f64> = q0.iter().chain(v0).copied().chain([0.0]).collect();
        let mut tableau = Tableau::new(self.options.max_rows);
        let pieces = self.options.substeps;
        let big = h / pieces as f64;
        for k in 0..pieces {
            self.advance_controlled(t0 + k as f64 * big, big, &mut y, &mut tableau)?;
        }
        Ok(FlowEnd {
            q: y[..n].to_vec(),
            v: y[n..2 * n].to_vec(),
            action: y[2 * n],
        })
    }

    fn advance_controlled(
        &self,
        t0: f64,
        h: f64,
        y: &mut [f64],
        tableau: &mut Tableau,
    ) -> Result<(), Error> {
        let last = f64::from_bits(self.last_substep.load(Ordering::Relaxed));
        let mut piece = if last > 0.0 && last < h.abs() {
            last.copysign(h)
        } else {
            h
        };
        let (mut done, mut rejections) = (0.0, 0);
        while done != h {
            let remaining = h - done;
            let step = if piece.abs() >= remaining.abs() {
                remaining
            } else {
                piece
            };
            // A substep too long for the equations (the modified midpoint's intermediate
            // states run off to where `L` is singular or not finite) is rejected and halved
            // like an inaccurate one; only the smallest substeps' failures are the flow's.
            let (estimate, row) = match self.extrapolate(t0 + done, step, y, tableau) {
                Ok(found) => found,
                Err(e)
                    if rejections >= self.options.max_halvings
                        || negligible(step, t0 + done, h) =>
                {
                    return Err(e);
                }
                Err(_) => (f64::INFINITY, 0),
            };
            let end = &tableau.end;
            // Relative to the substep's start, not its end: an end that ran away (a diverging
            // extrapolation) would otherwise make its own tolerance large enough to pass.
            if estimate <= self.options.tolerance * max_norm(y).max(1.0) {
                y.copy_from_slice(end);
                done = if step == remaining { h } else { done + step };
                self.last_substep
                    .store(step.abs().to_bits(), Ordering::Relaxed);
                piece = if row + 1 < self.options.max_rows {
                    2.0 * step
                } else {
                    step
                };
                rejections = 0;
            } else {
                rejections += 1;
                // A rejected substep too small to advance the time: the solution runs into a
                // singularity, and the accepted substeps would shrink towards it forever.
                if rejections > self.options.max_halvings || negligible(step, t0 + done, h) {
                    return Err(Error::Setup(SetupError::FlowDidNotConverge {
                        t: t0 + done,
                        substep: step,
                        estimate,
                        tolerance: self.options.tolerance,
                    }));
                }
                piece = 0.5 * step;
            }
        }
        Ok(())
    }

    /// Extrapolated modified-midpoint value over `[t, t + h]` from `y`, written into
    /// `tableau.end`, with the error estimate `|T_jj − T_{j,j−1}|` and the index of the row where
    /// it was accepted (or of the last row, with `max_rows`).
    fn extrapolate(
        &self,
        t: f64,
        h: f64,
        y: &[f64],
        tableau: &mut Tableau,
    ) -> Result<(f64, usize), Error> {
        let Tableau {
            f0,
            previous,
            row,
            midpoint,
            end,
        } = tableau;
        f0.resize(y.len(), 0.0);
        self.rhs(t, y, f0)?;
        let mut estimate = f64::INFINITY;
        let rows = self.options.max_rows;
        for j in 0..rows {
            let substep = Substep { t, h, y, f0 };
            self.modified_midpoint(substep, 2 * (j + 1), &mut row[0], midpoint)?;
            // Neville: T_{j,k} = T_{j,k−1} + (T_{j,k−1} − T_{j−1,k−1}) / ((n_j/n_{j−k})² − 1).
            for k in 1..=j {
                let ratio = (j + 1) as f64 / (j + 1 - k) as f64;
                let factor = 1.0 / (ratio * ratio - 1.0);
                let (done, rest) = row.split_at_mut(k);
                let (newer, older) = (&done[k - 1], &previous[k - 1]);
                let entry = newer.iter().zip(older).map(|(a, b)| a + (a - b) * factor);
                rest[0].clear();
                rest[0].extend(entry);
            }
            if j >= 2 {
                estimate = max_diff(&row[j], &row[j - 1]);
                if estimate <= self.options.tolerance * max_norm(y).max(1.0) {
                    end.clone_from(&row[j]);
                    return Ok((estimate, j));
                }
            }
            std::mem::swap(previous, row);
        }
        match previous.get(rows.wrapping_sub(1)) {
            Some(last) => end.clone_from(last),
            None => {
                end.clear();
                end.extend_from_slice(y);
            }
        }
        Ok((estimate, rows))
    }

    /// Gragg's modified midpoint rule with `steps` (even) steps over the substep `substep` (from
    /// `y`, where the vector field is `f0`, over `[t, t + h]`), with the final smoothing step,
    /// written into `out`; `scratch` holds the last two states and the vector field.
    fn modified_midpoint(
        &self,
        substep: Substep<'_>,
        steps: usize,
        out: &mut Vec<f64>,
        [prev, cur, f]: &mut [Vec<f64>; 3],
    ) -> Result<(), Error> {
        let Substep { t, h, y, f0 } = substep;
        let eta = h / steps as f64;
        prev.clear();
        prev.extend_from_slice(y);
        cur.clear();
        cur.extend(y.iter().zip(f0).map(|(a, f)| a + eta * f));
        f.clear();
        f.resize(y.len(), 0.0);
        for m in 1..steps {
            self.rhs(t + m as f64 * eta, cur, f)?;
            for i in 0..y.len() {
                let next = prev[i] + 2.0 * eta * f[i];
                prev[i] = cur[i];
                cur[i] = next;
            }
        }
        self.rhs(t + h, cur, f)?;
        out.clear();
        out.extend((0..y.len()).map(|i| 0.5 * (cur[i] + prev[i] + eta * f[i])));
        Ok(())
    }

    /// `(v, a, L)` at `(t, q, v)`.
    fn rhs(&self, t: f64, y: &[f64], out: &mut [f64]) -> Result<(), Error> {
        let n = (y.len() - 1) / 2;
        let (q, v) = (&y[..n], &y[n..2 * n]);
        if let Some(inverse_mass) = &self.inverse_mass {
            return self.rhs_separable(inverse_mass, t, q, v, out);
        }
        let jet = LagrangianJet::at(&self.lagrangian, t, q, v);
        let mut force = vec![0.0; n];
        if self.force.is_active() {
            self.force.force(t, q, v, &mut force);
        }
        let mut lu = Lu::new();
        lu.factor(&jet.d2l_dv2, n).map_err(|e| {
            Error::Setup(SetupError::SingularLagrangian {
                t,
                q: q.to_vec(),
                v: v.to_vec(),
                pivot: e.pivot,
                scale: max_norm(&jet.d2l_dv2),
            })
        })?;
        let a = &mut out[n..2 * n];
        for i in 0..n {
            let coupling: f64 = (0..n).map(|j| jet.d2l_dvdq[i * n + j] * v[j]).sum();
            a[i] = jet.dl_dq[i] + force[i] - coupling - jet.d2l_dvdt[i];
        }
        lu.solve(a, &mut Vec::with_capacity(n));
        out[..n].copy_from_slice(v);
        out[2 * n] = jet.value;
        Ok(())
    }
}

/// The substep of [`EulerLagrangeFlow::modified_midpoint`]: `[t, t + h]` from `y`.
#[derive(Clone, Copy)]
struct Substep<'a> {
    /// The substep's start time.
    t: f64,
    /// The substep's length.
    h: f64,
    /// The state at `t`.
    y: &'a [f64],
    /// The vector field at `y`.
    f0: &'a [f64],
}

impl<L: Lagrangian, F: Force> EulerLagrangeFlow<L, F> {
    /// `(v, M⁻¹(∂L/∂q + f), L)` for `L = ½vᵀMv − V(t, q)`.
    fn rhs_separable(
        &self,
        inverse_mass: &InverseMass,
        t: f64,
        q: &[f64],
        v: &[f64],
        out: &mut [f64],
    ) -> Result<(), Error> {
        let n = q.len();
        let (head, tail) = out.split_at_mut(n);
        head.copy_from_slice(v);
        let a = &mut tail[..n];
        crate::mechanics::dl_dq(&self.lagrangian, t, q, v, a);
        if self.force.is_active() {
            let mut force = vec![0.0; n];
            self.force.force(t, q, v, &mut force);
            a.iter_mut().zip(&force).for_each(|(ai, f)| *ai += f);
        }
        match inverse_mass {
            InverseMass::Diagonal(d) => a.iter_mut().zip(d).for_each(|(ai, di)| *ai *= di),
            InverseMass::Dense(lu) => lu.solve(a, &mut Vec::with_capacity(n)),
        }
        tail[n] = self.lagrangian.lagrangian(t, q, v);
        Ok(())
    }
}

/// The extrapolation's storage, reused by every substep of one
/// [`EulerLagrangeFlow::advance`] (no allocation per row or per midpoint sequence).
#[derive(Debug)]
struct Tableau {
    /// The vector field at the substep's start.
    f0: Vec<f64>,
    /// Row `j − 1` of the tableau (its first `j` entries).
    previous: Vec<Vec<f64>>,
    /// Row `j` (its first `j + 1` entries).
    row: Vec<Vec<f64>>,
    /// The midpoint rule's last two states and vector field.
    midpoint: [Vec<f64>; 3],
    /// The extrapolated value.
    end: Vec<f64>,
}

impl Tableau {
    fn new(rows: usize) -> Self {
        Self {
            f0: Vec::new(),
            previous: vec![Vec::new(); rows],
            row: vec![Vec::new(); rows],
            midpoint: Default::default(),
            end: Vec::new(),
        }
    }
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, crate::numerics::dense::max_or_nan)
}

/// A substep too small to advance the time: `|step| ≤ 64 ε · max(|t|, |h|)`.
fn negligible(step: f64, t: f64, h: f64) -> bool {
    step.abs() <= 64.0 * f64::EPSILON * t.abs().max(h.abs())
}
