//! Stage 1: the problem file as written — serde structs mirroring the TOML, nothing checked
//! beyond types and key names (`deny_unknown_fields` everywhere).
//!
//! Every field is optional here so that [`super::spec`] can say what is missing in its own
//! words; values carry their byte span ([`Spanned`]) so that every later message can point at
//! the value at fault. The schema is a contract: extend it, never rename.
//!
//! ```toml
//! [system]
//! name = "pendulum"
//! coordinates = ["theta"]
//! parameters = { m = 1.0, l = 1.0, g = 1.0 }
//! lagrangian = "0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)"   # or builtin = "pendulum"
//! forces = ["-c*theta_dot"]                                  # optional
//! constraints = ["x^2 + y^2 - l^2"]                          # optional
//! [[system.symmetry]]                                        # optional, repeatable
//! name = "Lz"
//! generator = ["-y", "x"]                                  # or rotation = "z" (translation = "x")
//! [initial]
//! q = [1.5]
//! v = [0.0]                  # or p = [...]
//! t0 = 0.0                   # extension: initial time (default 0)
//! project = false            # with constraints: project (q, v) onto the manifold first
//! [integrator]
//! method = "midpoint"
//! h = 0.05
//! steps = 100000             # or t_end = ...
//! tolerance = 1e-12
//! max_iterations = 50
//! fast_paths = true          # false: the general Newton path (the reference)
//! compensated = false        # true: compensated summation of the update (long high-order runs)
//! [output]
//! dir = "out/pendulum"
//! format = "csv"
//! every = 1
//! plots = true
//! [sensitivity]              # optional: ∂(q, p)/∂(q₀, p₀, parameters) along the run
//! initial = true
//! parameters = ["l"]
//! [sweep]                    # optional: an ensemble of runs
//! parameter = "l"            # or initial = "q[0]"
//! values = [0.5, 1.0]        # or range = { start = 0.1, stop = 1.0, count = 10 }
//! ```

use std::fmt;
use std::marker::PhantomData;

use serde::Deserialize;
use serde::de::{self, Deserializer, MapAccess, SeqAccess, Visitor};
use toml::Spanned;

use super::raw_multibody::{
    BodyOrUnknown, NamedBodyInitial, RawBody, RawDamper, RawJoint, RawParticle, RawSpring,
};

/// A list of spanned values, itself spanned.
pub type SpannedList<T> = Spanned<Vec<Spanned<T>>>;

/// The whole problem file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawProblem {
    /// `[system]`: what is simulated.
    pub system: Option<Spanned<RawSystem>>,
    /// `[initial]`: the initial state.
    pub initial: Option<Spanned<RawInitial>>,
    /// `[integrator]`: method, step, length of the run, Newton options.
    pub integrator: Option<Spanned<RawIntegrator>>,
    /// `[output]`: where and how results are written.
    pub output: Option<Spanned<RawOutput>>,
    /// `[sweep]`: one parameter or initial value over a list of values (an ensemble of runs).
    pub sweep: Option<Spanned<RawSweep>>,
    /// `[analysis]`: what is monitored besides the stored rows.
    pub analysis: Option<Spanned<RawAnalysis>>,
    /// `[sensitivity]`: the Jacobian of the run with respect to its initial state and
    /// parameters.
    pub sensitivity: Option<Spanned<RawSensitivity>>,
    /// `[optimal_control]`: a DMOC problem, solved by `marsden optimize`
    /// ([`super::optimal_control`]).
    pub optimal_control: Option<Spanned<super::optimal_control::raw::RawOptimalControl>>,
    /// `[[events]]`: zero crossings of expressions of the state, recorded or ending the run
    /// ([`super::events`]).
    pub events: Option<Vec<Spanned<super::events::RawEvent>>>,
}

