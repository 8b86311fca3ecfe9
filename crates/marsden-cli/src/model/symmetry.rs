//! Symmetries and their momentum maps `J(q, p) = ⟨p, ξ_Q(q)⟩` (seed: *momentum maps*).
//!
//! A symmetry of a problem file is given by its infinitesimal generator `ξ_Q(q)`, one expression
//! per coordinate. Evaluated with the discrete momenta `p_k` of a variational integrator, `J` is
//! the discrete momentum map, conserved up to the Newton tolerance when `L` is invariant
//! (discrete Noether theorem; Marsden & West, *Acta Numerica* 10 (2001), §1.3.3).

use crate::expr::ProgramSet;

/// Something whose value along a run is monitored: the momentum map of a symmetry (the core's
/// group actions will implement this too when they land).
pub trait MomentumMap {
    /// Name (the CSV column is `J_<name>`).
    fn name(&self) -> &str;
    /// `J(q, p)`; `scratch` is reusable workspace.
    fn value(&self, q: &[f64], p: &[f64], scratch: &mut Vec<f64>) -> f64;
}

/// A symmetry given by the expressions of its generator `ξ_Q(q)`.
///
/// ```
/// use marsden_cli::expr::{ProgramSet, Symbols};
/// use marsden_cli::model::{MomentumMap, Symmetry};
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
