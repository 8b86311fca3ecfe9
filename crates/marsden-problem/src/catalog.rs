//! The catalog systems of `marsden::systems` as problem files name them (`builtin = "…"`):
//! names, coordinates, parameters with their documented defaults, and the Lagrangian written
//! in the expression language (so `marsden systems` shows text a user can copy into
//! `lagrangian = "…"`).
//!
//! Defaults are read from the core types' `Default` impls, never repeated here.

use marsden::mechanics::Structure;
use marsden::mechanics::kernel::VerletKernel;
use marsden::numerics::banded::Banded;
use marsden::systems::{
    DoublePendulum, FreeFall, HarmonicOscillator, HenonHeiles, Kepler, NBody, Pendulum,
};
use marsden::{Lagrangian, Scalar};

/// A catalog system, by name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Builtin {
    /// `harmonic_oscillator`: [`HarmonicOscillator`].
    HarmonicOscillator,
    /// `free_fall`: [`FreeFall`].
    FreeFall,
    /// `pendulum`: [`Pendulum`].
    Pendulum,
    /// `double_pendulum`: [`DoublePendulum`].
    DoublePendulum,
    /// `kepler`: [`Kepler`].
    Kepler,
    /// `henon_heiles`: [`HenonHeiles`].
    HenonHeiles,
    /// `nbody`: [`NBody`].
    NBody,
}

/// A scalar parameter of a builtin: name, default, meaning.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Parameter {
    /// Name in `parameters = { … }`.
    pub name: &'static str,
    /// The catalog default.
    pub default: f64,
    /// What it is.
    pub doc: &'static str,
}

/// The list parameter of `nbody`.
pub const MASSES: &str = "masses";

impl Builtin {
    /// Every catalog system, in the order `marsden systems` lists them.
    pub const ALL: [Builtin; 7] = [
        Builtin::HarmonicOscillator,
        Builtin::FreeFall,
        Builtin::Pendulum,
        Builtin::DoublePendulum,
        Builtin::Kepler,
        Builtin::HenonHeiles,
        Builtin::NBody,
    ];