/// `[sweep]`: what is swept (`parameter` or `initial`) and over what (`values` or `range`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSweep {
    /// A scalar parameter of `[system] parameters` (or a builtin's default).
    pub parameter: Option<Spanned<String>>,
    /// An initial value: `q[i]`, `v[i]` or `p[i]`.
    pub initial: Option<Spanned<String>>,
    /// The values, as a list (numbers or constant expressions).
    #[serde(default, deserialize_with = "super::number::spanned_list")]
    pub values: Option<SpannedList<f64>>,
    /// The values, evenly spaced from `start` to `stop` (both included).
    pub range: Option<Spanned<RawRange>>,
    /// `[sweep.and]`: a further axis; the members are every combination (a grid).
    pub and: Option<Box<Spanned<RawSweep>>>,
}

/// `range = { start = 0.1, stop = 1.0, count = 10 }`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawRange {
    /// First value (a number or a constant expression).
    #[serde(default, deserialize_with = "super::number::spanned")]
    pub start: Option<Spanned<f64>>,
    /// Last value (included).
    #[serde(default, deserialize_with = "super::number::spanned")]
    pub stop: Option<Spanned<f64>>,
    /// Number of values (at least 1).
    pub count: Option<Spanned<i64>>,
}

/// `[system]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSystem {
    /// A name for the run (default: the builtin's name or the file's stem).
    pub name: Option<Spanned<String>>,
    /// Names of the coordinates `q`; velocities are `<name>_dot`.
    pub coordinates: Option<SpannedList<String>>,
    /// Parameters: numbers usable in every expression, or overrides of a builtin's defaults.
    pub parameters: Option<Spanned<Ordered<Spanned<RawParameter>>>>,
    /// The Lagrangian `L(q, q_dot, t)` as an expression.
    pub lagrangian: Option<Spanned<String>>,
    /// The Hamiltonian `H(q, p, t)` (reserved: not supported yet).
    pub hamiltonian: Option<Spanned<String>>,
    /// A catalog system instead of an expression.
    pub builtin: Option<Spanned<String>>,
    /// A discrete Lagrangian `L_d(q₀, q₁, h, t)` written with `<q>_0`, `<q>_1`, `h`, `t`: the
    /// researcher's own method, instead of a continuous `L` and a rule.
    pub discrete_lagrangian: Option<Spanned<String>>,
    /// Generalised forces, one expression per coordinate.
    pub forces: Option<SpannedList<String>>,
    /// Holonomic constraints `φ(q) = 0`, one expression each.
    pub constraints: Option<SpannedList<String>>,
    /// Names of controls `u`, piecewise constant per step, usable in `forces`
    /// ([`super::optimal_control`]); zero in a `marsden run`.
    pub controls: Option<SpannedList<String>>,
    /// A table of the controls per step (`t` and one column per control), read by
    /// `marsden run` ([`super::control_table`]); without it the controls are zero.
    pub control_table: Option<Spanned<String>>,
    /// Symmetries whose momentum maps are monitored.
    pub symmetry: Option<Vec<Spanned<RawSymmetry>>>,
    /// A rigid body instead of coordinates: its configuration is an attitude `R ∈ SO(3)`
    /// (and a centre of mass `x ∈ ℝ³` with `mass`), stepped by the Lie group variational
    /// integrator ([`super::rigid`]).
    pub rigid_body: Option<Spanned<RawRigidBody>>,
    /// A rigid body's potential `U` in `R11 … R33`, `x`, `y`, `z`, `t` and the parameters.
    pub potential: Option<Spanned<String>>,
    /// A rigid body's external torque in the body frame, three expressions like `potential`'s.
    pub torques: Option<SpannedList<String>>,
    /// A multibody system's uniform gravitational field, acting on every body's mass.
    pub gravity: Option<SpannedList<f64>>,
    /// A multibody system's bodies ([`super::raw_multibody`]).
    pub body: Option<Vec<Spanned<RawBody>>>,
    /// A multibody system's particles (point masses).
    pub particle: Option<Vec<Spanned<RawParticle>>>,
    /// A multibody system's joints.
    pub joint: Option<Vec<Spanned<RawJoint>>>,
    /// A multibody system's springs between body points.
    pub spring: Option<Vec<Spanned<RawSpring>>>,
    /// A multibody system's dampers between body points.
    pub damper: Option<Vec<Spanned<RawDamper>>>,
}

