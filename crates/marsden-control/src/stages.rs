//! How a rule's step sees the controls: one value per step, or one per stage.
//!
//! A two-point rule (midpoint, trapezoid, the α rules) samples the force at fixed points of the
//! step, and the controls are piecewise constant: `u_k` on `[t_k, t_{k+1}]` ([OJM11] §3). A
//! Galerkin rule (`gauss-s`, `lobatto-s`) samples the force and the running cost at its
//! quadrature nodes `c_i`; it takes **one control value per node**, `u_{k,i}` at
//! `t_k + c_i h`, so that the discrete problem is the symplectic partitioned Runge–Kutta
//! discretisation of [OJM11] §4.2 with control stages, whose adjoint is the same method and whose
//! optimum converges with the rule's own order (Sanz-Serna 2016 §4; Hager, *Runge–Kutta methods
//! in optimal control and the transformed adjoint system*, Numer. Math. 87 (2000)). Piecewise
//! constant controls would cap the order at 2: the best step function is `O(h)` from a smooth
//! control in `L²`, and the cost is quadratic in that error.
//!
//! The transcription feeds the controls to the rule's own quadrature as an extra coordinate
//! `u` of the augmented configuration `(q, u)`, with control points `U_0 … U_s` at the rule's
//! control-point times `d_j`: `U_j = P(d_j)`, `P` the polynomial of degree `σ − 1` through
//! `(c_i, u_{k,i})`. The Galerkin polynomial of degree `s ≥ σ − 1` through the `U_j` is `P`
//! itself, so node `i` sees `u_{k,i}` (to round-off) and its velocity is never used. A rule
//! with more nodes than control points (`galerkin-s-gauss-r`, `r > s + 1`) takes its values at
//! the control points instead (`σ = s + 1`, `U_j = u_{k,j}`).
//!
//! A composition keeps one value per step: its substeps of negative length would weigh their
//! own control's cost negatively (the quadratic program would not be convex). Its optimum
//! converges at order 2, whatever the scheme's order.
//!
//! [OJM11]: crate#references

use marsden::discrete::rules::{
    BaseMethod, Composition, Galerkin, GeneralizedMidpoint, Method, Midpoint, SymmetrizedMidpoint,
    Trapezoid,
};

/// The controls of one step of a rule.
#[derive(Debug, Clone, PartialEq)]
pub struct ControlStages {
    /// `c_i ∈ [0, 1]`: where in the step each control value acts (`σ` of them; `[0]` for one
    /// value per step, which acts on the whole step).
    pub times: Vec<f64>,
    /// `d_j`: the fractions of the step at the step's control points `Q_0 … Q_s` (`d_0 = 0`,
    /// `d_s = 1`; a composition's inner points may lie outside `[0, 1]`).
    pub points: Vec<f64>,
    /// `U_j = Σ_i to_points[j σ + i] u_{k,i}`: the control-point values of the augmented
    /// coordinate `u`, row-major (`points.len()` rows, `σ` columns).
    pub to_points: Vec<f64>,
}

impl ControlStages {
    /// One value per step, constant over it, for a step with control points at `points`.
    pub fn constant(points: Vec<f64>) -> Self {
        let to_points = vec![1.0; points.len()];
        Self {
            times: vec![0.0],
            points,
            to_points,
        }
    }

    /// One value per time of `times`, interpolated by a polynomial of degree `σ − 1` and read
    /// at `points`.
    pub fn interpolating(times: Vec<f64>, points: Vec<f64>) -> Self {
        let to_points = points
            .iter()
            .flat_map(|&d| (0..times.len()).map(move |i| (d, i)))
            .map(|(d, i)| lagrange(&times, i, d))
            .collect();
        Self {
            times,
            points,
            to_points,
        }
    }

    /// `σ`: control values per step.
    pub fn count(&self) -> usize {
        self.times.len()
    }

    /// Internal control points per step (`s − 1`).
    pub fn inner(&self) -> usize {
        self.points.len().saturating_sub(2)
    }