    /// The name used in problem files.
    pub fn name(self) -> &'static str {
        match self {
            Builtin::HarmonicOscillator => "harmonic_oscillator",
            Builtin::FreeFall => "free_fall",
            Builtin::Pendulum => "pendulum",
            Builtin::DoublePendulum => "double_pendulum",
            Builtin::Kepler => "kepler",
            Builtin::HenonHeiles => "henon_heiles",
            Builtin::NBody => "nbody",
        }
    }

    /// Looks a name up.
    pub fn from_name(name: &str) -> Option<Builtin> {
        Self::ALL.into_iter().find(|b| b.name() == name)
    }

    /// One line on what the system is.
    pub fn summary(self) -> &'static str {
        match self {
            Builtin::HarmonicOscillator => "harmonic oscillator (exact solution known)",
            Builtin::FreeFall => "free fall in a uniform field (variational integrators are exact)",
            Builtin::Pendulum => "planar pendulum, angle from the downward vertical",
            Builtin::DoublePendulum => "planar double pendulum, both angles from the vertical",
            Builtin::Kepler => "planar Kepler problem, unit mass",
            Builtin::HenonHeiles => "Hénon–Heiles potential",
            Builtin::NBody => "gravitational N-body problem in 3-D with Plummer softening",
        }
    }

    /// The Lagrangian in the expression language (for `nbody`, in words).
    pub fn formula(self) -> &'static str {
        match self {
            Builtin::HarmonicOscillator => "0.5*m*x_dot^2 - 0.5*k*x^2",
            Builtin::FreeFall => "0.5*m*z_dot^2 - m*g*z",
            Builtin::Pendulum => "0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)",
            Builtin::DoublePendulum => {
                "0.5*(m1+m2)*l1^2*theta1_dot^2 + 0.5*m2*l2^2*theta2_dot^2 \
                 + m2*l1*l2*theta1_dot*theta2_dot*cos(theta1-theta2) \
                 + (m1+m2)*g*l1*cos(theta1) + m2*g*l2*cos(theta2)"
            }
            Builtin::Kepler => "0.5*(x_dot^2 + y_dot^2) + mu/sqrt(x^2 + y^2)",
            Builtin::HenonHeiles => {
                "0.5*(x_dot^2 + y_dot^2) - 0.5*(x^2 + y^2) - lambda*(x^2*y - y^3/3)"
            }
            Builtin::NBody => {
                "sum_i 0.5*m_i*|v_i|^2 + sum_{i<j} G*m_i*m_j/sqrt(|q_i - q_j|^2 + softening^2)"
            }
        }
    }

    /// The scalar parameters with their defaults (`nbody` also needs the list `masses`).
    pub fn parameters(self) -> Vec<Parameter> {
        let p = |name, default, doc| Parameter { name, default, doc };
        match self {
            Builtin::HarmonicOscillator => {
                let d = HarmonicOscillator::default();
                vec![p("m", d.m, "mass"), p("k", d.k, "stiffness")]
            }
            Builtin::FreeFall => {
                let d = FreeFall::default();
                vec![p("m", d.m, "mass"), p("g", d.g, "field strength")]
            }
            Builtin::Pendulum => {
                let d = Pendulum::default();
                let (m, l, g) = (d.m, d.l, d.g);
                vec![
                    p("m", m, "bob mass"),
                    p("l", l, "rod length"),
                    p("g", g, "gravity"),
                ]
            }
            Builtin::DoublePendulum => {
                let d = DoublePendulum::default();
                vec![
                    p("m1", d.m1, "upper mass"),
                    p("m2", d.m2, "lower mass"),
                    p("l1", d.l1, "upper rod length"),
                    p("l2", d.l2, "lower rod length"),
                    p("g", d.g, "gravity"),
                ]
            }
            Builtin::Kepler => vec![p("mu", Kepler::default().mu, "gravitational parameter")],
            Builtin::HenonHeiles => {
                vec![p("lambda", HenonHeiles::default().lambda, "cubic coupling")]
            }
            Builtin::NBody => {
                let d = NBody::new(Vec::new());
                vec![
                    p("G", d.g, "gravitational constant"),
                    p("softening", d.softening, "Plummer softening length"),
                ]
            }
        }
    }

    /// Whether the system needs the list parameter `masses` (one mass per body).
    pub fn needs_masses(self) -> bool {
        self == Builtin::NBody
    }

    /// Coordinate names (`nbody`: `x1 y1 z1 x2 …` for `bodies` bodies; ignored otherwise).
    pub fn coordinates(self, bodies: usize) -> Vec<String> {
        let names: &[&str] = match self {
            Builtin::HarmonicOscillator => &["x"],
            Builtin::FreeFall => &["z"],
            Builtin::Pendulum => &["theta"],
            Builtin::DoublePendulum => &["theta1", "theta2"],
            Builtin::Kepler | Builtin::HenonHeiles => &["x", "y"],
            Builtin::NBody => {
                return (1..=bodies)
                    .flat_map(|i| ["x", "y", "z"].map(|axis| format!("{axis}{i}")))
                    .collect();
            }
        };
        names.iter().map(|s| s.to_string()).collect()
    }

    /// The configured system from the values of [`Builtin::parameters`] (in that order) and,
    /// for `nbody`, the masses.
    pub fn build(self, values: &[f64], masses: Vec<f64>) -> BuiltinSystem {
        let v = |i: usize| values.get(i).copied().unwrap_or(f64::NAN);
        match self {
            Builtin::HarmonicOscillator => {
                BuiltinSystem::HarmonicOscillator(HarmonicOscillator { m: v(0), k: v(1) })
            }
            Builtin::FreeFall => BuiltinSystem::FreeFall(FreeFall { m: v(0), g: v(1) }),
            Builtin::Pendulum => BuiltinSystem::Pendulum(Pendulum {
                m: v(0),
                l: v(1),
                g: v(2),
            }),
            Builtin::DoublePendulum => BuiltinSystem::DoublePendulum(DoublePendulum {
                m1: v(0),
                m2: v(1),
                l1: v(2),
                l2: v(3),
                g: v(4),
            }),
            Builtin::Kepler => BuiltinSystem::Kepler(Kepler { mu: v(0) }),
            Builtin::HenonHeiles => BuiltinSystem::HenonHeiles(HenonHeiles { lambda: v(0) }),
            Builtin::NBody => BuiltinSystem::NBody(NBody {
                masses,
                g: v(0),
                softening: v(1),
            }),
        }
    }
}

