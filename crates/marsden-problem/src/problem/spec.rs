//! Stage 2: the validated run specification. Everything here has been checked (lengths,
//! finiteness, ranges, names, compiled expressions), so building the problem cannot fail on
//! the file's account except for what only the core can judge (regularity of `L` at the
//! initial state), which [`SpecSpans`] lets the command point at.

use std::ops::Range;
use std::path::PathBuf;

use marsden::{Initial, NewtonOptions, TimeGrid};

use super::method::Method;
use super::multibody::MultibodySpec;
use super::rigid::{RigidInitial, RigidSpec};
use crate::catalog::{Builtin, BuiltinSystem};
use crate::model::{
    ExprConstraint, ExprDiscreteLagrangian, ExprForce, ExprLagrangian, HamiltonianExprLagrangian,
    Symmetry,
};
use crate::source::SourceFile;

/// Command-line overrides of the file's values (`marsden run --steps --h --out`).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Overrides {
    /// Replaces `steps` (and `t_end`).
    pub steps: Option<u64>,
    /// Replaces `h`; with `t_end` in the file, the number of steps follows.
    pub h: Option<f64>,
    /// Replaces `[output] dir`.
    pub out: Option<PathBuf>,
    /// Replaces `[output] checkpoint_every` (`marsden run --checkpoint-every`).
    pub checkpoint_every: Option<u64>,
    /// Replaces `[output] every` (Python's `solve(every=…)`).
    pub every: Option<u64>,
}

/// A validated problem file, ready to run.
#[derive(Debug, Clone)]
pub struct RunSpec {
    /// The file it came from.
    pub source: SourceFile,
    /// The command-line values that changed it.
    pub overrides: Overrides,
    /// The run's name (`[system] name`, else the builtin's name, else the file's stem).
    pub name: String,
    /// What is simulated.
    pub system: SystemSpec,
    /// The initial state.
    pub initial: InitialSpec,
    /// Method, grid and Newton options.
    pub integrator: IntegratorSpec,
    /// Where and how results go.
    pub output: OutputSpec,
    /// Spans of values the core may still reject.
    pub spans: SpecSpans,
    /// `[sweep]`: the ensemble to run instead of a single run (`None` for a plain file and
    /// for each member of a sweep).
    pub sweep: Option<super::SweepSpec>,
    /// `[analysis]`.
    pub analysis: AnalysisSpec,
    /// `[sensitivity]`: the derivatives computed beside the run (`None`: none).
    pub sensitivity: Option<super::SensitivitySpec>,
    /// `[[events]]`, `[output] observables` and `[output] section` (empty without them).
    pub events: super::events::EventsSpec,
}

impl RunSpec {
    /// The method's name: the rule, or `discrete_lagrangian` when the file gives its own `L_d`
    /// (then `[integrator] method` was refused and the default rule is not used).
    pub fn method_name(&self) -> String {
        match self.system.has_energy() {
            true => self.integrator.method.to_string(),
            false => DISCRETE_KEY.to_owned(),
        }
    }

    /// The method's order, where known (none for a file's own `L_d`).
    pub fn method_order(&self) -> Option<u32> {
        self.integrator
            .method
            .order()
            .filter(|_| self.system.has_energy())
    }
}

/// `[analysis]`, validated.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct AnalysisSpec {
    /// Monitor every step, not only the stored rows (the summary's maxima are then over every
    /// step).
    pub every_step: bool,
    /// Certificates after the run: the symplecticity defect of the step map at the start and
    /// the end, the equivariance defect of `L_d` for each symmetry.
    pub certify: bool,
}

/// Where the values that only the core can judge were written.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SpecSpans {
    /// The `lagrangian` or `builtin` value.
    pub lagrangian: Option<Range<usize>>,
    /// The `v` or `p` vector.
    pub initial_data: Option<Range<usize>>,
    /// The `[integrator] method` value.
    pub method: Option<Range<usize>>,
}

/// The Lagrangian: a catalog system or an expression.
#[derive(Debug, Clone)]
pub enum LagrangianSpec {
    /// `builtin = "…"`.
    Builtin {
        /// Which catalog entry.
        builtin: Builtin,
        /// The configured system.
        system: BuiltinSystem,
    },
    /// `lagrangian = "…"`.
    Expression(ExprLagrangian),
    /// `hamiltonian = "…"`, run through its Lagrangian `L = ⟨p, v⟩ − H` at `∂H/∂p = v`, or
    /// `L = ½ vᵀ K⁻¹ v − V` when `H` is separable.
    Hamiltonian(Box<HamiltonianSpec>),
    /// `discrete_lagrangian = "…"`: the file's own `L_d`, with no continuous `L` behind it.
    Discrete(ExprDiscreteLagrangian),
    /// `rigid_body = { … }`: a rigid body on SO(3) (× ℝ³), `L = ½ΩᵀJΩ (+ ½m|ẋ|²) − U`.
    Rigid(Box<RigidSpec>),
    /// `[[system.body]]`, `[[system.particle]]`, `[[system.joint]]`: rigid bodies on (SO(3) × ℝ³)ᵐ
    /// and particles on (ℝ³)ⁿ joined by joints.
    Multibody(Box<MultibodySpec>),
}

