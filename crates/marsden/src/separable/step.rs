//! A separable step as the integrator sees it: what a rule offers ([`SeparableStep`]), the fixed
//! data of one step ([`Frame`]) and the buffers kept between steps ([`SeparableWorkspace`]).

use crate::mechanics::MassMatrix;
use crate::numerics::banded::{BandLu, Banded};
use crate::numerics::newton::{NewtonFailure, NewtonOptions, NewtonReport};

/// The fixed data of one step.
#[derive(Debug, Clone, Copy)]
pub struct Frame<'a> {
    /// Start time.
    pub t0: f64,
    /// Time step.
    pub h: f64,
    /// `q_k`.
    pub q0: &'a [f64],
    /// `p_k`.
    pub p0: &'a [f64],
}

/// A step that is a Newton solve for the offset alone, with a structured Jacobian
/// (object-safe: plain `f64` data).
pub trait SeparableStep {
    /// The constant mass matrix, if the Lagrangian is separable (called once per integrator).
    fn mass(&self) -> Option<MassMatrix>;

    /// Solves the step from the predicted offset `z` (overwritten with the solution) and writes
    /// `p_{k+1}`; `report.evaluations` counts potential gradients, `report.factorizations` the
    /// Jacobians assembled and factored.
    fn solve_separable(
        &self,
        frame: Frame<'_>,
        z: &mut [f64],
        p_next: &mut [f64],
        options: &NewtonOptions,
        ws: &mut SeparableWorkspace,
    ) -> Result<NewtonReport, NewtonFailure>;
}

/// The constant mass matrix, as the step applies it.
#[derive(Debug, Clone)]
pub(super) enum Mass {
    Diagonal(Vec<f64>),
    /// Row-major n × n.
    Dense(Vec<f64>),
}

impl Mass {
    /// `M_ij` of the `n × n` mass.
    pub(super) fn entry(&self, n: usize, i: usize, j: usize) -> f64 {
        match self {
            Mass::Diagonal(d) if i == j => d[i],
            Mass::Diagonal(_) => 0.0,
            Mass::Dense(m) => m[i * n + j],
        }
    }

    /// `out = M x / h`.
    pub(super) fn apply_over_h(&self, x: &[f64], h: f64, out: &mut [f64]) {
        let inv_h = 1.0 / h;
        match self {
            Mass::Diagonal(d) => {
                for ((o, m), xi) in out.iter_mut().zip(d).zip(x) {
                    *o = m * (xi * inv_h);
                }
            }
            Mass::Dense(m) => {
                let n = x.len();
                for (i, o) in out.iter_mut().enumerate() {
                    let row = &m[i * n..(i + 1) * n];
                    *o = row.iter().zip(x).map(|(a, b)| a * (b * inv_h)).sum();
                }
            }
        }
    }
}

/// Buffers of the separable step and the factored Jacobian kept between steps.
#[derive(Debug, Clone)]
pub struct SeparableWorkspace {
    /// `None`: not asked yet; `Some(None)`: not separable.
    pub(super) mass: Option<Option<Mass>>,
    pub(super) grad: Vec<f64>,
    pub(super) node: Vec<f64>,
    pub(super) momentum: Vec<f64>,
    pub(super) residual: Vec<f64>,
    pub(super) update: Vec<f64>,
    pub(super) scratch: Vec<f64>,
    pub(super) hess: Banded,
    pub(super) lu: BandLu,
    /// The `h` of the factored Jacobian (`None`: nothing factored).
    pub(super) lu_h: Option<f64>,
    /// The last contraction rate measured (NaN: none yet).
    pub(super) theta: f64,
}

impl Default for SeparableWorkspace {
    fn default() -> Self {
        Self {
            mass: None,
            grad: Vec::new(),
            node: Vec::new(),
            momentum: Vec::new(),
            residual: Vec::new(),
            update: Vec::new(),
            scratch: Vec::new(),
            hess: Banded::default(),
            lu: BandLu::default(),
            lu_h: None,
            theta: f64::NAN,
        }
    }
}

/// The factored Jacobian a separable step leaves for the next one, and its last contraction
/// rate: what decides whether the next step reuses it.
#[derive(Debug, Clone, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct SeparableCarry {
    lu: BandLu,
    lu_h: Option<f64>,
    theta: f64,
}

impl SeparableWorkspace {
    /// What this workspace carries to the next step, as plain numbers (a checkpoint).
    pub(crate) fn carried(&self) -> SeparableCarry {
        SeparableCarry {
            lu: self.lu.clone(),
            lu_h: self.lu_h,
            theta: self.theta,
        }
    }

    /// Takes back what [`SeparableWorkspace::carried`] gave.
    pub(crate) fn restore_carried(&mut self, carry: &SeparableCarry) {
        self.lu.clone_from(&carry.lu);
        self.lu_h = carry.lu_h;
        self.theta = carry.theta;
    }

    /// Whether the action's Lagrangian is separable (asks `step` once, then remembers).
    pub fn applies(&mut self, step: &dyn SeparableStep) -> bool {
        let mass = self.mass.get_or_insert_with(|| {
            step.mass().map(|m| match m {
                MassMatrix::Diagonal(d) => Mass::Diagonal(d),
                MassMatrix::Dense(m) => Mass::Dense(m),
            })
        });
        mass.is_some()
    }

    pub(super) fn resize(&mut self, n: usize) {
        for v in [
            &mut self.grad,
            &mut self.node,
            &mut self.momentum,
            &mut self.residual,
            &mut self.update,
        ] {
            v.resize(n, 0.0);
        }
    }
}

/// `q_α = q₀ + αΔ`, formed as the rules form it ([`crate::discrete::rules`]).
#[inline]
pub(super) fn node(alpha: f64, q0: &[f64], delta: &[f64], out: &mut [f64]) {
    for ((o, q), d) in out.iter_mut().zip(q0).zip(delta) {
        *o = match alpha {
            0.0 => *q,
            1.0 => q + d,
            _ => q + d * alpha,
        };
    }
}