    /// The weights `ℓ_i(τ)` of the stage values at the fraction `τ` of the step: the control
    /// between the stages, as the transcription's quadrature sees it (constant for `σ = 1`).
    pub fn weights_at(&self, tau: f64, out: &mut [f64]) {
        for (i, w) in out.iter_mut().enumerate().take(self.times.len()) {
            *w = lagrange(&self.times, i, tau);
        }
    }
}

/// Where a step's path inequalities are imposed, and how the state there is read off the
/// step's control points `Q_0 … Q_s` ([`ControlStages::path_points`]).
#[derive(Debug, Clone, PartialEq)]
pub struct PathPoints {
    /// The fractions `τ_i` of the step (one per control value: the value `u_{k,i}` acts there).
    pub times: Vec<f64>,
    /// `q(τ_i) = Σ_j position[i (s+1) + j] Q_j`, row-major.
    pub position: Vec<f64>,
    /// `q̇(τ_i) = Σ_j rate[i (s+1) + j] Q_j / h`, row-major.
    pub rate: Vec<f64>,
}

impl ControlStages {
    /// The points where the path inequalities `g(t, q, q̇, u) ≤ 0` are imposed: one per
    /// control value. For one value per step, the step's midpoint with the secant
    /// `q = (q_k + q_{k+1})/2`, `q̇ = (q_{k+1} − q_k)/h` — the midpoint rule's own state, and
    /// a composition's inner points (which may lie outside the step) left out; for stage
    /// values `u_{k,i}`, the node `c_i` with the rule's polynomial through its control points
    /// (`q(c_i)`, `q̇(c_i)` of the Galerkin curve, [OJM11] §4.2).
    ///
    /// [OJM11]: crate#references
    pub fn path_points(&self) -> PathPoints {
        let points = self.points.len();
        if self.count() == 1 {
            let mut position = vec![0.0; points];
            let mut rate = vec![0.0; points];
            (position[0], position[points - 1]) = (0.5, 0.5);
            (rate[0], rate[points - 1]) = (-1.0, 1.0);
            return PathPoints {
                times: vec![0.5],
                position,
                rate,
            };
        }
        let at = |weight: fn(&[f64], usize, f64) -> f64| {
            (self.times.iter())
                .flat_map(|&c| (0..points).map(move |j| (c, j)))
                .map(|(c, j)| weight(&self.points, j, c))
                .collect()
        };
        PathPoints {
            times: self.times.clone(),
            position: at(lagrange),
            rate: at(lagrange_derivative),
        }
    }
}

/// `ℓ_i'(τ) = Σ_{m≠i} 1/(c_i − c_m) Π_{l≠i,m} (τ − c_l)/(c_i − c_l)`.
fn lagrange_derivative(c: &[f64], i: usize, tau: f64) -> f64 {
    (0..c.len())
        .filter(|&m| m != i)
        .map(|m| {
            let rest: f64 = (0..c.len())
                .filter(|&l| l != i && l != m)
                .map(|l| (tau - c[l]) / (c[i] - c[l]))
                .product();
            rest / (c[i] - c[m])
        })
        .sum()
}

/// `ℓ_i(τ) = Π_{m≠i} (τ − c_m)/(c_i − c_m)` (1 for a single node).
fn lagrange(c: &[f64], i: usize, tau: f64) -> f64 {
    (0..c.len())
        .filter(|&m| m != i)
        .map(|m| (tau - c[m]) / (c[i] - c[m]))
        .product()
}

/// A rule the transcription can take: how its steps see the controls.
pub trait StagedControls {
    /// The controls of one step.
    fn control_stages(&self) -> ControlStages;
}

/// The two-point rules: one value per step.
macro_rules! two_point {
    ($($rule:ty),*) => {$(
        impl StagedControls for $rule {
            fn control_stages(&self) -> ControlStages {
                ControlStages::constant(vec![0.0, 1.0])
            }
        }
    )*};
}

two_point!(
    Midpoint,
    Trapezoid,
    GeneralizedMidpoint,
    SymmetrizedMidpoint
);

impl StagedControls for Galerkin {
    /// One value per quadrature node (see the module's documentation).
    fn control_stages(&self) -> ControlStages {
        let table = self.table();
        let s = table.degree;
        let points: Vec<f64> = (0..=s).map(|j| j as f64 / s as f64).collect();
        let nodes = &table.quadrature.nodes;
        match nodes.len() <= s + 1 {
            true => ControlStages::interpolating(nodes.clone(), points),
            false => ControlStages::interpolating(points.clone(), points),
        }
    }
}

