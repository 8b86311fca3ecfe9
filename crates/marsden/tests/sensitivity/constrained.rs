//! Sensitivities of constrained runs: the spherical pendulum as a Cartesian particle on
//! `|q| = 1` (SHAKE + RATTLE), with the midpoint rule and constrained Lobatto IIIA–IIIB
//! (`lobatto-3`, order 4). The tangent map is checked against central differences of whole runs
//! started from initial data projected back onto `T*N`, for tangency of the propagated vectors,
//! for symplecticity restricted to `T*N` (R17) and against the adjoint; with a damping force
//! (Lagrange–d'Alembert) against central differences and for tangency.
//!
//! For `L = ½|v|² − z` and `φ = ½(|q|² − 1)` the cotangent bundle is `q·q = 1`, `q·p = 0`; its
//! tangent vectors at `(q, p)` are the `(δq, δp)` with `q·δq = 0` and `δq·p + q·δp = 0`.

use super::common::relative_distance;
use crate::common::tight;
use marsden::analysis::certificate::DifferentiableStep;
use marsden::discrete::rules::Galerkin;
use marsden::forces::LinearDamping;
use marsden::holonomic::Rattle;
use marsden::sensitivity::{AdjointOptions, SensitiveStep, TangentOptions, adjoint, tangent};
use marsden::systems::SphericalPendulum;
use marsden::{DiscreteAction, Initial, Integrator, Midpoint, NoForce, Rule, State, TimeGrid};

type Constrained<A, F = NoForce> =
    Integrator<A, F, SphericalPendulum, Rattle<SphericalPendulum, SphericalPendulum>>;

fn pendulum() -> SphericalPendulum {
    SphericalPendulum::default()
}

/// A tightly converged SHAKE + RATTLE integrator of the spherical pendulum under `rule`.
fn constrained<R: Rule>(rule: &R) -> Constrained<R::Discrete<SphericalPendulum>>
where
    R::Discrete<SphericalPendulum>: DiscreteAction,
{
    let p = pendulum();
    Integrator::new(rule.discretize(p))
        .with_constraint(p)
        .with_projection(Rattle::new(p, p).with_options(tight()))
        .with_options(tight())
        .unwrap()
}

/// The spherical pendulum with anisotropic linear damping `f = −diag(0.1, 0.05, 0.02) v`
/// (Lagrange–d'Alembert; the constraint force stays normal, the damping need not be tangent).
fn damped<R: Rule>(
    rule: &R,
) -> Constrained<R::Discrete<SphericalPendulum>, R::DiscreteForce<LinearDamping>> {
    let p = pendulum();
    let damping = LinearDamping::diagonal(&[0.1, 0.05, 0.02]).unwrap();
    Integrator::new(rule.discretize(p))
        .with_force(rule.discretize_force(damping, 3))
        .with_constraint(p)
        .with_projection(Rattle::new(p, p).with_options(tight()))
        .with_options(tight())
        .unwrap()
}

/// `(q, p)` projected onto `T*N` by the crate's projection of initial data.
fn projected(q: &[f64], p: &[f64]) -> State {
    let s = pendulum();
    match Initial::momentum(q, p).project_onto(&s, &s, 0.0).unwrap() {
        Initial::Momentum { q, p } => State { t: 0.0, q, p },
        Initial::Velocity { .. } => unreachable!("a momentum stays a momentum"),
    }
}