/// A catalog system with its parameters set.
#[derive(Debug, Clone, PartialEq)]
pub enum BuiltinSystem {
    /// See [`HarmonicOscillator`].
    HarmonicOscillator(HarmonicOscillator),
    /// See [`FreeFall`].
    FreeFall(FreeFall),
    /// See [`Pendulum`].
    Pendulum(Pendulum),
    /// See [`DoublePendulum`].
    DoublePendulum(DoublePendulum),
    /// See [`Kepler`].
    Kepler(Kepler),
    /// See [`HenonHeiles`].
    HenonHeiles(HenonHeiles),
    /// See [`NBody`].
    NBody(NBody),
}

/// `$body` with `$s` bound to the system inside `$self`, whichever it is.
macro_rules! each {
    ($self:expr, $s:ident => $body:expr) => {
        match $self {
            BuiltinSystem::HarmonicOscillator($s) => $body,
            BuiltinSystem::FreeFall($s) => $body,
            BuiltinSystem::Pendulum($s) => $body,
            BuiltinSystem::DoublePendulum($s) => $body,
            BuiltinSystem::Kepler($s) => $body,
            BuiltinSystem::HenonHeiles($s) => $body,
            BuiltinSystem::NBody($s) => $body,
        }
    };
}

/// Every catalog system as one Lagrangian type, forwarding each call to the system it holds:
/// the same numbers as the system itself, at the cost of a branch per call and of what the
/// optimiser no longer sees across it. For computations that cost far more than that per
/// evaluation of `L` (`method = "exact"`'s shooting), so that they are compiled once for the
/// catalog instead of once per system (`marsden_engine::ExactRun`).
impl Lagrangian for BuiltinSystem {
    #[inline]
    fn dof(&self) -> usize {
        each!(self, s => s.dof())
    }

    // Always inlined: the shooting evaluates `L` at dual numbers thousands of times per step,
    // and a call per evaluation cost `exact` a further 4 % (BENCHMARKS.md).
    #[inline(always)]
    fn lagrangian<S: Scalar>(&self, t: S, q: &[S], v: &[S]) -> S {
        each!(self, s => s.lagrangian(t, q, v))
    }

    #[inline]
    fn structure(&self) -> Structure {
        each!(self, s => s.structure())
    }

    #[inline]
    fn potential_gradient(&self, t: f64, q: &[f64], grad: &mut [f64], scratch: &mut Vec<f64>) {
        each!(self, s => s.potential_gradient(t, q, grad, scratch))
    }

    #[inline]
    fn potential_bandwidth(&self) -> Option<usize> {
        each!(self, s => s.potential_bandwidth())
    }

    #[inline]
    fn potential_hessian(&self, t: f64, q: &[f64], hess: &mut Banded) {
        each!(self, s => s.potential_hessian(t, q, hess))
    }

    #[inline]
    fn potential_hessian_packed(&self, t: f64, q: &[f64], packed: &mut [f64]) -> bool {
        each!(self, s => s.potential_hessian_packed(t, q, packed))
    }

