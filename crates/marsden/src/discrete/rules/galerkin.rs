//! Galerkin variational integrators: `q(t)` a polynomial of degree `s` on each step, the action
//! by a quadrature rule.
//!
//! [MW01] §2.2.6 and [OBS15]: with control points `Q₀ = q_k, Q₁, …, Q_s = q_{k+1}` at the
//! equispaced times `d_j h`, `d_j = j/s`, and the Lagrange basis `ℓ_j` of those times,
//!
//! ```text
//!     q(t₀ + τh) = Σ_j ℓ_j(τ) Q_j,      L_d(Q₀, …, Q_s) = h Σ_i b_i L(t₀ + c_i h, q(c_i h), q̇(c_i h)),
//! ```
//!
//! with quadrature nodes `c_i` and weights `b_i` ([`Quadrature`]). The discrete Lagrangian of the
//! step is this action extremised over the interior control points; the integrator's step
//! solves `∂L_d/∂Q_j = 0` (`0 < j < s`) in the same Newton system as the discrete Legendre
//! transform (`crate::integrator::equations`). Where the interior points sit does not change `L_d` (the space of
//! polynomials with fixed end values is the same), so the equispaced times, which the
//! predictor's first guess `Q_j ≈ q_k + d_j h v_k` assumes, are used. Written over offsets
//! `Δ_j = Q_j − Q₀` (`Σ_j ℓ_j = 1`, `Σ_j ℓ_j' = 0`):
//!
//! ```text
//!     q(c_i h) = q₀ + Σ_{j≥1} ℓ_j(c_i) Δ_j,      q̇(c_i h) = (1/h) Σ_{j≥1} ℓ_j'(c_i) Δ_j.
//! ```
//!
//! Discrete forces by the same quadrature (Lagrange–d'Alembert, [MW01] §3.2): the force on
//! control point `j` is `f_j = h Σ_i b_i ℓ_j(c_i) f(t₀ + c_i h, q(c_i h), q̇(c_i h))`.
//!
//! Orders ([OBS15]; [OB17] proves the Gauss case; [HLW06] §VI.6): with `r` Gauss points the
//! order is `min(2s, 2r)`, with `r` Lobatto points `min(2s, 2r − 2)`. `P_s` with `s` Gauss points
//! is the `s`-stage Gauss collocation method; `P_{s−1}` with `s` Lobatto points is Lobatto
//! IIIA–IIIB (reference case R6). The rule needs `r ≥ s` points: with fewer, some non-constant
//! velocity polynomial of degree `s − 1` vanishes at every node, the quadrature of the kinetic
//! energy is degenerate and the step is not regular.
//!
//! With holonomic constraints the Lobatto rules impose `φ = 0` at every interior node
//! ([`DiscreteAction::constrained_stages`]): the constrained Lobatto IIIA–IIIB method of [Jay96],
//! which keeps the order `2s − 2`; the Gauss rules have no such form here and are refused.
//!
//! [MW01]: crate#references
//! [OBS15]: crate#references
//! [OB17]: crate#references
//! [HLW06]: crate#references
//! [Jay96]: crate#references

use crate::error::InputError;
use std::sync::Arc;

use super::Rule;
use super::quadrature::{Quadrature, QuadratureFamily};
use crate::discrete::{DiscreteAction, DiscreteForce};
use crate::error::Error;
use crate::mechanics::{Force, Lagrangian};
use crate::numerics::scratch::{Buffer, NODE};
use crate::scalar::Scalar;

/// Largest polynomial degree accepted (equispaced Lagrange bases stay well conditioned).
pub const MAX_DEGREE: usize = 10;

/// The Galerkin rule `P_s` with a quadrature rule.
///
/// ```
/// use marsden::discrete::rules::Galerkin;
/// use marsden::{Rule, Problem, Initial, TimeGrid, SolveOptions, systems::Pendulum};
///
/// let gauss3 = Galerkin::gauss(3)?; // P3 with 3 Gauss points: order 6
/// assert_eq!(gauss3.order(), 6);
/// let problem = Problem::new(Pendulum::default(), Initial::velocity(&[1.5], &[0.0]), TimeGrid::new(0.0, 0.1, 100)?)?;
/// let run = problem.solve(&gauss3, &SolveOptions::default())?;
/// assert!((run.q(run.len() - 1)[0] + 1.054049155334075).abs() < 1e-11); // R6
/// assert!(Galerkin::new(3, marsden::discrete::rules::QuadratureFamily::Gauss, 2).is_err()); // too few points
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Galerkin {
    table: Arc<GalerkinTable>,
}

