//! Continuous mechanics of a [`Lagrangian`] by automatic differentiation.
//!
//! Concept of the notes (MW01): *Legendre transforms*. With `z = (t, q, v)` one hyper-dual evaluation of `L` gives
//! `∂L/∂q`, `∂L/∂v` and the block `∂²L/∂v∂(t, q, v)`, from which ([MW01] §1.2–1.4, [HLW06] §VI.1):
//!
//! * the Legendre transform `FL(q, v) = (q, ∂L/∂v)` ([`momentum`]);
//! * the energy `E(q, v) = ⟨∂L/∂v, v⟩ − L` ([`energy`]);
//! * the Euler–Lagrange residual `d/dt ∂L/∂v − ∂L/∂q
//!   = ∂²L/∂v² a + ∂²L/∂v∂q v + ∂²L/∂v∂t − ∂L/∂q` ([`euler_lagrange_residual`]);
//! * the accelerations `a = (∂²L/∂v²)⁻¹ (∂L/∂q − ∂²L/∂v∂q v − ∂²L/∂v∂t)` ([`acceleration`]);
//! * the regularity check (`∂²L/∂v²` invertible, [`check_regular`]) and the inverse Legendre
//!   transform `v = FH(q, p)` by Newton's method ([`velocity`]).
//!
//! Large separable Lagrangians (more than [`structure::LARGE`] degrees of freedom) take the
//! shortcuts of [`crate::mechanics::structure`] in [`momentum`], [`check_regular`] and
//! [`check_structure`]: the AD jet would cost `O(n)` evaluations of `L`. Every separable
//! Lagrangian, whatever its size, inverts the Legendre transform as `v = M⁻¹ p` ([`velocity`]).
//!
//! [MW01]: crate#references
//! [HLW06]: crate#references

use crate::error::Error;
use crate::error::SetupError;
use crate::mechanics::lagrangian::times_dof;
use crate::mechanics::{Lagrangian, structure};
use crate::numerics::ad::{self, HessianParts, MultiFunction};
use crate::numerics::dense::{Lu, max_norm};
use crate::numerics::scratch::with_slice;
use crate::scalar::Scalar;

/// `L` as a function of `z = (t, q, v)` for the AD drivers.
struct OnTangentBundle<'a, L>(&'a L);

impl<L: Lagrangian> MultiFunction for OnTangentBundle<'_, L> {
    const MAX_INPUTS: Option<usize> = times_dof(L::FIXED_DOF, 2, 1);
    fn inputs(&self) -> usize {
        2 * self.0.dof() + 1
    }
    fn outputs(&self) -> usize {
        1
    }
    #[inline]
    fn eval<S: Scalar>(&self, z: &[S], out: &mut [S]) {
        let n = self.0.dof();
        out[0] = self.0.lagrangian(z[0], &z[1..=n], &z[n + 1..]);
    }
}

/// Derivatives of `L` at one state: what every function of this module is built from.
#[derive(Debug, Clone)]
pub struct LagrangianJet {
    /// Degrees of freedom.
    pub n: usize,
    /// `L(t, q, v)`.
    pub value: f64,
    /// `∂L/∂t`.
    pub dl_dt: f64,
    /// `∂L/∂q` (length n).
    pub dl_dq: Vec<f64>,
    /// `∂L/∂v` (length n): the momenta `p = FL(q, v)`.
    pub dl_dv: Vec<f64>,
    /// `∂²L/∂v∂t` (length n).
    pub d2l_dvdt: Vec<f64>,
    /// `∂²L/∂v∂q`, row-major n × n (row: v index).
    pub d2l_dvdq: Vec<f64>,
    /// `∂²L/∂v²`, row-major n × n: the generalised mass matrix.
    pub d2l_dv2: Vec<f64>,
}

impl LagrangianJet {
    /// Evaluates all first derivatives and the second derivatives in `v` at `(t, q, v)`.
    pub fn at<L: Lagrangian>(l: &L, t: f64, q: &[f64], v: &[f64]) -> Self {
        let n = l.dof();
        let mut parts = HessianParts::default();
        at_tangent_point(t, q, v, |z| {
            let (rows, cols) = (n + 1..2 * n + 1, 0..2 * n + 1);
            ad::partial_hessian(&OnTangentBundle(l), z, rows, cols, &mut parts)
        });
        let row = |a: usize, range: std::ops::Range<usize>| -> Vec<f64> {
            range.map(|j| parts.hess[a * (2 * n + 1) + j]).collect()
        };
        let mut d2l_dvdq = Vec::with_capacity(n * n);
        let mut d2l_dv2 = Vec::with_capacity(n * n);
        for a in 0..n {
            d2l_dvdq.extend(row(a, 1..n + 1));
            d2l_dv2.extend(row(a, n + 1..2 * n + 1));
        }
        Self {
            n,
            value: parts.values[0],
            dl_dt: parts.jac_cols[0],
            dl_dq: parts.jac_cols[1..=n].to_vec(),
            dl_dv: parts.grad_rows.clone(),
            d2l_dvdt: (0..n).map(|a| parts.hess[a * (2 * n + 1)]).collect(),
            d2l_dvdq,
            d2l_dv2,
        }
    }
}

