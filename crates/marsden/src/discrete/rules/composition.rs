//! Symmetric compositions of a variational integrator: higher order from a second-order one.
//!
//! With a symmetric one-step map `Φ_h` of order 2 and coefficients `γ₁ … γ_m` (`Σγ_i = 1`,
//! `γ_i = γ_{m+1−i}`) satisfying the order conditions, `Ψ_h = Φ_{γ_m h} ∘ … ∘ Φ_{γ₁ h}` has order
//! `p` (Hairer–Lubich–Wanner, *Geometric Numerical Integration*, §II.4 and §V.3; Yoshida, Phys.
//! Lett. A 150 (1990); Kahan & Li, Math. Comp. 66 (1997)). A composition of symplectic maps is
//! symplectic, and it is again variational ([MW01] §2.5): its discrete Lagrangian is the sum of
//! the substeps' discrete Lagrangians over the composed control points,
//!
//! ```text
//!     L_d^Ψ(Q₀, …, Q_m) = Σ_i L_d(Q_{i−1}, Q_i, γ_i h)      (t_i = t₀ + h Σ_{j<i} γ_j),
//! ```
//!
//! extremised over the interior points `Q₁ … Q_{m−1}`; that is how [`ComposedLd`] presents it to
//! the integrator, as a [`DiscreteAction`] with internal stages (each substep's own stages
//! included). Two consequences:
//!
//! * Implicit bases (midpoint, Galerkin) are solved as one Newton system over all substeps; the
//!   integrator sees one step of constant `h`, so its predictor extrapolates every substep's
//!   points from the previous steps — substeps of different (even negative) length never
//!   disturb the extrapolation history.
//! * If the base has an explicit form (the trapezoid rule on a separable Lagrangian is velocity
//!   Störmer–Verlet), the composed step is explicit too ([`ExplicitStep`]): `m` Verlet substeps,
//!   one force evaluation each (the first kick of a substep reuses nothing; the cost is
//!   `m + 1` gradients per step). This is the fast high-order route for N-body problems.
//!
//! | scheme | stages | order | source |
//! |---|---|---|---|
//! | `triple-jump-p` (p = 4, 6, 8, …) | `3^{p/2−1}` | p | Yoshida 1990 (recursive; Creutz & Gocksch, Suzuki) |
//! | `suzuki-4` | 5 | 4 | Suzuki, Phys. Lett. A 146 (1990) |
//! | `yoshida-6` | 7 | 6 | Yoshida 1990, solution A |
//! | `kahan-li-6` | 9 | 6 | Kahan & Li 1997, s9odr6a (HLW06 §V.3.2, eq. 3.11) |
//! | `suzuki-umeno-8` | 15 | 8 | Suzuki & Umeno 1993, McLachlan 1995 (HLW06 §V.3.2, eq. 3.12) |
//!
//! With holonomic constraints every substep is a full SHAKE + RATTLE step on `T*N` ([Rei96];
//! [`DiscreteAction::constrained_stages`]), so the composition keeps the scheme's order.
//!
//! [MW01]: crate#references
//! [Rei96]: crate#references
// The published coefficients are quoted with all their digits.
#![allow(clippy::excessive_precision)]

use crate::error::InputError;
use std::cell::Cell;
use std::sync::Arc;

use super::Rule;
use crate::discrete::{DiscreteAction, DiscreteForce};
use crate::error::Error;
use crate::mechanics::{Force, Lagrangian};
use crate::numerics::scratch::{Buffer, NODE};
use crate::scalar::Scalar;
use crate::separable::{ExplicitStep, ExplicitWorkspace};

/// A set of symmetric composition coefficients.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum CompositionScheme {
    /// Recursive triple jump of even order `p ≥ 4`: `γ = (x, −2^{1/(k+1)} x, x)`,
    /// `x = 1/(2 − 2^{1/(k+1)})`, applied for k = 2, 4, …, p − 2 (`3^{p/2−1}` stages).
    TripleJump {
        /// The order reached (even, 4 ≤ p ≤ 10).
        order: u32,
    },
    /// Suzuki's 5-stage fourth-order scheme: `x = 1/(4 − 4^{1/3})`, `(x, x, −4^{1/3}x, x, x)`.
    Suzuki4,
    /// Yoshida's 7-stage sixth-order scheme (solution A).
    Yoshida6,
    /// Kahan & Li's 9-stage sixth-order scheme s9odr6a.
    KahanLi6,
    /// The 15-stage eighth-order scheme s15odr8 of Suzuki & Umeno and McLachlan.
    SuzukiUmeno8,
}