/// A `hamiltonian = "…"` system: the Lagrangian of a general `H`, and for a separable
/// `H = ½ pᵀ K p + V(t, q)` the same Lagrangian in closed form, `L = ½ vᵀ K⁻¹ v − V(t, q)`, as an
/// expression Lagrangian the run takes instead (its separable fast paths).
#[derive(Debug, Clone)]
pub struct HamiltonianSpec {
    /// `L = ⟨p, v⟩ − H` at `∂H/∂p = v` (`general.hamiltonian` is `H`).
    pub general: HamiltonianExprLagrangian,
    /// `L = ½ vᵀ K⁻¹ v − V(t, q)` when `H` is separable.
    pub separable: Option<ExprLagrangian>,
}

/// The key of a file's own discrete Lagrangian, `[system] discrete_lagrangian`, which is also
/// the method's name in its outputs.
pub const DISCRETE_KEY: &str = "discrete_lagrangian";

/// What a run of a `discrete_lagrangian` file says instead of an energy.
pub const ENERGY_NOT_AVAILABLE: &str =
    "not available (no continuous Lagrangian: the file gives L_d)";

impl LagrangianSpec {
    /// `builtin <name>` or the expression text.
    pub fn describe(&self) -> String {
        match self {
            LagrangianSpec::Builtin { builtin, .. } => {
                format!("builtin {}: L = {}", builtin.name(), builtin.formula())
            }
            LagrangianSpec::Expression(l) => format!("L = {}", l.program().text()),
            LagrangianSpec::Hamiltonian(h) => {
                format!("H = {}", h.general.hamiltonian.program().text())
            }
            LagrangianSpec::Discrete(ld) => format!("L_d = {}", ld.program().text()),
            LagrangianSpec::Rigid(r) => format!(
                "rigid body: L = ½ΩᵀJΩ{} − U, U = {}",
                if r.mass.is_some() {
                    " + ½m|ẋ|²"
                } else {
                    ""
                },
                r.potential.text().unwrap_or("0")
            ),
            LagrangianSpec::Multibody(m) => format!(
                "{} joined by {} joint{}: L = Σ ½ΩᵀJΩ + ½m|ẋ|² − U, U = −Σ m g·x{}{}, g = {:?}{}",
                m.members(),
                m.joints.len(),
                if m.joints.len() == 1 { "" } else { "s" },
                match m.springs.len() {
                    0 => String::new(),
                    n => format!(
                        " + {n} spring{} ½k(‖d‖ − ℓ₀)²",
                        if n == 1 { "" } else { "s" }
                    ),
                },
                match &m.potential {
                    None => String::new(),
                    Some(u) => format!(" + {}", u.text()),
                },
                m.gravity,
                match m.dampers.len() {
                    0 => String::new(),
                    n => format!(", {n} damper{} −c(ḋ·e)e", if n == 1 { "" } else { "s" }),
                }
            ),
        }
    }
}

/// `[system]`, validated.
#[derive(Debug, Clone)]
pub struct SystemSpec {
    /// The Lagrangian.
    pub lagrangian: LagrangianSpec,
    /// Coordinate names (n of them).
    pub coordinates: Vec<String>,
    /// Every scalar parameter with its value: for a builtin its catalog parameters (defaults
    /// filled in) then the others, for an expression Lagrangian in the file's order.
    pub parameters: Vec<(String, f64)>,
    /// `nbody` masses.
    pub masses: Option<Vec<f64>>,
    /// External force (empty: none).
    pub force: ExprForce,
    /// Constraints (empty: none).
    pub constraint: ExprConstraint,
    /// Monitored symmetries.
    pub symmetries: Vec<Symmetry>,
}

impl SystemSpec {
    /// Degrees of freedom.
    pub fn dof(&self) -> usize {
        self.coordinates.len()
    }

    /// The rigid body, if the system is one.
    pub fn rigid(&self) -> Option<&RigidSpec> {
        match &self.lagrangian {
            LagrangianSpec::Rigid(r) => Some(r),
            _ => None,
        }
    }

    /// The bodies and joints, if the system is a multibody one.
    pub fn multibody(&self) -> Option<&MultibodySpec> {
        match &self.lagrangian {
            LagrangianSpec::Multibody(m) => Some(m),
            _ => None,
        }
    }

    /// The names of the monitored momentum maps (columns `J_<name>`), in the file's order.
    pub fn momentum_names(&self) -> Vec<String> {
        match self.rigid() {
            Some(r) => r.momentum_names(),
            None => (self.symmetries.iter())
                .map(|s| {
                    use crate::model::MomentumMap as _;
                    s.name().to_owned()
                })
                .collect(),
        }
    }