/// Basis values at the quadrature nodes, shared by the discrete Lagrangian and forces.
#[derive(Debug, Clone, PartialEq)]
pub struct GalerkinTable {
    /// Polynomial degree `s`.
    pub degree: usize,
    /// The quadrature rule.
    pub quadrature: Quadrature,
    /// `ℓ_j(c_i)` for `j = 0 … s`, row-major (node `i`, point `j`).
    pub value: Vec<f64>,
    /// `ℓ_j'(c_i)` for `j = 0 … s`, row-major.
    pub slope: Vec<f64>,
}

impl Galerkin {
    /// `P_degree` with `points` nodes of `family`.
    ///
    /// # Errors
    /// [`crate::error::InputError::InvalidGalerkin`] if `degree ∉ 1..=MAX_DEGREE` or
    /// `points < degree`; [`crate::error::InputError::InvalidQuadrature`] if the family has no
    /// rule with `points` nodes.
    pub fn new(degree: usize, family: QuadratureFamily, points: usize) -> Result<Self, Error> {
        let invalid = |reason: String| {
            Error::Input(InputError::InvalidGalerkin {
                degree,
                family: family.name(),
                points,
                reason,
                max_degree: MAX_DEGREE,
            })
        };
        if !(1..=MAX_DEGREE).contains(&degree) {
            return Err(invalid(format!("the degree must be in 1..={MAX_DEGREE}")));
        }
        if points < degree {
            return Err(invalid(format!(
                "{points} quadrature points are too few for degree {degree} (the kinetic \
                 energy's quadrature would be degenerate; use at least {degree})"
            )));
        }
        let quadrature = Quadrature::new(family, points)?;
        Ok(Self {
            table: Arc::new(GalerkinTable::new(degree, quadrature)),
        })
    }

    /// `gauss-s`: `P_s` with `s` Gauss points, the `s`-stage Gauss method (order `2s`).
    pub fn gauss(s: usize) -> Result<Self, Error> {
        Self::new(s, QuadratureFamily::Gauss, s)
    }

    /// `lobatto-s`: `P_{s−1}` with `s` Lobatto points, Lobatto IIIA–IIIB (order `2s − 2`).
    pub fn lobatto(s: usize) -> Result<Self, Error> {
        if s < 2 {
            return Err(Error::Input(InputError::InvalidQuadrature {
                family: "lobatto",
                points: s,
                valid: format!("2 ≤ s ≤ {}", MAX_DEGREE + 1),
            }));
        }
        Self::new(s - 1, QuadratureFamily::Lobatto, s)
    }

    /// The basis table (degree, quadrature, basis values).
    pub fn table(&self) -> &GalerkinTable {
        &self.table
    }

    /// Polynomial degree `s`.
    pub fn degree(&self) -> usize {
        self.table.degree
    }
}

impl GalerkinTable {
    fn new(degree: usize, quadrature: Quadrature) -> Self {
        let times: Vec<f64> = (0..=degree).map(|j| j as f64 / degree as f64).collect();
        let mut value = Vec::with_capacity(quadrature.points() * (degree + 1));
        let mut slope = Vec::with_capacity(value.capacity());
        for &c in &quadrature.nodes {
            for j in 0..=degree {
                value.push(lagrange(&times, j, c));
                slope.push(lagrange_slope(&times, j, c));
            }
        }
        Self {
            degree,
            quadrature,
            value,
            slope,
        }
    }

    /// Classical order: `min(2s, quadrature order)` ([OBS15]).
    ///
    /// [OBS15]: crate#references
    pub fn order(&self) -> u32 {
        let quadrature_order = self.quadrature.exact_degree() + 1;
        (2 * self.degree).min(quadrature_order) as u32
    }