/// Yoshida (1990) solution A, to 26 digits (HLW06 §V.3.2): `γ₁ … γ₄`, mirrored.
const YOSHIDA6: [f64; 4] = [
    0.784_513_610_477_557_263_819_497_63,
    0.235_573_213_359_358_133_684_793_18,
    -1.177_679_984_178_871_006_946_415_68,
    1.315_186_320_683_911_218_884_249_73,
];

/// Kahan & Li (1997) s9odr6a (HLW06 eq. V.3.11): `γ₁ … γ₅`, mirrored.
const KAHAN_LI6: [f64; 5] = [
    0.392_161_444_007_314_139_279_250_56,
    0.332_599_136_789_359_438_599_748_64,
    -0.706_246_172_557_639_359_809_964_82,
    0.082_213_596_293_550_800_231_490_45,
    0.798_543_990_934_829_963_398_950_35,
];

/// Suzuki & Umeno (1993), McLachlan (1995) s15odr8 (HLW06 eq. V.3.12): `γ₁ … γ₈`, mirrored.
const SUZUKI_UMENO8: [f64; 8] = [
    0.741_670_364_350_612_953_448_227_80,
    -0.409_100_825_800_031_593_997_300_10,
    0.190_754_710_296_238_379_953_876_26,
    -0.573_862_471_116_082_266_656_387_73,
    0.299_064_181_303_655_923_844_463_54,
    0.334_624_918_245_298_183_784_957_98,
    0.315_293_092_396_766_596_632_056_66,
    -0.796_887_939_352_916_354_019_788_84,
];

/// Every named scheme (triple jumps of orders 4, 6, 8), for listings and error messages.
pub const SCHEMES: [CompositionScheme; 7] = [
    CompositionScheme::TripleJump { order: 4 },
    CompositionScheme::TripleJump { order: 6 },
    CompositionScheme::TripleJump { order: 8 },
    CompositionScheme::Suzuki4,
    CompositionScheme::Yoshida6,
    CompositionScheme::KahanLi6,
    CompositionScheme::SuzukiUmeno8,
];

/// Mirrors `half` (centre last) into a symmetric sequence.
fn mirrored(half: &[f64]) -> Vec<f64> {
    let (outer, centre) = half.split_at(half.len() - 1);
    outer
        .iter()
        .chain(centre)
        .chain(outer.iter().rev())
        .copied()
        .collect()
}

impl CompositionScheme {
    /// The coefficients `γ₁ … γ_m` (symmetric, summing to 1).
    pub fn coefficients(self) -> Vec<f64> {
        match self {
            Self::TripleJump { order } => {
                let mut gammas = vec![1.0];
                for k in (2..order).step_by(2) {
                    let root = 2f64.powf(1.0 / (k as f64 + 1.0));
                    let x = 1.0 / (2.0 - root);
                    let jump = [x, -root * x, x];
                    gammas = jump
                        .iter()
                        .flat_map(|a| gammas.iter().map(move |g| a * g))
                        .collect();
                }
                gammas
            }
            Self::Suzuki4 => {
                let root = 4f64.powf(1.0 / 3.0);
                let x = 1.0 / (4.0 - root);
                vec![x, x, -root * x, x, x]
            }
            Self::Yoshida6 => mirrored(&YOSHIDA6),
            Self::KahanLi6 => mirrored(&KAHAN_LI6),
            Self::SuzukiUmeno8 => mirrored(&SUZUKI_UMENO8),
        }
    }

    /// The order reached from a symmetric second-order base.
    pub fn order(self) -> u32 {
        match self {
            Self::TripleJump { order } => order,
            Self::Suzuki4 => 4,
            Self::Yoshida6 | Self::KahanLi6 => 6,
            Self::SuzukiUmeno8 => 8,
        }
    }

    /// The name used in method strings, e.g. `kahan-li-6`.
    pub fn name(self) -> String {
        match self {
            Self::TripleJump { order } => format!("triple-jump-{order}"),
            Self::Suzuki4 => "suzuki-4".into(),
            Self::Yoshida6 => "yoshida-6".into(),
            Self::KahanLi6 => "kahan-li-6".into(),
            Self::SuzukiUmeno8 => "suzuki-umeno-8".into(),
        }
    }

