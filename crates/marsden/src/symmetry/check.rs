//! Is a declared action a symmetry? Infinitesimal invariance at sampled states, with the size
//! of the defect.
//!
//! Concept of the notes (MW01): *symmetries of the Lagrangian* (`⟨dL, ξ_TQ⟩ = 0`), *discrete Noether* (`L_d` invariant
//! ⟹ `⟨dL_d, ξ_{Q×Q}⟩ = 0`) and *Hamiltonian momentum maps* (`⟨dH, ξ_T*Q⟩ = 0`). At each
//! sample the directional derivative `⟨dF, ξ⟩ = Σᵢ ∂F/∂xᵢ ξᵢ` is computed exactly by AD; its
//! size is compared with the size of the terms that should cancel, `Σᵢ |∂F/∂xᵢ ξᵢ|`, so the
//! relative defect of a true symmetry is at round-off (≈ 1e-16) whatever the units. With
//! holonomic constraints a symmetry must also keep `φ` invariant (`Dφ·ξ_Q = 0`,
//! [`check_constraint`]).

use crate::error::SetupError;
use std::fmt;

use super::{FiniteAction, GroupAction, tangent_lift, validate};
use crate::discrete::DiscreteLagrangian;
use crate::error::Error;
use crate::hamiltonian::Hamiltonian;
use crate::mechanics::{Constraint, Lagrangian, constraint_jacobian};
use crate::numerics::ad::{self, MultiFunction};
use crate::scalar::Scalar;
use crate::symmetry::cotangent_lift;

/// Default relative tolerance of the symmetry checks.
pub const DEFAULT_TOLERANCE: f64 = 1e-10;

/// A sampled state `(t, q, v)` (for Hamiltonian checks `v` holds the momenta `p`; for discrete
/// checks the pair is `(q, q + h v)`).
#[derive(Debug, Clone, PartialEq)]
pub struct Sample {
    /// Time.
    pub t: f64,
    /// Positions.
    pub q: Vec<f64>,
    /// Velocities (or momenta).
    pub v: Vec<f64>,
}

impl Sample {
    /// A sample at `(t, q, v)`.
    pub fn new(t: f64, q: &[f64], v: &[f64]) -> Self {
        Self {
            t,
            q: q.to_vec(),
            v: v.to_vec(),
        }
    }

    /// `count` reproducible pseudo-random samples with `q, v` uniform in `[−radius, radius]ⁿ`
    /// and `t = 0` (SplitMix64 from `seed`).
    pub fn random(dof: usize, count: usize, seed: u64, radius: f64) -> Vec<Self> {
        let mut state = seed;
        let mut uniform = move || {
            state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = state;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            z ^= z >> 31;
            ((z >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0) * radius
        };
        (0..count)
            .map(|_| {
                let q: Vec<f64> = (0..dof).map(|_| uniform()).collect();
                let v: Vec<f64> = (0..dof).map(|_| uniform()).collect();
                Self { t: 0.0, q, v }
            })
            .collect()
    }
}

/// The worst defect of one basis generator over the samples.
#[derive(Debug, Clone, PartialEq)]
pub struct GeneratorDefect {
    /// Index `a` of the basis element `e_a`.
    pub generator: usize,
    /// `max |⟨dF, (e_a)⟩|` over the samples.
    pub max_defect: f64,
    /// `max |⟨dF, e_a⟩| / Σᵢ |∂F/∂xᵢ (e_a)ᵢ|` over the samples.
    pub max_relative: f64,
    /// Index of the sample where the relative defect is largest.
    pub worst_sample: usize,
}

/// The outcome of a symmetry check.
#[derive(Debug, Clone, PartialEq)]
pub struct SymmetryReport {
    /// Name of the group action.
    pub symmetry: String,
    /// What was checked: `"L"`, `"L_d"`, `"H"` or `"φ"` (the constraints).
    pub of: &'static str,
    /// Relative tolerance.
    pub tolerance: f64,
    /// Number of samples.
    pub samples: usize,
    /// One entry per basis generator.
    pub generators: Vec<GeneratorDefect>,
}

impl SymmetryReport {
    /// Whether every generator's relative defect is within the tolerance.
    pub fn is_symmetry(&self) -> bool {
        self.generators
            .iter()
            .all(|g| g.max_relative <= self.tolerance)
    }