/// `rigid_body = { inertia = [..], mass = m }`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawRigidBody {
    /// The principal moments `[J1, J2, J3]` (body axes) or the symmetric 3×3 inertia tensor,
    /// about the fixed point (or the centre of mass of a body with `mass`).
    pub inertia: Option<Spanned<RawInertia>>,
    /// The mass of a free body, whose centre of mass `x ∈ ℝ³` moves too (absent: the body turns
    /// about a fixed point).
    pub mass: Option<Spanned<f64>>,
}

/// An inertia as written: three principal moments or a 3×3 matrix (rows).
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub enum RawInertia {
    /// `[J1, J2, J3]`.
    Principal(Vec<f64>),
    /// `[[J11, J12, J13], [J21, J22, J23], [J31, J32, J33]]`.
    Matrix(Vec<Vec<f64>>),
}

/// One `[[system.symmetry]]` entry.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSymmetry {
    /// Name of the momentum map (the column is `J_<name>`).
    pub name: Option<Spanned<String>>,
    /// The infinitesimal generator `ξ_Q(q)`, one expression per coordinate.
    pub generator: Option<SpannedList<String>>,
    /// A named translation instead of `generator`: `"x"`, `"y"` or `"z"`
    /// ([`super::named_symmetry`]).
    pub translation: Option<Spanned<String>>,
    /// A named rotation about an axis instead of `generator`: `"x"`, `"y"` or `"z"` (for a
    /// rigid body: a rotation in space, whose momentum map is the spatial angular momentum).
    pub rotation: Option<Spanned<String>>,
    /// A rigid body only: a rotation about a body axis, `"x"`, `"y"` or `"z"` (the right
    /// action; its momentum map is that component of the body momentum `Π`).
    pub body_rotation: Option<Spanned<String>>,
}

/// `[initial]` (deserialized by hand: its own keys, then `[initial.<body>]` tables of a
/// multibody file, [`super::raw_multibody`]).
#[derive(Debug, Default)]
pub struct RawInitial {
    /// Initial time (extension; default 0).
    pub t0: Option<Spanned<f64>>,
    /// Positions.
    pub q: Option<SpannedList<f64>>,
    /// Velocities (exactly one of `v` and `p`).
    pub v: Option<SpannedList<f64>>,
    /// Momenta (exactly one of `v` and `p`).
    pub p: Option<SpannedList<f64>>,
    /// `nbody` only: masses, positions and velocities from a file in the benchmark format
    /// (`N`, then `m x y z vx vy vz` per body), relative to the problem file.
    pub file: Option<Spanned<String>>,
    /// Project `(q, v)` or `(q, p)` onto the constraint manifold before the run (default
    /// false: initial data off the constraints are an error).
    pub project: Option<bool>,
    /// A rigid body's initial attitude as a rotation vector (axis times angle).
    pub rotation_vector: Option<SpannedList<f64>>,
    /// A rigid body's initial attitude as a matrix (rows; body → space).
    pub r: Option<Spanned<Vec<Vec<f64>>>>,
    /// A rigid body's initial attitude as a unit quaternion `[w, x, y, z]`.
    pub quaternion: Option<SpannedList<f64>>,
    /// A rigid body's initial angular velocity in the body frame.
    pub omega: Option<SpannedList<f64>>,
    /// A rigid body's initial angular momentum in the body frame, `Π = JΩ`.
    pub pi: Option<SpannedList<f64>>,
    /// A multibody system's `[initial.<body>]` tables, in the file's order.
    pub bodies: Vec<NamedBodyInitial>,
}

/// The keys of `[initial]` itself (besides the body tables).
const INITIAL_KEYS: &[&str] = &[
    "t0",
    "q",
    "v",
    "p",
    "file",
    "project",
    "rotation_vector",
    "R",
    "quaternion",
    "Omega",
    "Pi",
];

impl<'de> Deserialize<'de> for RawInitial {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_map(InitialVisitor)
    }
}

/// The visitor of `[initial]`: its keys, and any other key as a body's table.
struct InitialVisitor;

impl<'de> serde::de::Visitor<'de> for InitialVisitor {
    type Value = RawInitial;

    fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("the table [initial]")
    }

    fn visit_map<A: serde::de::MapAccess<'de>>(self, mut map: A) -> Result<RawInitial, A::Error> {
        let mut out = RawInitial::default();
        while let Some(key) = map.next_key::<String>()? {
            match key.as_str() {
                // Numbers or constant expressions ([`super::number`]).
                "t0" => out.t0 = Some(super::number::unwrap(map.next_value()?)),
                "q" => out.q = Some(super::number::list(map.next_value()?)),
                "v" => out.v = Some(super::number::list(map.next_value()?)),
                "p" => out.p = Some(super::number::list(map.next_value()?)),
                "file" => out.file = Some(map.next_value()?),
                "project" => out.project = Some(map.next_value()?),
                "rotation_vector" => out.rotation_vector = Some(map.next_value()?),
                "R" => out.r = Some(map.next_value()?),
                "quaternion" => out.quaternion = Some(map.next_value()?),
                "Omega" => out.omega = Some(map.next_value()?),
                "Pi" => out.pi = Some(map.next_value()?),
                _ => {
                    let seed = BodyOrUnknown {
                        key: &key,
                        known: INITIAL_KEYS,
                    };
                    let data = map.next_value_seed(seed)?;
                    out.bodies.push(NamedBodyInitial { name: key, data });
                }
            }
        }
        Ok(out)
    }
}

/// `[integrator]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawIntegrator {
    /// Method name (default `midpoint`).
    pub method: Option<Spanned<String>>,
    /// Time step (a number or a constant expression, [`super::number`]).
    #[serde(default, deserialize_with = "super::number::spanned")]
    pub h: Option<Spanned<f64>>,
    /// Number of steps (exactly one of `steps` and `t_end`).
    pub steps: Option<Spanned<i64>>,
    /// Final time (exactly one of `steps` and `t_end`; a number or a constant expression).
    #[serde(default, deserialize_with = "super::number::spanned")]
    pub t_end: Option<Spanned<f64>>,
    /// Newton residual tolerance (default 1e-12; a number or a constant expression).
    #[serde(default, deserialize_with = "super::number::spanned")]
    pub tolerance: Option<Spanned<f64>>,
    /// Newton iterations per step (default 50).
    pub max_iterations: Option<Spanned<i64>>,
    /// Structure-aware fast paths where they apply (default true); `false` takes the general
    /// Newton path, the reference they are tested against.
    pub fast_paths: Option<Spanned<bool>>,
    /// Compensated summation of each step's increments (default false; unconstrained
    /// problems only).
    pub compensated: Option<Spanned<bool>>,
}

/// `[output]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawOutput {
    /// Output directory (default `out/<name>`), relative to the working directory.
    pub dir: Option<Spanned<String>>,
    /// `csv` (default) or `npy`.
    pub format: Option<Spanned<String>>,
    /// Store every k-th step (default 1).
    pub every: Option<Spanned<i64>>,
    /// Save a checkpoint of the run every this many steps (none by default).
    pub checkpoint_every: Option<Spanned<i64>>,
    /// Times at which to sample the state, between grid points too (numbers or constant
    /// expressions, [`super::sampled_times`]).
    #[serde(default, deserialize_with = "super::number::spanned_list")]
    pub times: Option<SpannedList<f64>>,
    /// Reach each of `times` inside a step by a step of its own size (default false: read off
    /// the step's interpolant).
    pub exact_times: Option<Spanned<bool>>,
    /// Draw PNG plots (default true).
    pub plots: Option<Spanned<bool>>,
    /// Coordinates that are angles: plots show them wrapped to (−π, π].
    pub angles: Option<SpannedList<String>>,
    /// Named expressions of `(t, q, v, p)` written as columns after the state
    /// ([`super::events`]).
    pub observables: Option<Spanned<super::events::RawObservables>>,
    /// The axes of the Poincaré section plot of the recorded events: two of the coordinates,
    /// velocities and momenta.
    pub section: Option<SpannedList<String>>,
}

/// A parameter value: a number, or a list of numbers (N-body masses).
#[derive(Debug, Clone, PartialEq)]
pub enum RawParameter {
    /// `m = 1.0` (integers are accepted).
    Number(f64),
    /// `masses = [1.0, 1e-3]`.
    List(Vec<f64>),
}