    /// Parses a scheme name (`triple-jump-<p>` with even `4 ≤ p ≤ 10`, or a named scheme).
    pub fn parse(name: &str) -> Result<Self, Error> {
        if let Some(order) = name
            .strip_prefix("triple-jump-")
            .and_then(|p| p.parse::<u32>().ok())
            .filter(|order| order.is_multiple_of(2) && (4..=10).contains(order))
        {
            return Ok(Self::TripleJump { order });
        }
        SCHEMES
            .iter()
            .copied()
            .find(|s| s.name() == name)
            .ok_or_else(|| {
                Error::Input(InputError::UnknownMethod {
                    name: name.to_owned(),
                    reason: "no such composition scheme".into(),
                    valid: Self::valid_names(),
                })
            })
    }

    /// The valid scheme names, for messages.
    pub fn valid_names() -> String {
        "triple-jump-<p> (p = 4, 6, 8, 10), suzuki-4, yoshida-6, kahan-li-6, suzuki-umeno-8".into()
    }
}

/// A symmetric composition of a base rule: `Ψ_h = Φ_{γ_m h} ∘ … ∘ Φ_{γ₁ h}`.
///
/// ```
/// use marsden::discrete::rules::{Composition, CompositionScheme};
/// use marsden::{Rule, Trapezoid};
///
/// let verlet8 = Composition::new(Trapezoid, CompositionScheme::SuzukiUmeno8);
/// assert_eq!((verlet8.name().as_str(), verlet8.order()), ("suzuki-umeno-8(trapezoid)", 8));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Composition<R> {
    /// The base rule (second order and symmetric for the scheme's order to hold).
    pub base: R,
    /// The coefficients.
    pub scheme: CompositionScheme,
    gammas: Arc<[f64]>,
}

impl<R: Rule> Composition<R> {
    /// The composition of `base` with `scheme`.
    pub fn new(base: R, scheme: CompositionScheme) -> Self {
        Self {
            base,
            scheme,
            gammas: scheme.coefficients().into(),
        }
    }

    /// The coefficients `γ_i`.
    pub fn coefficients(&self) -> &[f64] {
        &self.gammas
    }
}

/// The composed discrete action (built by [`Composition`]).
pub struct ComposedLd<D> {
    /// The base discrete action, used for every substep.
    pub base: D,
    gammas: Arc<[f64]>,
    /// Scratch for the explicit step (intermediate positions and offsets).
    scratch: Cell<Vec<f64>>,
}

impl<D: std::fmt::Debug> std::fmt::Debug for ComposedLd<D> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ComposedLd")
            .field("base", &self.base)
            .field("gammas", &self.gammas)
            .finish()
    }
}

impl<D: Clone> Clone for ComposedLd<D> {
    fn clone(&self) -> Self {
        Self {
            base: self.base.clone(),
            gammas: Arc::clone(&self.gammas),
            scratch: Cell::new(Vec::new()),
        }
    }
}

/// `(t_i, h_i)` of every substep.
fn substeps(gammas: &[f64], t0: f64, h: f64) -> impl Iterator<Item = (f64, f64)> + '_ {
    gammas.iter().scan(0.0, move |elapsed, g| {
        let start = t0 + *elapsed * h;
        *elapsed += g;
        Some((start, g * h))
    })
}

/// Calls `f(i, t_i, h_i, Q_{i·sb}, offsets of substep i)` for every substep `i` (of size
/// `γ_i h`, `γ` = `gammas`, with `sb` offsets each) of the step of size `h` from `(t0, q0)` with
/// `offsets`, where the substep's offsets are `Δ_{i·sb+k} − Δ_{i·sb}`, `k = 1 … sb`.
#[inline]
fn for_each_substep<S: Scalar>(
    gammas: &[f64],
    sb: usize,
    t0: f64,
    h: f64,
    q0: &[S],
    offsets: &[S],
    mut f: impl FnMut(usize, (f64, f64), &[S], &[S]),
) {
    let n = q0.len();
    let zero = S::from(0.0);
    for (i, (ti, hi)) in substeps(gammas, t0, h).enumerate() {
        let first = i * sb;
        let start = |a: usize| {
            if first == 0 {
                zero
            } else {
                offsets[(first - 1) * n + a]
            }
        };
        let mut shift = Buffer::<S, NODE>::empty();
        let shift: &[S] = shift.from_fn(n, zero, start);
        let mut qi = Buffer::<S, NODE>::empty();
        let qi = qi.from_fn(n, zero, |a| q0[a] + shift[a]);
        let mut sub = Buffer::<S, { 2 * NODE }>::empty();
        let sub = sub.from_fn(sb * n, zero, |k| offsets[first * n + k] - shift[k % n]);
        f(i, (ti, hi), qi, sub);
    }
}