    /// Calls `f(i, t_i, q(c_i h), q̇(c_i h))` at every quadrature node, from `q₀` and the offsets.
    #[inline]
    fn for_each_node<S: Scalar>(
        &self,
        t0: f64,
        h: f64,
        q0: &[S],
        offsets: &[S],
        mut f: impl FnMut(usize, S, &[S], &[S]),
    ) {
        let (n, s1) = (q0.len(), self.degree + 1);
        let zero = S::from(0.0);
        for (i, &c) in self.quadrature.nodes.iter().enumerate() {
            let (ell, slope) = (&self.value[i * s1..], &self.slope[i * s1..]);
            let position = |a: usize| {
                let mut x = q0[a];
                for j in 1..s1 {
                    x += offsets[(j - 1) * n + a] * ell[j];
                }
                x
            };
            let velocity = |a: usize| {
                let mut v = zero;
                for j in 1..s1 {
                    v += offsets[(j - 1) * n + a] * slope[j];
                }
                v / h
            };
            let mut q = Buffer::<S, NODE>::empty();
            let q = q.from_fn(n, zero, position);
            let mut v = Buffer::<S, NODE>::empty();
            let v = v.from_fn(n, zero, velocity);
            f(i, S::from(t0 + c * h), q, v);
        }
    }
}

/// `ℓ_j(τ) = Π_{m≠j} (τ − d_m)/(d_j − d_m)`.
fn lagrange(d: &[f64], j: usize, tau: f64) -> f64 {
    (0..d.len())
        .filter(|&m| m != j)
        .map(|m| (tau - d[m]) / (d[j] - d[m]))
        .product()
}

/// `ℓ_j'(τ) = Σ_{k≠j} 1/(d_j − d_k) Π_{m≠j,k} (τ − d_m)/(d_j − d_m)`.
fn lagrange_slope(d: &[f64], j: usize, tau: f64) -> f64 {
    (0..d.len())
        .filter(|&k| k != j)
        .map(|k| {
            let rest: f64 = (0..d.len())
                .filter(|&m| m != j && m != k)
                .map(|m| (tau - d[m]) / (d[j] - d[m]))
                .product();
            rest / (d[j] - d[k])
        })
        .sum()
}

/// The Galerkin discrete action of a Lagrangian (built by [`Galerkin`]).
#[derive(Debug, Clone)]
pub struct GalerkinLd<L> {
    /// The continuous Lagrangian.
    pub lagrangian: L,
    table: Arc<GalerkinTable>,
}

impl<L: Lagrangian> DiscreteAction for GalerkinLd<L> {
    const FIXED_DOF: Option<usize> = L::FIXED_DOF;
    fn dof(&self) -> usize {
        self.lagrangian.dof()
    }
    fn internal_stages(&self) -> usize {
        self.table.degree - 1
    }
    #[inline]
    fn action<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], offsets: &[S]) -> S {
        let mut sum = S::from(0.0);
        let weights = &self.table.quadrature.weights;
        self.table.for_each_node(t0, h, q0, offsets, |i, t, q, v| {
            sum += self.lagrangian.lagrangian(t, q, v) * weights[i];
        });
        sum * h
    }

    /// Lobatto IIIA–IIIB with constraints ([Jay96]; [HLW06] §VII.1): `φ` at every interior
    /// Lobatto node `q(c_i h)`, with one multiplier each, keeps the order `2s − 2`. Other
    /// quadratures (Gauss) are refused above degree 1: with the constraint at the step ends only
    /// the constraint force is discretised at order 2 (SPARK stage constraints are not
    /// implemented).
    ///
    /// [Jay96]: crate#references
    /// [HLW06]: crate#references
    fn constrained_stages(&self) -> Result<usize, String> {
        let (s, q) = (self.table.degree, &self.table.quadrature);
        if s == 1 {
            return Ok(0);
        }
        match q.family {
            QuadratureFamily::Lobatto if q.points() == s + 1 => Ok(q.points() - 2),
            QuadratureFamily::Gauss if q.points() == s => Err(format!(
                "gauss-{s} has no stage constraints here (SPARK methods are not implemented): \
                 with the constraint at the step end only a constrained run has order 2, not \
                 {}; use lobatto-{} (constrained Lobatto IIIA–IIIB, order {}) instead",
                2 * s,
                s + 1,
                2 * s
            )),
            family => Err(format!(
                "galerkin-{s}-{}-{} has no stage constraints; use lobatto-{} (constrained \
                 Lobatto IIIA–IIIB, order {})",
                family.name(),
                q.points(),
                s + 1,
                2 * s
            )),
        }
    }

    /// `q(c_{i+1} h) = Q₀ + Σ_{j≥1} ℓ_j(c_{i+1}) Δ_j` at the interior node `c_{i+1}`.
    fn stage_point<S: Scalar>(&self, i: usize, q0: &[S], offsets: &[S], out: &mut [S]) {
        let (n, s1) = (q0.len(), self.table.degree + 1);
        let ell = &self.table.value[(i + 1) * s1..(i + 2) * s1];
        for (a, x) in out.iter_mut().enumerate() {
            let mut sum = q0[a];
            for (j, &w) in ell.iter().enumerate().skip(1) {
                sum += offsets[(j - 1) * n + a] * w;
            }
            *x = sum;
        }
    }

    /// The last quadrature weight (`½` for degree 1).
    fn end_weight(&self) -> f64 {
        match (self.table.degree, self.table.quadrature.family) {
            (1, _) | (_, QuadratureFamily::Gauss) => 0.5,
            _ => self.table.quadrature.weights.last().copied().unwrap_or(0.5),
        }
    }
}