    /// The generator with the largest relative defect.
    pub fn worst(&self) -> Option<&GeneratorDefect> {
        self.generators
            .iter()
            .max_by(|a, b| a.max_relative.total_cmp(&b.max_relative))
    }

    /// `Ok(self)` for a symmetry, otherwise [`crate::error::SetupError::NotASymmetry`] with the
    /// worst defect.
    pub fn into_result(self) -> Result<Self, Error> {
        match self.worst() {
            Some(w) if !self.is_symmetry() => Err(Error::Setup(SetupError::NotASymmetry {
                symmetry: self.symmetry.clone(),
                of: self.of,
                generator: w.generator,
                defect: w.max_defect,
                relative: w.max_relative,
                tolerance: self.tolerance,
            })),
            _ => Ok(self),
        }
    }
}

impl fmt::Display for SymmetryReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let verdict = if self.is_symmetry() { "is" } else { "is NOT" };
        write!(
            f,
            "\"{}\" {verdict} a symmetry of {} ({} samples, tolerance {:.1e})",
            self.symmetry, self.of, self.samples, self.tolerance
        )?;
        for g in &self.generators {
            write!(
                f,
                "; generator {}: max |<d{}, xi>| = {:.3e} (relative {:.3e}, sample {})",
                g.generator, self.of, g.max_defect, g.max_relative, g.worst_sample
            )?;
        }
        Ok(())
    }
}

/// A scalar function of `x` with `t` fixed, for the AD drivers.
struct ScalarFn<'a, F>(&'a F);

/// `F(x)` where `x` is the concatenation of two length-n blocks.
trait TwoBlock {
    fn dof(&self) -> usize;
    fn value<S: Scalar>(&self, a: &[S], b: &[S]) -> S;
}

impl<F: TwoBlock> MultiFunction for ScalarFn<'_, F> {
    fn inputs(&self) -> usize {
        2 * self.0.dof()
    }
    fn outputs(&self) -> usize {
        1
    }
    fn eval<S: Scalar>(&self, x: &[S], out: &mut [S]) {
        let (a, b) = x.split_at(self.0.dof());
        out[0] = self.0.value(a, b);
    }
}

struct OfL<'a, L>(&'a L, f64);
impl<L: Lagrangian> TwoBlock for OfL<'_, L> {
    fn dof(&self) -> usize {
        self.0.dof()
    }
    fn value<S: Scalar>(&self, q: &[S], v: &[S]) -> S {
        self.0.lagrangian(S::from(self.1), q, v)
    }
}

struct OfLd<'a, D>(&'a D, f64, f64);
impl<D: DiscreteLagrangian> TwoBlock for OfLd<'_, D> {
    fn dof(&self) -> usize {
        self.0.dof()
    }
    fn value<S: Scalar>(&self, q0: &[S], q1: &[S]) -> S {
        self.0.discrete_lagrangian(self.1, self.2, q0, q1)
    }
}

struct OfH<'a, H>(&'a H, f64);
impl<H: Hamiltonian> TwoBlock for OfH<'_, H> {
    fn dof(&self) -> usize {
        self.0.dof()
    }
    fn value<S: Scalar>(&self, q: &[S], p: &[S]) -> S {
        self.0.hamiltonian(S::from(self.1), q, p)
    }
}

/// `(⟨dF, d⟩, Σ|∂F/∂xᵢ dᵢ|)` at `x = (a, b)` in direction `d`.
fn directional<F: TwoBlock>(f: &F, x: &[f64], d: &[f64]) -> (f64, f64) {
    let mut grad = vec![0.0; x.len()];
    ad::jacobian(&ScalarFn(f), x, 0..x.len(), &mut [0.0], &mut grad);
    grad.iter().zip(d).fold((0.0, 0.0), |(s, m), (g, di)| {
        (s + g * di, m + (g * di).abs())
    })
}

