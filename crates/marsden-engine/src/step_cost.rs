//! What one Newton iteration of a large implicit step costs, said before the run starts.
//!
//! The general implicit step forms the Jacobian of its momentum-balance equations as the mixed
//! Hessian `∂²S/∂Q_{0…s−1}∂Q_{1…s}` of the step's action `S` over the `s·n` offsets of its
//! control points, by forward AD ([GW08] ch. 3) in 4 × 4 chunks of hyper-dual numbers (the core's
//! `numerics::ad`): `⌈sn/4⌉²` evaluations of `S`, every value carrying `1 + 4 + 4 + 16 = 25`
//! parts. Each evaluation of `S` evaluates `L` once per quadrature node of every substep (a
//! composition `Φ_{γ_m h} ∘ … ∘ Φ_{γ₁ h}` evaluates its base `m` times, [MW01] §2.5), counted
//! here by evaluating the rule's action once on a Lagrangian that counts its calls. The dense
//! `u × u` Jacobian is then factored by LU with partial pivoting, `≈ 2u³/3` flops ([GVL13]
//! §3.2); it and its factors hold `2u²` numbers of 8 bytes.
//!
//! [GW08]: marsden#references
//! [MW01]: marsden#references
//! [GVL13]: marsden#references

use std::cell::Cell;

use marsden::discrete::DiscreteAction as _;
use marsden::discrete::rules::Method as CoreMethod;
use marsden::{Lagrangian, Rule as _, Scalar};

use crate::step_system::step_system_bytes;

/// The hyper-dual chunk width of the core's forward AD for systems of more than four inputs.
const CHUNK: usize = 4;

/// Parts of one hyper-dual number of the 4 × 4 chunk: value, two gradients of 4, the 4 × 4 block.
pub const HYPER_DUAL_PARTS: usize = 1 + 2 * CHUNK + CHUNK * CHUNK;

/// The cost of one Newton iteration of a step with `unknowns` unknowns.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepCost {
    /// Unknowns `u` of the step's Newton system.
    pub unknowns: usize,
    /// Bytes of the dense Jacobian and its LU factors (`2u²` numbers of 8 bytes).
    pub bytes: u64,
    /// Evaluations of the step's action in hyper-dual numbers that assemble the Jacobian:
    /// `⌈sn/4⌉²`.
    pub action_evaluations: u64,
    /// Evaluations of `L` in one evaluation of the step's action (its quadrature nodes).
    pub lagrangian_per_action: u64,
    /// Floating-point operations of the LU factorisation, `2u³/3`.
    pub lu_flops: f64,
}

impl StepCost {
    /// The cost of a step of `rule` on `n` degrees of freedom whose Newton system has
    /// `unknowns` unknowns.
    pub fn of(rule: &CoreMethod, n: usize, unknowns: usize) -> Self {
        let counted = count_evaluations(rule);
        let blocks = (counted.segments * n).div_ceil(CHUNK) as u64;
        let u = unknowns as f64;
        Self {
            unknowns,
            bytes: step_system_bytes(unknowns),
            action_evaluations: blocks * blocks,
            lagrangian_per_action: counted.lagrangian,
            lu_flops: 2.0 * u * u * u / 3.0,
        }
    }

    /// Evaluations of `L` in hyper-dual numbers per Newton iteration.
    pub fn lagrangian_evaluations(&self) -> u64 {
        self.action_evaluations
            .saturating_mul(self.lagrangian_per_action)
    }

    /// `its Jacobian and LU factors take 1.2 MiB; each Newton iteration …`, for the warning.
    pub fn describe(&self) -> String {
        format!(
            "its Jacobian and LU factors take {}; each Newton iteration assembles the Jacobian \
             from {} evaluations of the step's action in hyper-dual numbers of {HYPER_DUAL_PARTS} \
             parts ({} evaluations of L) and factors it in ≈ {:.1e} flops",
            bytes_text(self.bytes),
            self.action_evaluations,
            self.lagrangian_evaluations(),
            self.lu_flops
        )
    }
}

/// What one evaluation of a rule's action does.
struct Counted {
    /// Segments `s` of the step (control points `Q₀ … Q_s`).
    segments: usize,
    /// Evaluations of `L`.
    lagrangian: u64,
}

/// The segments of `rule`'s step and the evaluations of `L` in one evaluation of its action
/// (on one degree of freedom: the count does not depend on `L`).
fn count_evaluations(rule: &CoreMethod) -> Counted {
    let counter = CountingLagrangian::default();
    let action = rule.discretize(&counter);
    let segments = action.internal_stages() + 1;
    let _ = action.action(0.0, 1.0, &[0.0], &vec![0.0; segments]);
    Counted {
        segments,
        lagrangian: counter.calls.get(),
    }
}

/// `L = ½v²` on one degree of freedom, counting its evaluations.
#[derive(Debug, Default)]
struct CountingLagrangian {
    calls: Cell<u64>,
}

impl Lagrangian for CountingLagrangian {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<S: Scalar>(&self, _t: S, _q: &[S], v: &[S]) -> S {
        self.calls.set(self.calls.get() + 1);
        v[0] * v[0] * 0.5
    }
}

/// Bytes in B, KiB, MiB or GiB.
fn bytes_text(bytes: u64) -> String {
    let units = ["B", "KiB", "MiB", "GiB"];
    let mut value = bytes as f64;
    let mut unit = 0;
    while value >= 1024.0 && unit + 1 < units.len() {
        value /= 1024.0;
        unit += 1;
    }
    match unit {
        0 => format!("{bytes} B"),
        _ => format!("{value:.1} {}", units[unit]),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cost(name: &str, n: usize, unknowns: usize) -> StepCost {
        StepCost::of(&CoreMethod::parse(name).unwrap(), n, unknowns)
    }

    /// One evaluation of the action evaluates `L` at each quadrature node: `s` Gauss points for
    /// `gauss-s`, `s` Lobatto points for `lobatto-s`, three substeps' worth for `triple-jump-4`
    /// ([MW01] §2.5).
    #[test]
    fn lagrangian_evaluations_are_the_quadrature_nodes() {
        assert_eq!(cost("gauss-2", 1, 2).lagrangian_per_action, 2);
        assert_eq!(cost("gauss-10", 1, 10).lagrangian_per_action, 10);
        assert_eq!(cost("lobatto-3", 1, 2).lagrangian_per_action, 3);
        assert_eq!(
            cost("triple-jump-4(gauss-3)", 1, 9).lagrangian_per_action,
            9
        );
    }

    /// `triple-jump-4(gauss-10)` on two degrees of freedom: 3 × 10 segments, 60 offsets in 15
    /// chunks of 4, so 225 hyper-dual evaluations of the action, 2250 of `L`; 60 unknowns take
    /// 2·60²·8 = 57600 bytes and `2·60³/3 = 144000` flops to factor.
    #[test]
    fn a_composed_gauss_step_counts_its_chunks_and_flops() {
        let c = cost("triple-jump-4(gauss-10)", 2, 60);
        assert_eq!(c.action_evaluations, 225);
        assert_eq!(c.lagrangian_evaluations(), 225 * 30);
        assert_eq!(c.bytes, 57_600);
        assert!((c.lu_flops - 144_000.0).abs() < 1e-6);
        let text = c.describe();
        assert!(
            text.contains("56.2 KiB") && text.contains("1.4e5 flops"),
            "{text}"
        );
    }
}