/// `body` at `z = (t, q, v)`, the input of [`OnTangentBundle`], held on the stack for small
/// systems (these derivatives are taken at every evaluation of the Euler–Lagrange vector field
/// by [`crate::discrete::exact`]).
#[inline(always)]
fn at_tangent_point<R>(t: f64, q: &[f64], v: &[f64], body: impl FnOnce(&[f64]) -> R) -> R {
    let n = q.len();
    with_slice(1 + 2 * n, t, |z| {
        z[1..=n].copy_from_slice(q);
        z[n + 1..].copy_from_slice(v);
        body(z)
    })
}

/// Legendre transform `p = ∂L/∂v (t, q, v)`, written into `p`.
pub fn momentum<L: Lagrangian>(l: &L, t: f64, q: &[f64], v: &[f64], p: &mut [f64]) {
    if let Some(mass) = structure::large_separable(l) {
        return structure::momentum(&mass, v, p);
    }
    let n = l.dof();
    at_tangent_point(t, q, v, |z| {
        ad::jacobian(&OnTangentBundle(l), z, n + 1..2 * n + 1, &mut [0.0], p)
    });
}

/// `∂L/∂q (t, q, v)`, written into `out`.
pub fn dl_dq<L: Lagrangian>(l: &L, t: f64, q: &[f64], v: &[f64], out: &mut [f64]) {
    let n = l.dof();
    at_tangent_point(t, q, v, |z| {
        ad::jacobian(&OnTangentBundle(l), z, 1..n + 1, &mut [0.0], out)
    });
}

/// Energy `E = ⟨∂L/∂v, v⟩ − L` at `(t, q, v)`.
pub fn energy<L: Lagrangian>(l: &L, t: f64, q: &[f64], v: &[f64]) -> f64 {
    let mut p = vec![0.0; l.dof()];
    momentum(l, t, q, v, &mut p);
    let pv: f64 = p.iter().zip(v).map(|(a, b)| a * b).sum();
    pv - l.lagrangian(t, q, v)
}

/// Euler–Lagrange residual `d/dt(∂L/∂v) − ∂L/∂q` along a path through `(t, q, v)` with
/// acceleration `a`; zero exactly on solutions.
pub fn euler_lagrange_residual<L: Lagrangian>(
    l: &L,
    t: f64,
    q: &[f64],
    v: &[f64],
    a: &[f64],
    out: &mut [f64],
) {
    let jet = LagrangianJet::at(l, t, q, v);
    let n = jet.n;
    for (i, r) in out.iter_mut().enumerate().take(n) {
        let mut s = jet.d2l_dvdt[i] - jet.dl_dq[i];
        for j in 0..n {
            s += jet.d2l_dv2[i * n + j] * a[j] + jet.d2l_dvdq[i * n + j] * v[j];
        }
        *r = s;
    }
}

/// Factors `∂²L/∂v²` of a jet, or reports the Lagrangian singular.
fn factor_mass(jet: &LagrangianJet, t: f64, q: &[f64], v: &[f64]) -> Result<Lu, Error> {
    let mut lu = Lu::new();
    let scale = max_norm(&jet.d2l_dv2);
    lu.factor(&jet.d2l_dv2, jet.n).map_err(|e| {
        Error::Setup(SetupError::SingularLagrangian {
            t,
            q: q.to_vec(),
            v: v.to_vec(),
            pivot: e.pivot,
            scale,
        })
    })?;
    Ok(lu)
}

/// Checks that `L` is regular at `(t, q, v)`: `∂²L/∂v²` is invertible.
pub fn check_regular<L: Lagrangian>(l: &L, t: f64, q: &[f64], v: &[f64]) -> Result<(), Error> {
    if let Some(mass) = structure::large_separable(l) {
        return structure::velocity(&mass, t, q, v, &mut vec![0.0; v.len()]);
    }
    factor_mass(&LagrangianJet::at(l, t, q, v), t, q, v).map(|_| ())
}

/// Accelerations `a` solving the Euler–Lagrange equations at `(t, q, v)`.
pub fn acceleration<L: Lagrangian>(
    l: &L,
    t: f64,
    q: &[f64],
    v: &[f64],
    a: &mut [f64],
) -> Result<(), Error> {
    let jet = LagrangianJet::at(l, t, q, v);
    let lu = factor_mass(&jet, t, q, v)?;
    let n = jet.n;
    for (i, ai) in a.iter_mut().enumerate().take(n) {
        let row = &jet.d2l_dvdq[i * n..(i + 1) * n];
        let coupling: f64 = row.iter().zip(v).map(|(m, vj)| m * vj).sum();
        *ai = jet.dl_dq[i] - coupling - jet.d2l_dvdt[i];
    }
    lu.solve(a, &mut Vec::with_capacity(n));
    Ok(())
}