    /// Whether the system has an energy `⟨p, q̇⟩ − L`: not for a file's own `L_d`.
    pub fn has_energy(&self) -> bool {
        !matches!(self.lagrangian, LagrangianSpec::Discrete(_))
    }

    /// Why the energy is not conserved, if it is not: forces act, or the Lagrangian depends on
    /// `t` (its input slot `2n` is read). The catalog Lagrangians are autonomous.
    pub fn energy_not_conserved(&self) -> Option<&'static str> {
        if self.force.is_active() {
            return Some("forces act");
        }
        if self.multibody().is_some_and(|m| !m.dampers.is_empty()) {
            return Some("dampers act");
        }
        if let Some(r) = self.rigid() {
            use marsden::lie::potential::ExternalLoads as _;
            return match (r.loads.is_active(), r.potential.depends_on_time()) {
                (true, _) => Some("torques or forces act"),
                (false, true) => Some("the potential depends on t"),
                (false, false) => None,
            };
        }
        match (&self.lagrangian, self.depends_on_time()) {
            (_, false) => None,
            (LagrangianSpec::Hamiltonian(_), true) => Some("the Hamiltonian depends on t"),
            (_, true) => Some("the Lagrangian depends on t"),
        }
    }

    /// Whether the Lagrangian is an expression that reads `t` (its input slot `2n`), or the
    /// Legendre transform of a Hamiltonian that does (its slot `2n` too: `q`, `p`, `t`); the
    /// catalog Lagrangians are autonomous.
    pub fn depends_on_time(&self) -> bool {
        let t = 2 * self.dof();
        match &self.lagrangian {
            LagrangianSpec::Expression(l) => l.program().inputs_used().contains(&t),
            LagrangianSpec::Hamiltonian(h) => {
                (h.general.hamiltonian.program().inputs_used()).contains(&t)
            }
            _ => false,
        }
    }
}

/// How the initial state was given.
#[derive(Debug, Clone, PartialEq)]
pub enum InitialData {
    /// `v = [...]`.
    Velocity(Vec<f64>),
    /// `p = [...]`.
    Momentum(Vec<f64>),
}

/// `[initial]`, validated (lengths match the coordinates, all finite).
#[derive(Debug, Clone, PartialEq)]
pub struct InitialSpec {
    /// Initial time.
    pub t0: f64,
    /// Positions.
    pub q: Vec<f64>,
    /// Velocities or momenta.
    pub data: InitialData,
    /// Project the data onto the constraint manifold (`φ(q) = 0`, `Dφ(q) v = 0`) before the
    /// run; otherwise data off the manifold are refused.
    pub project: bool,
    /// A rigid body's attitude and body momentum (`q`, `v`/`p` are then its centre of mass's,
    /// empty for a body turning about a fixed point).
    pub rigid: Option<RigidInitial>,
}

impl InitialSpec {
    /// The core's form.
    pub fn to_initial(&self) -> Initial {
        match &self.data {
            InitialData::Velocity(v) => Initial::velocity(&self.q, v),
            InitialData::Momentum(p) => Initial::momentum(&self.q, p),
        }
    }
}

/// `[integrator]`, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct IntegratorSpec {
    /// The rule.
    pub method: Method,
    /// `t_k = t₀ + k h`, `k = 0 … steps`.
    pub grid: TimeGrid,
    /// Newton options of each step.
    pub newton: NewtonOptions,
    /// Structure-aware fast paths allowed (`[integrator] fast_paths`, default true).
    pub fast_paths: bool,
    /// Compensated summation of the state update (`[integrator] compensated`, default false).
    pub compensated: bool,
    /// `t_end` as written, if the steps were derived from it.
    pub t_end: Option<f64>,
}

/// Output format of the trajectory.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// `trajectory.csv`.
    Csv,
    /// `t.npy`, `q.npy`, `p.npy`, … (one per column group).
    Npy,
}

impl Format {
    /// `"csv"` or `"npy"`.
    pub fn name(self) -> &'static str {
        match self {
            Format::Csv => "csv",
            Format::Npy => "npy",
        }
    }
}

/// `[output]`, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct OutputSpec {
    /// Output directory.
    pub dir: PathBuf,
    /// Trajectory format.
    pub format: Format,
    /// Store every k-th step (and always the first and the last).
    pub every: usize,
    /// Draw PNG plots after the run.
    pub plots: bool,
    /// Coordinates that are angles (plots wrap them to (−π, π]).
    pub angles: Vec<String>,
    /// Save a checkpoint of the run every this many steps (`None`: never), from which
    /// `marsden resume` continues it bit for bit.
    pub checkpoint_every: Option<usize>,
    /// Times at which the state is sampled (`[output] times`, checked: increasing, inside the
    /// run; empty: none).
    pub times: Vec<f64>,
    /// `[output] exact_times`: each time inside a step reached by a variational step of its
    /// own size from the grid point before it, not read off the step's interpolant.
    pub exact_times: bool,
}