impl<D: DiscreteAction> DiscreteAction for ComposedLd<D> {
    const FIXED_DOF: Option<usize> = D::FIXED_DOF;
    // Every scheme has at least three substeps.
    const MAY_BE_TWO_POINT: bool = false;
    fn dof(&self) -> usize {
        self.base.dof()
    }
    fn internal_stages(&self) -> usize {
        self.gammas.len() * (self.base.internal_stages() + 1) - 1
    }
    #[inline]
    fn action<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], offsets: &[S]) -> S {
        let sb = self.base.internal_stages() + 1;
        let mut sum = S::from(0.0);
        for_each_substep(&self.gammas, sb, t0, h, q0, offsets, |_, (ti, hi), q, d| {
            sum += self.base.action(ti, hi, q, d);
        });
        sum
    }
    fn explicit(&self) -> Option<&dyn ExplicitStep> {
        self.base.explicit().map(|_| self as &dyn ExplicitStep)
    }

    /// A composition of constrained steps ([Rei96]): `φ = 0` at every inner substep boundary
    /// and at the base's own stages in every substep. Eliminating the momenta at a boundary,
    /// its multiplier is the sum of the RATTLE multipliers `μ_i + λ_{i+1}` of the two substeps
    /// that meet there, so the positions and the end momenta are those of `m` SHAKE + RATTLE
    /// steps (each on `T*N`), and a symmetric composition keeps its order.
    ///
    /// [Rei96]: crate#references
    fn constrained_stages(&self) -> Result<usize, String> {
        let base = self.base.constrained_stages()?;
        Ok(self.gammas.len() * (base + 1) - 1)
    }

    /// Stage `i`: the base's stage `i mod (b + 1)` of substep `i / (b + 1)`, or that substep's
    /// end point when the remainder is `b` (`b` the base's stage constraints).
    fn stage_point<S: Scalar>(&self, i: usize, q0: &[S], offsets: &[S], out: &mut [S]) {
        let n = q0.len();
        let per = self.base.constrained_stages().unwrap_or(0) + 1;
        let sb = self.base.internal_stages() + 1;
        let (k, r) = (i / per, i % per);
        let first = k * sb;
        let start = |a: usize| {
            if first == 0 {
                S::from(0.0)
            } else {
                offsets[(first - 1) * n + a]
            }
        };
        if r + 1 == per {
            let end = (first + sb - 1) * n;
            for (a, x) in out.iter_mut().enumerate() {
                *x = q0[a] + offsets[end + a];
            }
            return;
        }
        let zero = S::from(0.0);
        let mut shift = Buffer::<S, NODE>::empty();
        let shift: &[S] = shift.from_fn(n, zero, start);
        let mut qi = Buffer::<S, NODE>::empty();
        let qi = qi.from_fn(n, zero, |a| q0[a] + shift[a]);
        let mut sub = Buffer::<S, { 2 * NODE }>::empty();
        let sub = sub.from_fn(sb * n, zero, |j| offsets[first * n + j] - shift[j % n]);
        self.base.stage_point(r, qi, sub, out);
    }

    /// `γ_m` times the base's end weight.
    fn end_weight(&self) -> f64 {
        self.gammas.last().copied().unwrap_or(1.0) * self.base.end_weight()
    }
}

impl<D: DiscreteAction> ExplicitStep for ComposedLd<D> {
    /// `m` explicit substeps of the base; `Δ` is the sum of the substeps' offsets (no difference
    /// of rounded positions). Each substep starts from the previous one's `qᵢ + δᵢ`, computed
    /// exactly as the base computes its end point, so the base's first-same-as-last gradient
    /// cache hits and a composition of `m` substeps costs `m` gradients, not `2m`.
    fn explicit_step(
        &self,
        t: f64,
        h: f64,
        q: &[f64],
        p: &mut [f64],
        delta: &mut [f64],
        work: &mut ExplicitWorkspace,
    ) -> usize {
        let Some(base) = self.base.explicit() else {
            delta.fill(f64::NAN);
            return 0;
        };
        let n = q.len();
        let mut buffer = self.scratch.take();
        buffer.resize(2 * n, 0.0);
        let (qi, di) = buffer.split_at_mut(n);
        qi.copy_from_slice(q);
        delta.fill(0.0);
        let mut gradients = 0;
        for (ti, hi) in substeps(&self.gammas, t, h) {
            gradients += base.explicit_step(ti, hi, qi, p, di, work);
            for a in 0..n {
                delta[a] += di[a];
                qi[a] += di[a];
            }
        }
        self.scratch.set(buffer);
        gradients
    }
}