/// `|defect| / scale`: 0 for an exact zero (whatever the scale), infinite when the scale
/// vanishes or the defect is not finite (a defect that cannot be judged certifies nothing).
pub fn relative_defect(defect: f64, scale: f64) -> f64 {
    let d = defect.abs();
    if d == 0.0 {
        0.0
    } else if scale > 0.0 && d.is_finite() {
        d / scale
    } else {
        f64::INFINITY
    }
}

/// Runs `eval(a, sample) → (defect, scale)` over every generator and sample.
fn check_with(
    symmetry: String,
    of: &'static str,
    m: usize,
    samples: &[Sample],
    tolerance: f64,
    mut eval: impl FnMut(usize, &Sample) -> (f64, f64),
) -> SymmetryReport {
    let generators = (0..m)
        .map(|a| {
            let mut g = GeneratorDefect {
                generator: a,
                max_defect: 0.0,
                max_relative: 0.0,
                worst_sample: 0,
            };
            for (k, s) in samples.iter().enumerate() {
                let (defect, scale) = eval(a, s);
                let d = defect.abs();
                let relative = relative_defect(d, scale);
                g.max_defect = g.max_defect.max(d);
                if relative > g.max_relative {
                    g.max_relative = relative;
                    g.worst_sample = k;
                }
            }
            g
        })
        .collect();
    SymmetryReport {
        symmetry,
        of,
        tolerance,
        samples: samples.len(),
        generators,
    }
}

fn validate_samples<G: GroupAction>(action: &G, n: usize, samples: &[Sample]) -> Result<(), Error> {
    for s in samples {
        Error::check_len("sample q", &s.q, n)?;
        Error::check_len("sample v", &s.v, n)?;
        validate(action, n, &s.q)?;
    }
    if samples.is_empty() {
        validate(action, n, &vec![0.0; n])?;
    }
    Ok(())
}

/// Checks `⟨dL, ξ_TQ⟩ = 0` at every sample `(t, q, v)` for every basis generator.
///
/// Returns the report (a non-symmetry is a report with `is_symmetry() == false`, see
/// [`SymmetryReport::into_result`]); errors only if the action does not fit the system.
pub fn check_lagrangian<L: Lagrangian, G: GroupAction>(
    l: &L,
    action: &G,
    samples: &[Sample],
    tolerance: f64,
) -> Result<SymmetryReport, Error> {
    let n = l.dof();
    validate_samples(action, n, samples)?;
    let mut d = vec![0.0; 2 * n];
    Ok(check_with(
        action.name(),
        "L",
        action.algebra_dim(),
        samples,
        tolerance,
        |a, s| {
            let (dq, dv) = d.split_at_mut(n);
            tangent_lift(action, a, &s.q, &s.v, dq, dv);
            let x: Vec<f64> = s.q.iter().chain(&s.v).copied().collect();
            directional(&OfL(l, s.t), &x, &d)
        },
    ))
}

/// Checks `⟨dL_d, ξ_{Q×Q}⟩ = D₁L_d·ξ_Q(q₀) + D₂L_d·ξ_Q(q₁) = 0` for the steps
/// `(q₀, q₁) = (q, q + h v)` from `t` to `t + h` at every sample.
pub fn check_discrete<D: DiscreteLagrangian, G: GroupAction>(
    ld: &D,
    action: &G,
    h: f64,
    samples: &[Sample],
    tolerance: f64,
) -> Result<SymmetryReport, Error> {
    let n = ld.dof();
    validate_samples(action, n, samples)?;
    let (mut x, mut d) = (vec![0.0; 2 * n], vec![0.0; 2 * n]);
    Ok(check_with(
        action.name(),
        "L_d",
        action.algebra_dim(),
        samples,
        tolerance,
        |a, s| {
            for i in 0..n {
                x[i] = s.q[i];
                x[n + i] = s.q[i] + h * s.v[i];
            }
            let (d0, d1) = d.split_at_mut(n);
            action.generator(a, &x[..n], d0);
            action.generator(a, &x[n..], d1);
            directional(&OfLd(ld, s.t, h), &x, &d)
        },
    ))
}