/// Discrete forces of a Galerkin rule: `f_j = h Σ_i b_i ℓ_j(c_i) f(c_i)` on every control point.
#[derive(Debug, Clone)]
pub struct GalerkinForce<F> {
    /// The continuous force.
    pub force: F,
    /// Degrees of freedom.
    pub dof: usize,
    table: Arc<GalerkinTable>,
}

impl<F: Force> DiscreteForce for GalerkinForce<F> {
    #[inline]
    fn discrete_force<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], offsets: &[S], out: &mut [S]) {
        let (n, s1) = (self.dof, self.table.degree + 1);
        let zero = S::from(0.0);
        out[..s1 * n].iter_mut().for_each(|o| *o = zero);
        let table = &*self.table;
        table.for_each_node(t0, h, q0, offsets, |i, t, q, v| {
            let mut f = Buffer::<S, NODE>::empty();
            let f = f.filled(n, zero);
            self.force.force(t, q, v, f);
            let b = table.quadrature.weights[i] * h;
            for j in 0..s1 {
                let w = b * table.value[i * s1 + j];
                for a in 0..n {
                    out[j * n + a] += f[a] * w;
                }
            }
        });
    }
    fn is_active(&self) -> bool {
        self.force.is_active()
    }
}

impl Rule for Galerkin {
    type Discrete<L: Lagrangian> = GalerkinLd<L>;
    type DiscreteForce<F: Force> = GalerkinForce<F>;
    fn discretize<L: Lagrangian>(&self, lagrangian: L) -> GalerkinLd<L> {
        GalerkinLd {
            lagrangian,
            table: Arc::clone(&self.table),
        }
    }
    fn discretize_force<F: Force>(&self, force: F, dof: usize) -> GalerkinForce<F> {
        GalerkinForce {
            force,
            dof,
            table: Arc::clone(&self.table),
        }
    }
    /// `gauss-s`, `lobatto-s` for the two classical families, else `galerkin-s-<family>-r`.
    fn name(&self) -> String {
        let (s, q) = (self.table.degree, &self.table.quadrature);
        match q.family {
            QuadratureFamily::Gauss if q.points() == s => format!("gauss-{s}"),
            QuadratureFamily::Lobatto if q.points() == s + 1 => format!("lobatto-{}", s + 1),
            family => format!("galerkin-{s}-{}-{}", family.name(), q.points()),
        }
    }
    fn order(&self) -> u32 {
        self.table.order()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn basis_is_a_partition_of_unity() {
        let g = Galerkin::new(5, QuadratureFamily::Lobatto, 7).unwrap();
        let t = g.table();
        for i in 0..t.quadrature.points() {
            let row = &t.value[i * 6..(i + 1) * 6];
            let slope = &t.slope[i * 6..(i + 1) * 6];
            assert!((row.iter().sum::<f64>() - 1.0).abs() < 1e-14);
            assert!(slope.iter().sum::<f64>().abs() < 1e-12);
        }
    }

    #[test]
    fn names_orders_and_rejections() {
        assert_eq!(Galerkin::gauss(2).unwrap().name(), "gauss-2");
        assert_eq!(Galerkin::lobatto(3).unwrap().name(), "lobatto-3");
        assert_eq!(Galerkin::lobatto(3).unwrap().order(), 4);
        let g = Galerkin::new(2, QuadratureFamily::Gauss, 3).unwrap();
        assert_eq!((g.name().as_str(), g.order()), ("galerkin-2-gauss-3", 4));
        assert!(matches!(
            Galerkin::new(4, QuadratureFamily::Gauss, 3),
            Err(Error::Input(InputError::InvalidGalerkin { .. }))
        ));
        assert!(Galerkin::new(0, QuadratureFamily::Gauss, 3).is_err());
        assert!(Galerkin::lobatto(1).is_err());
    }
}