/// θ = 1, ϕ = 0, θ̇ = 0.3, ϕ̇ = 0.8 (a non-planar quasi-periodic orbit), on `T*N`.
fn start() -> State {
    let s = pendulum();
    let (Initial::Velocity { q, v } | Initial::Momentum { q, p: v }) =
        s.initial(1.0, 0.0, 0.3, 0.8);
    projected(&q, &v)
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Four tangent vectors of `T*N` at `x` (columns of a 6 × 4 matrix, stored as vectors): two
/// position directions `δq ⊥ q` with `δp` fixed by `δq·p + q·δp = 0`, two momentum directions
/// `δp ⊥ q`.
fn tangent_basis(x: &State) -> Vec<Vec<f64>> {
    let (q, p) = (&x.q, &x.p);
    let perp = |w: [f64; 3]| -> Vec<f64> {
        let c = dot(&w, q) / dot(q, q);
        (0..3).map(|i| w[i] - c * q[i]).collect()
    };
    let mut basis = Vec::new();
    for (dq, w) in [
        (perp([0.3, 1.0, -0.2]), [0.1, -0.4, 0.7]),
        (perp([-0.5, 0.2, 0.9]), [0.6, 0.3, -0.1]),
    ] {
        // δp = w⊥ − q (δq·p)/|q|²: then q·δp = −δq·p.
        let c = dot(&dq, p) / dot(q, q);
        let dp: Vec<f64> = perp(w).iter().zip(q).map(|(a, b)| a - c * b).collect();
        basis.push(dq.iter().chain(&dp).copied().collect());
    }
    for w in [[1.0, -0.3, 0.2], [0.2, 0.8, 0.5]] {
        basis.push([0.0; 3].iter().chain(&perp(w)).copied().collect());
    }
    basis
}

/// `S u` for the 6 × 6 Jacobian `s` (row-major).
fn apply(s: &[f64], u: &[f64]) -> Vec<f64> {
    (0..6).map(|r| dot(&s[r * 6..(r + 1) * 6], u)).collect()
}

/// The final `(q, p)` of a run of `stepper` from `x`.
fn run<D: SensitiveStep>(mut stepper: D, mut x: State, grid: &TimeGrid) -> Vec<f64> {
    for k in 0..grid.steps {
        stepper.step(&mut x, grid.h).unwrap();
        x.t = grid.time(k + 1);
    }
    x.q.iter().chain(&x.p).copied().collect()
}

/// `(x_K(P(x₀ + εu)) − x_K(P(x₀ − εu)))/2ε` with `P` the projection onto `T*N`.
fn central_difference<D: SensitiveStep>(
    make: &impl Fn() -> D,
    x0: &State,
    u: &[f64],
    grid: &TimeGrid,
    eps: f64,
) -> Vec<f64> {
    let shifted = |sign: f64| {
        let q: Vec<f64> = (0..3).map(|i| x0.q[i] + sign * eps * u[i]).collect();
        let p: Vec<f64> = (0..3).map(|i| x0.p[i] + sign * eps * u[3 + i]).collect();
        run(make(), projected(&q, &p), grid)
    };
    let (plus, minus) = (shifted(1.0), shifted(-1.0));
    plus.iter()
        .zip(&minus)
        .map(|(a, b)| (a - b) / (2.0 * eps))
        .collect()
}

fn check_finite_differences<D: SensitiveStep>(name: &str, make: impl Fn() -> D) {
    let (x0, grid) = (start(), TimeGrid::new(0.0, 0.01, 1000).unwrap());
    let run = tangent(&mut make(), x0.clone(), &grid, &TangentOptions::default()).unwrap();
    let (mut exact, mut fd) = (Vec::new(), Vec::new());
    for u in tangent_basis(&x0) {
        exact.extend(apply(&run.jacobian, &u));
        fd.extend(central_difference(&make, &x0, &u, &grid, 1e-5));
    }
    let d = relative_distance(&exact, &fd);
    println!("{name}: tangent map vs projected central differences over 1000 steps: {d:.2e}");
    assert!(d <= 1e-6, "{name}: relative distance {d:e}");
}

#[test]
fn spherical_pendulum_midpoint_tangent_map_matches_projected_central_differences() {
    check_finite_differences("midpoint", || constrained(&Midpoint));
}

#[test]
fn spherical_pendulum_lobatto3_tangent_map_matches_projected_central_differences() {
    check_finite_differences("lobatto-3", || constrained(&Galerkin::lobatto(3).unwrap()));
}

#[test]
fn damped_spherical_pendulum_tangent_map_matches_projected_central_differences() {
    check_finite_differences("damped, midpoint", || damped(&Midpoint));
    check_finite_differences("damped, lobatto-3", || {
        damped(&Galerkin::lobatto(3).unwrap())
    });
}

/// The largest relative defect of tangency to `T*N` of the propagated basis vectors over a run:
/// `|q·δq| / (|q||δq|)` and `|δq·p + q·δp| / (|δq||p| + |q||δp|)`.
fn tangency_defect<D: SensitiveStep>(stepper: &mut D, steps: usize) -> (f64, f64) {
    let (x0, grid) = (start(), TimeGrid::new(0.0, 0.01, steps).unwrap());
    let basis = tangent_basis(&x0);
    let run = tangent(stepper, x0, &grid, &TangentOptions { every: 1 }).unwrap();
    let norm = |a: &[f64]| dot(a, a).sqrt();
    let (mut position, mut hidden) = (0.0_f64, 0.0_f64);
    for sample in &run.samples {
        let (q, p) = (&sample.state.q, &sample.state.p);
        for u in &basis {
            let su = apply(&sample.jacobian, u);
            let (dq, dp) = su.split_at(3);
            position = position.max(dot(q, dq).abs() / (norm(q) * norm(dq)));
            let scale = norm(dq) * norm(p) + norm(q) * norm(dp);
            hidden = hidden.max((dot(dq, p) + dot(q, dp)).abs() / scale);
        }
    }
    (position, hidden)
}

#[test]
fn spherical_pendulum_propagated_vectors_stay_tangent_to_cotangent_bundle() {
    for (name, (position, hidden)) in [
        (
            "midpoint",
            tangency_defect(&mut constrained(&Midpoint), 1000),
        ),
        (
            "lobatto-3",
            tangency_defect(&mut constrained(&Galerkin::lobatto(3).unwrap()), 1000),
        ),
        (
            "damped, midpoint",
            tangency_defect(&mut damped(&Midpoint), 1000),
        ),
        (
            "damped, lobatto-3",
            tangency_defect(&mut damped(&Galerkin::lobatto(3).unwrap()), 1000),
        ),
    ] {
        println!(
            "{name}: max relative Dφ δq = {position:.2e}, δ(hidden constraint) = {hidden:.2e}"
        );
        assert!(position <= 1e-10, "{name}: Dφ δq = {position:e}");
        assert!(hidden <= 1e-10, "{name}: δ(q·p) = {hidden:e}");
    }
}

/// `ω(u, w) = u_q·w_p − u_p·w_q`.
fn omega(u: &[f64], w: &[f64]) -> f64 {
    dot(&u[..3], &w[3..]) - dot(&u[3..], &w[..3])
}

/// R17 (symplecticity), restricted to `T*N`: `ω(S u, S w) = ω(u, w)` for all pairs of the
/// tangent basis after `10⁴` steps, to `1e-10` absolutely and relative to `|Su||Sw|`, the size
/// of the terms whose difference `ω` is (round-off accumulates on that scale).
fn check_symplectic_on_cotangent_bundle<D: SensitiveStep>(name: &str, stepper: &mut D) {
    let (x0, grid) = (start(), TimeGrid::new(0.0, 0.01, 10_000).unwrap());
    let basis = tangent_basis(&x0);
    let run = tangent(stepper, x0, &grid, &TangentOptions::default()).unwrap();
    let images: Vec<Vec<f64>> = basis.iter().map(|u| apply(&run.jacobian, u)).collect();
    let norm = |a: &[f64]| dot(a, a).sqrt();
    let (mut absolute, mut relative, mut largest) = (0.0_f64, 0.0_f64, 0.0_f64);
    for i in 0..basis.len() {
        for j in i + 1..basis.len() {
            let defect = (omega(&images[i], &images[j]) - omega(&basis[i], &basis[j])).abs();
            let scale = norm(&images[i]) * norm(&images[j]);
            absolute = absolute.max(defect);
            relative = relative.max(defect / scale);
            largest = largest.max(scale);
        }
    }
    println!(
        "{name}: 1e4 steps, max |ω(Su, Sw) − ω(u, w)| = {absolute:.2e}, relative to |Su||Sw| \
         {relative:.2e}, max |Su||Sw| = {largest:.2e}"
    );
    assert!(absolute <= 1e-10, "{name}: defect {absolute:e}");
    assert!(relative <= 1e-10, "{name}: relative defect {relative:e}");
}

#[test]
fn spherical_pendulum_midpoint_tangent_map_symplectic_on_cotangent_bundle_r17() {
    check_symplectic_on_cotangent_bundle("midpoint", &mut constrained(&Midpoint));
}

#[test]
fn spherical_pendulum_lobatto3_tangent_map_symplectic_on_cotangent_bundle_r17() {
    let rule = Galerkin::lobatto(3).unwrap();
    check_symplectic_on_cotangent_bundle("lobatto-3", &mut constrained(&rule));
}

/// The loss cotangent of sample k: ℓ_k = Σ_i w_i x_i²/2 on every 5th step.
fn cotangent(k: usize, x: &State, out: &mut [f64]) {
    if k.is_multiple_of(5) {
        for (i, o) in out.iter_mut().enumerate() {
            let xi = if i < 3 { x.q[i] } else { x.p[i - 3] };
            *o += (1.0 + 0.1 * i as f64) * xi;
        }
    }
}

#[test]
fn spherical_pendulum_adjoint_gradient_matches_forward_to_1e10() {
    let grid = TimeGrid::new(0.0, 0.01, 2000).unwrap();
    for (name, rule) in [
        ("midpoint", None),
        ("lobatto-3", Some(Galerkin::lobatto(3).unwrap())),
    ] {
        let make = || match &rule {
            None => StepperKind::Midpoint(constrained(&Midpoint)),
            Some(r) => StepperKind::Lobatto(constrained(r)),
        };
        let forward = {
            let run = tangent(&mut make(), start(), &grid, &TangentOptions { every: 1 }).unwrap();
            let mut g = vec![0.0; 6];
            let mut cot = vec![0.0; 6];
            for sample in &run.samples {
                cot.fill(0.0);
                cotangent(sample.step, &sample.state, &mut cot);
                for (c, gc) in g.iter_mut().enumerate() {
                    *gc += (0..6)
                        .map(|r| cot[r] * sample.jacobian[r * 6 + c])
                        .sum::<f64>();
                }
            }
            g
        };
        for every in [0, 1, 64] {
            let options = AdjointOptions {
                checkpoint_every: every,
            };
            let reverse = adjoint(&mut make(), start(), &grid, cotangent, &options).unwrap();
            let d = relative_distance(&reverse.gradient, &forward);
            println!("{name}, checkpoint every {every}: forward vs adjoint {d:.2e}");
            assert!(d <= 1e-10, "{name}, every {every}: {d:e}");
        }
    }
}

/// Either constrained integrator, so one loop covers both rules.
#[derive(Clone)]
enum StepperKind {
    Midpoint(Constrained<<Midpoint as Rule>::Discrete<SphericalPendulum>>),
    Lobatto(Constrained<<Galerkin as Rule>::Discrete<SphericalPendulum>>),
}

impl DifferentiableStep for StepperKind {
    fn dof(&self) -> usize {
        3
    }
    fn step(&mut self, state: &mut State, h: f64) -> Result<marsden::StepReport, marsden::Error> {
        match self {
            Self::Midpoint(i) => DifferentiableStep::step(i, state, h),
            Self::Lobatto(i) => DifferentiableStep::step(i, state, h),
        }
    }
    fn step_with_jacobian(
        &mut self,
        state: &mut State,
        h: f64,
        jac: &mut [f64],
    ) -> Result<marsden::StepReport, marsden::Error> {
        self.step_with_sensitivity(state, h, jac)
    }
}

impl SensitiveStep for StepperKind {
    fn step_with_sensitivity(
        &mut self,
        state: &mut State,
        h: f64,
        jac: &mut [f64],
    ) -> Result<marsden::StepReport, marsden::Error> {
        match self {
            Self::Midpoint(i) => i.step_with_sensitivity(state, h, jac),
            Self::Lobatto(i) => i.step_with_sensitivity(state, h, jac),
        }
    }
}
