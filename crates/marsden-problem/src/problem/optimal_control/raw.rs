//! Stage 1 of `[optimal_control]`: the section as written (serde, spans, nothing checked).
//!
//! ```toml
//! [system]
//! coordinates = ["x"]
//! lagrangian = "0.5*x_dot^2"
//! controls = ["u"]                  # per step (per node for gauss/lobatto), usable in `forces`
//! forces = ["u"]
//! [optimal_control]
//! cost = "0.5*u^2"                  # running cost C(t, q, q_dot, u)
//! final_cost = "10*(x - 1)^2"       # optional Φ(q_N, p_N), in q, p_<coordinate> and t
//! t_end = 1.0
//! steps = 100
//! method = "midpoint"               # any rule but exact (default midpoint)
//! start = { q = [0.0], v = [0.0] }  # or p; any component may be "free"
//! end = { q = [1.0], v = [0.0] }
//! guess = "simulation"              # or "line" (default: simulation when the start is complete)
//! max_iterations = 200
//! tolerance = 1e-8                  # KKT residual
//! constraint_tolerance = 1e-10
//! path = ["x - 0.8"]               # optional path inequalities g(t, q, q_dot, u) <= 0
//! [optimal_control.bounds]          # optional, per control or coordinate: [lo, hi]
//! u = [-10.0, 10.0]
//! ```

use std::fmt;

use serde::Deserialize;
use serde::de::{self, Deserializer, Visitor};
use toml::Spanned;

use crate::problem::raw::{Ordered, SpannedList};

/// `[optimal_control]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawOptimalControl {
    /// The running cost `C(t, q, q̇, u)` as an expression.
    pub cost: Option<Spanned<String>>,
    /// The final cost `Φ(q_N, p_N)` in the coordinates, `p_<coordinate>` and `t`.
    pub final_cost: Option<Spanned<String>>,
    /// Initial time (default 0).
    pub t0: Option<Spanned<f64>>,
    /// Final time.
    pub t_end: Option<Spanned<f64>>,
    /// Number of steps `N`.
    pub steps: Option<Spanned<i64>>,
    /// The rule (default `midpoint`).
    pub method: Option<Spanned<String>>,
    /// Conditions at `t0`.
    pub start: Option<Spanned<RawEnd>>,
    /// Conditions at `t_end`.
    pub end: Option<Spanned<RawEnd>>,
    /// `name = [lo, hi]` for controls and coordinates.
    pub bounds: Option<Spanned<Ordered<SpannedList<f64>>>>,
    /// Path inequalities `g(t, q, q̇, u) ≤ 0`, each an expression over `[q, q̇, t, u]`.
    pub path: Option<SpannedList<String>>,
    /// `"simulation"` or `"line"`.
    pub guess: Option<Spanned<String>>,
    /// SQP iteration budget (default 200).
    pub max_iterations: Option<Spanned<i64>>,
    /// KKT tolerance (default 1e-8).
    pub tolerance: Option<Spanned<f64>>,
    /// Constraint tolerance (default 1e-10).
    pub constraint_tolerance: Option<Spanned<f64>>,
}

/// `start = { q = [...], v = [...] }` (or `p`), components numbers or `"free"`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawEnd {
    /// Positions.
    pub q: Option<SpannedList<RawComponent>>,
    /// Velocities.
    pub v: Option<SpannedList<RawComponent>>,
    /// Momenta.
    pub p: Option<SpannedList<RawComponent>>,
}

/// One boundary component: a number, or `"free"`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RawComponent {
    /// Fixed to this value.
    Value(f64),
    /// Left to the optimiser.
    Free,
}

impl<'de> Deserialize<'de> for RawComponent {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(ComponentVisitor)
    }
}

struct ComponentVisitor;

impl Visitor<'_> for ComponentVisitor {
    type Value = RawComponent;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a number or \"free\"")
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<RawComponent, E> {
        Ok(RawComponent::Value(v))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<RawComponent, E> {
        Ok(RawComponent::Value(v as f64))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<RawComponent, E> {
        Ok(RawComponent::Value(v as f64))
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<RawComponent, E> {
        match v {
            "free" => Ok(RawComponent::Free),
            other => Err(E::invalid_value(de::Unexpected::Str(other), &self)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_numbers_and_free_components() {
        let text = "start = { q = [0, \"free\", 1.5] }\n";
        #[derive(Deserialize)]
        struct T {
            start: RawEnd,
        }
        let t: T = toml::from_str(text).unwrap();
        let q: Vec<RawComponent> = t
            .start
            .q
            .unwrap()
            .into_inner()
            .into_iter()
            .map(Spanned::into_inner)
            .collect();
        assert_eq!(
            q,
            [
                RawComponent::Value(0.0),
                RawComponent::Free,
                RawComponent::Value(1.5)
            ]
        );
        assert!(toml::from_str::<T>("start = { q = [\"loose\"] }\n").is_err());
    }
}
