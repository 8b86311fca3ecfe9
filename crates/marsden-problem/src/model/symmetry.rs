//! Symmetries and their momentum maps `J(q, p) = ⟨p, ξ_Q(q)⟩` (seed: *momentum maps*).
//!
//! A symmetry of a problem file is given by its infinitesimal generator `ξ_Q(q)`, one expression
//! per coordinate. Evaluated with the discrete momenta `p_k` of a variational integrator, `J` is
//! the discrete momentum map, conserved up to the Newton tolerance when `L` is invariant
//! (discrete Noether theorem; Marsden & West, *Acta Numerica* 10 (2001), §1.3.3).

use marsden::Scalar;
use marsden::symmetry::GroupAction;

use marsden_expr::ProgramSet;

/// Something whose value along a run is monitored: the momentum map of a symmetry, evaluated
/// on `f64` samples as rows are streamed (the symmetry is also a core
/// [`marsden::symmetry::GroupAction`], used to check it before the run).
pub trait MomentumMap {
    /// Name (the CSV column is `J_<name>`).
    fn name(&self) -> &str;
    /// `J(q, p)`; `scratch` is reusable workspace.
    fn value(&self, q: &[f64], p: &[f64], scratch: &mut Vec<f64>) -> f64;
}

/// A symmetry given by the expressions of its generator `ξ_Q(q)`.
///
/// ```
/// use marsden_expr::{ProgramSet, Symbols};
/// use marsden_problem::model::{MomentumMap, Symmetry};
///
/// let symbols = Symbols::with_inputs(["x", "y"]).unwrap();
/// let rotation = Symmetry::new("Lz", ProgramSet::compile(["-y", "x"], &symbols).unwrap());
/// // J = ⟨p, (−y, x)⟩ = x p_y − y p_x
/// assert_eq!(rotation.value(&[1.0, 0.0], &[0.0, 2.0], &mut Vec::new()), 2.0);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Symmetry {
    name: String,
    generator: ProgramSet,
}

impl Symmetry {
    /// A symmetry called `name` with generator components compiled against `[q₁ … qₙ]`.
    pub fn new(name: impl Into<String>, generator: ProgramSet) -> Self {
        Self {
            name: name.into(),
            generator,
        }
    }

    /// The generator's compiled components.
    pub fn generator(&self) -> &ProgramSet {
        &self.generator
    }
}

impl MomentumMap for Symmetry {
    fn name(&self) -> &str {
        &self.name
    }

    fn value(&self, q: &[f64], p: &[f64], scratch: &mut Vec<f64>) -> f64 {
        scratch.resize(self.generator.len(), 0.0);
        self.generator.eval_into(q, scratch);
        p.iter().zip(scratch.iter()).map(|(p, xi)| p * xi).sum()
    }
}

/// A problem file's symmetry is a one-parameter group action of the core (so the core's checks
/// and momentum maps apply): its Lie algebra is spanned by the one generator `ξ_Q(q)`.
impl GroupAction for Symmetry {
    fn name(&self) -> String {
        self.name.clone()
    }
    fn dof(&self) -> usize {
        self.generator.len()
    }
    fn algebra_dim(&self) -> usize {
        1
    }
    fn generator<S: Scalar>(&self, _a: usize, q: &[S], out: &mut [S]) {
        self.generator.eval_into(q, out);
    }
}