impl<'de> Deserialize<'de> for RawParameter {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(ParameterVisitor)
    }
}

struct ParameterVisitor;

impl<'de> Visitor<'de> for ParameterVisitor {
    type Value = RawParameter;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a number, a constant expression such as \"2*pi\", or a list of them")
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<RawParameter, E> {
        Ok(RawParameter::Number(v))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<RawParameter, E> {
        Ok(RawParameter::Number(v as f64))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<RawParameter, E> {
        Ok(RawParameter::Number(v as f64))
    }

    /// `l = "2*pi"`: a constant expression ([`super::number`]).
    fn visit_str<E: de::Error>(self, v: &str) -> Result<RawParameter, E> {
        super::number::constant(v)
            .map(RawParameter::Number)
            .map_err(E::custom)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<RawParameter, A::Error> {
        let mut values = Vec::new();
        while let Some(v) = seq.next_element::<super::number::Number>()? {
            values.push(v.0);
        }
        Ok(RawParameter::List(values))
    }
}

/// A TOML table read in the file's order (so parameters are listed as written).
#[derive(Debug, Clone, PartialEq)]
pub struct Ordered<T>(pub Vec<(String, T)>);

impl<'de, T: Deserialize<'de>> Deserialize<'de> for Ordered<T> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_map(OrderedVisitor(PhantomData))
    }
}

struct OrderedVisitor<T>(PhantomData<T>);

impl<'de, T: Deserialize<'de>> Visitor<'de> for OrderedVisitor<T> {
    type Value = Ordered<T>;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a table")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Ordered<T>, A::Error> {
        let mut entries = Vec::new();
        while let Some(entry) = map.next_entry::<String, T>()? {
            entries.push(entry);
        }
        Ok(Ordered(entries))
    }
}

/// Parses the text of a problem file (types and key names only).
///
/// # Errors
/// `toml`'s error, with the span of the offending key or value.
pub fn parse(text: &str) -> Result<RawProblem, toml::de::Error> {
    toml::from_str(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_the_issue_schema_with_spans() {
        let text = r#"
[system]
coordinates = ["theta"]
parameters = { m = 1, masses = [1.0, 2] }
lagrangian = "0.5*theta_dot^2"
[[system.symmetry]]
name = "Lz"
generator = ["0"]
[initial]
q = [1.5]
v = [0.0]
[integrator]
h = 0.05
steps = 10
"#;
        let raw = parse(text).unwrap();
        let system = raw.system.unwrap().into_inner();
        let params = system.parameters.unwrap().into_inner().0;
        assert_eq!(params[0].0, "m");
        assert_eq!(*params[0].1.get_ref(), RawParameter::Number(1.0));
        assert_eq!(params[1].0, "masses");
        assert_eq!(*params[1].1.get_ref(), RawParameter::List(vec![1.0, 2.0]));
        let h = raw.integrator.unwrap().into_inner().h.unwrap();
        assert_eq!(&text[h.span()], "0.05");
        assert_eq!(system.symmetry.unwrap().len(), 1);
    }

    #[test]
    fn rejects_unknown_keys() {
        let err = parse("[system]\nlagrangain = \"x\"\n").unwrap_err();
        assert!(
            err.message().contains("unknown field `lagrangain`"),
            "{err}"
        );
        let err = parse("[output]\nplot = true\n").unwrap_err();
        assert!(err.message().contains("unknown field `plot`"), "{err}");
    }
}

/// `[analysis]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawAnalysis {
    /// Monitor energy, momentum maps and constraint residuals at every step, not only at the
    /// stored rows (default false).
    pub every_step: Option<Spanned<bool>>,
    /// Certificates: the symplecticity defect of the step map at the start and the end, and
    /// the equivariance defect of `L_d` for each symmetry (default false).
    pub certify: Option<Spanned<bool>>,
}

/// `[sensitivity]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSensitivity {
    /// Differentiate with respect to the initial state `(q₀, p₀)` (default false).
    pub initial: Option<Spanned<bool>>,
    /// Differentiate with respect to these scalar parameters.
    pub parameters: Option<SpannedList<String>>,
}