/// The control-point fractions of a composition with substeps `gammas` of a base whose own
/// points are `base`.
fn composed_points(gammas: &[f64], base: &[f64]) -> Vec<f64> {
    let mut points = vec![0.0];
    let mut start = 0.0;
    for &g in gammas {
        points.extend(base.iter().skip(1).map(|d| start + g * d));
        start += g;
    }
    points
}

impl<R: StagedControls + marsden::Rule> StagedControls for Composition<R> {
    /// One value per step (see the module's documentation).
    fn control_stages(&self) -> ControlStages {
        let base = self.base.control_stages();
        ControlStages::constant(composed_points(self.coefficients(), &base.points))
    }
}

impl StagedControls for BaseMethod {
    fn control_stages(&self) -> ControlStages {
        match self {
            BaseMethod::Galerkin(g) => g.control_stages(),
            _ => ControlStages::constant(vec![0.0, 1.0]),
        }
    }
}

impl StagedControls for Method {
    fn control_stages(&self) -> ControlStages {
        match self {
            Method::Single(base) => base.control_stages(),
            Method::Composed(scheme, base) => ControlStages::constant(composed_points(
                &scheme.coefficients(),
                &base.control_stages().points,
            )),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use marsden::discrete::rules::CompositionScheme;

    #[test]
    fn stage_values_are_read_back_at_the_nodes() {
        // gauss-2: P of degree 1 through the two nodes, read at d = 0, ½, 1.
        let g = Galerkin::gauss(2).unwrap().control_stages();
        assert_eq!((g.count(), g.inner()), (2, 1));
        let u = [0.3, -1.1];
        let at = |j: usize| (0..2).map(|i| g.to_points[j * 2 + i] * u[i]).sum::<f64>();
        let slope = (u[1] - u[0]) / (g.times[1] - g.times[0]);
        for (j, &d) in g.points.iter().enumerate() {
            assert!((at(j) - (u[0] + slope * (d - g.times[0]))).abs() < 1e-14);
        }
        let mut w = [0.0; 2];
        g.weights_at(g.times[1], &mut w);
        assert!((w[0]).abs() < 1e-15 && (w[1] - 1.0).abs() < 1e-15);
    }

    #[test]
    fn path_points_read_a_polynomial_and_its_derivative() {
        // gauss-2 reads q(c_i), q̇(c_i) of the quadratic through its three control points:
        // exact for q(τ) = 1 + 2τ − 3τ².
        let g = Galerkin::gauss(2).unwrap().control_stages().path_points();
        let q = |t: f64| 1.0 + 2.0 * t - 3.0 * t * t;
        let points = [0.0, 0.5, 1.0].map(q);
        for (i, &c) in g.times.iter().enumerate() {
            let row = |w: &[f64]| (0..3).map(|j| w[i * 3 + j] * points[j]).sum::<f64>();
            assert!((row(&g.position) - q(c)).abs() < 1e-14);
            assert!((row(&g.rate) - (2.0 - 6.0 * c)).abs() < 1e-13);
        }
        // One value per step: the secant at the midpoint, inner points of a composition unused.
        let c = Composition::new(Midpoint, CompositionScheme::TripleJump { order: 4 });
        let p = c.control_stages().path_points();
        assert_eq!(p.times, [0.5]);
        assert_eq!(p.position, [0.5, 0.0, 0.0, 0.5]);
        assert_eq!(p.rate, [-1.0, 0.0, 0.0, 1.0]);
    }

    #[test]
    fn compositions_keep_one_value_and_place_their_points() {
        let c = Composition::new(Midpoint, CompositionScheme::TripleJump { order: 4 });
        let s = c.control_stages();
        assert_eq!((s.count(), s.inner()), (1, 2));
        let g = c.coefficients();
        assert!((s.points[1] - g[0]).abs() < 1e-15);
        assert!((s.points[3] - 1.0).abs() < 1e-14);
        let m = Method::parse("triple-jump-4(midpoint)").unwrap();
        assert_eq!(m.control_stages(), s);
    }
}