/// Inverse Legendre transform `v = FH(t, q, p)`: solves `∂L/∂v(t, q, v) = p` by Newton's
/// method from the guess already in `v` (zero is a fine guess for mechanical systems, whose
/// momenta are linear in `v`). Converges to `|∂L/∂v − p| ≤ 1e-14 · max(1, |p|)`. A Lagrangian
/// that declares itself separable gets `v = M⁻¹ p` directly.
pub fn velocity<L: Lagrangian>(
    l: &L,
    t: f64,
    q: &[f64],
    p: &[f64],
    v: &mut [f64],
) -> Result<(), Error> {
    const MAX_ITERATIONS: usize = 50;
    if let Some(mass) = structure::separable_mass(l) {
        return structure::velocity(&mass, t, q, p, v);
    }
    let n = l.dof();
    if v.iter().all(|x| *x == 0.0) {
        // No guess given: the Lagrangian's own, where it has one (`∂H/∂p` for a Hamiltonian's).
        l.velocity_guess(t, q, p, v);
    }
    let tol = 1e-14 * max_norm(p).max(1.0);
    let mut r = vec![0.0; n];
    let mut scratch = Vec::with_capacity(n);
    let mut residual = f64::INFINITY;
    for iteration in 0..MAX_ITERATIONS {
        let jet = LagrangianJet::at(l, t, q, v);
        for i in 0..n {
            r[i] = p[i] - jet.dl_dv[i];
        }
        let previous = residual;
        residual = max_norm(&r);
        // Stop at tolerance, or once round-off stalls the decrease.
        if residual <= tol || (iteration > 0 && residual >= previous && residual < 1e3 * tol) {
            return Ok(());
        }
        let lu = factor_mass(&jet, t, q, v)?;
        lu.solve(&mut r, &mut scratch);
        for (vi, d) in v.iter_mut().zip(&r) {
            *vi += d;
        }
    }
    Err(Error::Setup(SetupError::InverseLegendre {
        t,
        iterations: MAX_ITERATIONS,
        residual,
    }))
}

/// Checks a declared [`crate::mechanics::Structure`] at `(t, q, v)` by AD: for `Separable`, `∂²L/∂v²`
/// must equal the mass matrix and `∂²L/∂v∂q`, `∂²L/∂v∂t` must vanish (relative 1e-10).
pub fn check_structure<L: Lagrangian>(l: &L, t: f64, q: &[f64], v: &[f64]) -> Result<(), Error> {
    let crate::mechanics::Structure::Separable { mass } = l.structure() else {
        return Ok(());
    };
    if l.dof() > structure::LARGE {
        return structure::check_by_probes(l, &mass, t, q, v);
    }
    let jet = LagrangianJet::at(l, t, q, v);
    let dense = mass.to_dense();
    let scale = max_norm(&dense).max(1.0);
    let mismatch = |what, defect: f64| {
        Error::Setup(SetupError::StructureMismatch {
            q: q.to_vec(),
            v: v.to_vec(),
            what,
            defect,
        })
    };
    let defect = |a: &[f64], b: &[f64]| {
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, crate::numerics::dense::max_or_nan)
    };
    if dense.len() != jet.n * jet.n {
        return Err(mismatch(
            "the size of the mass matrix",
            (dense.len() as f64).sqrt() - jet.n as f64,
        ));
    }
    let checks = [
        (
            "∂²L/∂v² against the mass matrix",
            defect(&jet.d2l_dv2, &dense),
        ),
        ("∂²L/∂v∂q", max_norm(&jet.d2l_dvdq)),
        ("∂²L/∂v∂t", max_norm(&jet.d2l_dvdt)),
    ];
    match checks
        .iter()
        .find(|(_, d)| d.is_nan() || d.abs() > 1e-10 * scale)
    {
        Some((what, d)) => Err(mismatch(what, *d)),
        None => Ok(()),
    }
}

/// Energy at a phase-space point `(t, q, p)`: `E(q, FH(q, p))`, the Hamiltonian.
pub fn energy_from_momentum<L: Lagrangian>(
    l: &L,
    t: f64,
    q: &[f64],
    p: &[f64],
    v_guess: &mut [f64],
) -> Result<f64, Error> {
    velocity(l, t, q, p, v_guess)?;
    let pv: f64 = p.iter().zip(v_guess.iter()).map(|(a, b)| a * b).sum();
    Ok(pv - l.lagrangian(t, q, v_guess))
}