    #[inline]
    fn verlet_kernel(&self) -> Option<&dyn VerletKernel> {
        each!(self, s => s.verlet_kernel())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{ExprLagrangian, slots};
    use marsden_expr::{Program, Symbols};

    /// `L` at a fixed, generic state.
    fn sample<L: Lagrangian>(l: &L) -> f64 {
        let n = l.dof();
        let q: Vec<f64> = (0..n).map(|i| 0.3 + 0.2 * i as f64).collect();
        let v: Vec<f64> = (0..n).map(|i| -0.7 + 0.3 * i as f64).collect();
        l.lagrangian(0.0, &q, &v)
    }

    #[test]
    fn formulas_are_the_catalog_lagrangians() {
        for b in Builtin::ALL.into_iter().filter(|b| !b.needs_masses()) {
            let params = b.parameters();
            let values: Vec<f64> = params.iter().map(|p| p.default * 1.3).collect();
            let system = b.build(&values, Vec::new());
            let rust = each!(&system, s => sample(s));
            let coordinates = b.coordinates(0);
            let mut symbols = Symbols::with_inputs(slots::tangent_inputs(&coordinates)).unwrap();
            for (p, v) in params.iter().zip(&values) {
                symbols.add_constant(p.name, *v).unwrap();
            }
            let program = Program::compile(b.formula(), &symbols).unwrap();
            let expr = sample(&ExprLagrangian::new(program, coordinates.len()));
            assert!(
                (rust - expr).abs() <= 1e-14 * rust.abs().max(1.0),
                "{}",
                b.name()
            );
        }
    }

    /// What [`probe`] finds: the degrees of freedom, the values, the structure, the
    /// bandwidth, and whether a packed Hessian and a Verlet kernel exist.
    type Probed = (usize, Vec<f64>, String, Option<usize>, [bool; 2]);

    /// Everything the integrators ask of a Lagrangian, at a fixed state.
    fn probe<L: Lagrangian>(l: &L) -> Probed {
        let n = l.dof();
        let q: Vec<f64> = (0..n).map(|i| 0.3 + 0.2 * i as f64).collect();
        let v: Vec<f64> = (0..n).map(|i| -0.7 + 0.3 * i as f64).collect();
        let mut values = vec![l.lagrangian(0.4, &q, &v)];
        let mut grad = vec![0.0; n];
        l.potential_gradient(0.4, &q, &mut grad, &mut Vec::new());
        values.extend(grad);
        let mut hess = Banded::new(n, l.potential_bandwidth().unwrap_or(n));
        l.potential_hessian(0.4, &q, &mut hess);
        values.extend(
            (0..n)
                .flat_map(|i| hess.columns(i).map(move |j| (i, j)))
                .map(|(i, j)| hess.get(i, j)),
        );
        let mut packed = vec![0.0; n * (n + 1) / 2];
        let has_packed = l.potential_hessian_packed(0.4, &q, &mut packed);
        values.extend(packed);
        let structure = format!("{:?}", l.structure());
        let kernel = l.verlet_kernel().is_some();
        (
            n,
            values,
            structure,
            l.potential_bandwidth(),
            [has_packed, kernel],
        )
    }

    /// The shared catalog type answers every call as the system it holds does, bit for bit
    /// (the `exact` runs of every catalog system go through it).
    #[test]
    fn the_shared_catalog_type_forwards_every_call_to_its_system() {
        for b in Builtin::ALL {
            let values: Vec<f64> = b.parameters().iter().map(|p| p.default * 1.3).collect();
            let masses = if b.needs_masses() {
                vec![1.0, 2.5]
            } else {
                Vec::new()
            };
            let system = b.build(&values, masses);
            let own = each!(&system, s => probe(s));
            let shared = probe(&system);
            assert_eq!(own.0, shared.0, "{}", b.name());
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&own.1), bits(&shared.1), "{}", b.name());
            assert!(own.1.iter().all(|x| x.is_finite()), "{}", b.name());
            assert_eq!((own.2, own.3, own.4), (shared.2, shared.3, shared.4));
        }
    }

    #[test]
    fn names_round_trip_and_nbody_coordinates() {
        for b in Builtin::ALL {
            assert_eq!(Builtin::from_name(b.name()), Some(b));
        }
        assert_eq!(
            Builtin::NBody.coordinates(2),
            ["x1", "y1", "z1", "x2", "y2", "z2"]
        );
    }
}