/// Discrete forces of a composition: each substep's forces on its own control points.
#[derive(Debug, Clone)]
pub struct ComposedForce<G> {
    /// The base rule's discrete force, used for every substep.
    pub base: G,
    /// Degrees of freedom.
    pub dof: usize,
    /// Segments per substep (the base's internal stages + 1).
    pub segments: usize,
    gammas: Arc<[f64]>,
}

impl<G: DiscreteForce> DiscreteForce for ComposedForce<G> {
    fn discrete_force<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], offsets: &[S], out: &mut [S]) {
        let (n, sb) = (self.dof, self.segments);
        let zero = S::from(0.0);
        out[..(self.gammas.len() * sb + 1) * n]
            .iter_mut()
            .for_each(|o| *o = zero);
        for_each_substep(&self.gammas, sb, t0, h, q0, offsets, |i, (ti, hi), q, d| {
            let mut f = Buffer::<S, { 2 * NODE }>::empty();
            let f = f.filled((sb + 1) * n, zero);
            self.base.discrete_force(ti, hi, q, d, f);
            let first = i * sb * n;
            for (k, fk) in f.iter().enumerate() {
                out[first + k] += *fk;
            }
        });
    }
    fn is_active(&self) -> bool {
        self.base.is_active()
    }
}

impl<R: Rule> Rule for Composition<R> {
    type Discrete<L: Lagrangian> = ComposedLd<R::Discrete<L>>;
    type DiscreteForce<F: Force> = ComposedForce<R::DiscreteForce<F>>;
    fn discretize<L: Lagrangian>(&self, lagrangian: L) -> Self::Discrete<L> {
        ComposedLd {
            base: self.base.discretize(lagrangian),
            gammas: Arc::clone(&self.gammas),
            scratch: Cell::new(Vec::new()),
        }
    }
    fn discretize_force<F: Force>(&self, force: F, dof: usize) -> Self::DiscreteForce<F> {
        let base = self.base.discretize_force(force, dof);
        // The base's segments: from a probe discretisation is not possible without a
        // Lagrangian, so the rule reports them.
        ComposedForce {
            base,
            dof,
            segments: self.base_segments(),
            gammas: Arc::clone(&self.gammas),
        }
    }
    /// `<scheme>(<base>)`, e.g. `kahan-li-6(trapezoid)`.
    fn name(&self) -> String {
        format!("{}({})", self.scheme.name(), self.base.name())
    }
    /// The scheme's order for a symmetric (even-order) base, at least the base's own order.
    fn order(&self) -> u32 {
        let base = self.base.order();
        if base.is_multiple_of(2) {
            base.max(self.scheme.order())
        } else {
            base
        }
    }
}

impl<R: Rule> Composition<R> {
    /// Segments per substep of the base rule (internal stages + 1), found by discretising a
    /// one-dimensional free particle (the count does not depend on the Lagrangian).
    fn base_segments(&self) -> usize {
        self.base.discretize(FreeParticle).internal_stages() + 1
    }
}

/// `L = ½v²`, only used to ask a rule how many control points it places.
struct FreeParticle;

impl Lagrangian for FreeParticle {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<S: Scalar>(&self, _t: S, _q: &[S], v: &[S]) -> S {
        v[0] * v[0] * 0.5
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coefficients_sum_to_one_and_kill_the_cubic_term() {
        for scheme in SCHEMES {
            let g = scheme.coefficients();
            // Σγ^k relative to Σ|γ|^k (round-off of the sum).
            let moment = |k: i32| {
                let sum: f64 = g.iter().map(|x| x.powi(k)).sum();
                let size: f64 = g.iter().map(|x| x.abs().powi(k)).sum();
                sum / size
            };
            let sum: f64 = g.iter().sum();
            assert!((sum - 1.0).abs() < 4e-15, "{}: Σγ = {sum}", scheme.name());
            assert!(
                moment(3).abs() < 4e-15,
                "{}: Σγ³ = {}",
                scheme.name(),
                moment(3)
            );
            assert!(g.iter().zip(g.iter().rev()).all(|(a, b)| a == b));
            if scheme.order() >= 6 {
                assert!(
                    moment(5).abs() < 4e-15,
                    "{}: Σγ⁵ = {}",
                    scheme.name(),
                    moment(5)
                );
            }
            assert_eq!(CompositionScheme::parse(&scheme.name()), Ok(scheme));
        }
        assert_eq!(
            CompositionScheme::TripleJump { order: 8 }
                .coefficients()
                .len(),
            27
        );
        assert!(CompositionScheme::parse("yoshida-5").is_err());
    }
}