/// Checks `⟨dH, ξ_T*Q⟩ = 0` at every sample `(t, q, p)` (`p` in [`Sample::v`]).
pub fn check_hamiltonian<H: Hamiltonian, G: GroupAction>(
    ham: &H,
    action: &G,
    samples: &[Sample],
    tolerance: f64,
) -> Result<SymmetryReport, Error> {
    let n = ham.dof();
    validate_samples(action, n, samples)?;
    let mut d = vec![0.0; 2 * n];
    Ok(check_with(
        action.name(),
        "H",
        action.algebra_dim(),
        samples,
        tolerance,
        |a, s| {
            let (dq, dp) = d.split_at_mut(n);
            cotangent_lift(action, a, &s.q, &s.v, dq, dp);
            let x: Vec<f64> = s.q.iter().chain(&s.v).copied().collect();
            directional(&OfH(ham, s.t), &x, &d)
        },
    ))
}

/// Checks that every basis generator keeps the constraints invariant, `Dφ(q)·ξ_Q(q) = 0`
/// (the action maps the constraint manifold `N` to itself, so `J` is a momentum map of the
/// constrained system; otherwise the constraint forces `Dφᵀλ` have a component along `ξ_Q` and
/// `J` is not conserved), at every sample's `q`. The defect of a generator is the largest
/// `|Dφ_c(q)·ξ_Q(q)|` over the constraints `c`, relative to `Σᵢ |∂φ_c/∂qᵢ ξᵢ|`. Without
/// constraints every action passes.
pub fn check_constraint<C: Constraint, G: GroupAction>(
    constraint: &C,
    action: &G,
    samples: &[Sample],
    tolerance: f64,
) -> Result<SymmetryReport, Error> {
    let n = action.dof();
    validate_samples(action, n, samples)?;
    let d = constraint.count();
    let (mut phi, mut g, mut xi) = (vec![0.0; d], vec![0.0; d * n], vec![0.0; n]);
    Ok(check_with(
        action.name(),
        "φ",
        action.algebra_dim(),
        samples,
        tolerance,
        |a, s| {
            if d == 0 {
                return (0.0, 0.0);
            }
            constraint_jacobian(constraint, &s.q, &mut phi, &mut g);
            action.generator(a, &s.q, &mut xi);
            let mut worst = (0.0, 0.0);
            let mut worst_relative = -1.0;
            for row in g.chunks_exact(n) {
                let (sum, scale) = row.iter().zip(&xi).fold((0.0, 0.0), |(s, m), (gi, x)| {
                    (s + gi * x, m + (gi * x).abs())
                });
                let relative = if sum == 0.0 { 0.0 } else { sum.abs() / scale };
                if relative > worst_relative {
                    (worst, worst_relative) = ((sum, scale), relative);
                }
            }
            worst
        },
    ))
}

/// Finite invariance of `L_d`: `max |L_d(Φ_g q₀, Φ_g q₁) − L_d(q₀, q₁)| / max(|L_d|, tiny)` over
/// the samples `(q, q + h v)`, for `g = exp(ξ)`.
pub fn discrete_invariance_defect<D: DiscreteLagrangian, G: FiniteAction>(
    ld: &D,
    action: &G,
    xi: &[f64],
    h: f64,
    samples: &[Sample],
) -> Result<f64, Error> {
    let n = ld.dof();
    validate_samples(action, n, samples)?;
    let (mut g0, mut g1) = (vec![0.0; n], vec![0.0; n]);
    let mut worst: f64 = 0.0;
    for s in samples {
        let q1: Vec<f64> = s.q.iter().zip(&s.v).map(|(q, v)| q + h * v).collect();
        action.act(xi, &s.q, &mut g0);
        action.act(xi, &q1, &mut g1);
        let before = ld.discrete_lagrangian(s.t, h, &s.q, &q1);
        let after = ld.discrete_lagrangian(s.t, h, &g0, &g1);
        worst = worst.max((after - before).abs() / before.abs().max(f64::MIN_POSITIVE));
    }
    Ok(worst)
}
