//! The size of the Newton system an implicit method solves every step, said before a run whose
//! every step would be slow.
//!
//! An implicit step solves for the offsets of its control points and the constraint
//! multipliers at once ([`marsden::integrator::StepShape::unknowns`]: `s·n + d·(1 + c)`, with
//! `s` the step's segments, `n` the degrees of freedom, `d` the constraints and `c` the stage
//! constraints). A composition `Ψ_h = Φ_{γ_m h} ∘ … ∘ Φ_{γ₁ h}` presents all its substeps as one
//! step ([MW01] §2.5, [`marsden::discrete::rules::composition`]): its `s` is `m` times the base's,
//! so `triple-jump-10(gauss-10)` (81 substeps of 10 segments) solves 810 unknowns per degree of
//! freedom. Each Newton update differentiates the whole composed action twice by forward AD
//! over all `(s + 1)·n` control coordinates and factors the dense Jacobian, a cost that grows
//! with the cube of the size or faster. Explicit steps (the trapezoid rule and its
//! compositions on `½ vᵀMv − V`, unforced and unconstrained) solve nothing and get no remark.
//!
//! [MW01]: marsden#references

use marsden::discrete::DiscreteAction as _;
use marsden::integrator::StepShape;
use marsden::{Constraint as _, Lagrangian, Rule as _};

pub use crate::step_cost::StepCost;

use marsden_problem::error::Diagnostic;
use marsden_problem::problem::RunSpec;

/// Unknowns per step above which the method is said to be slow: a step of this size already
/// takes a good part of a second, and the cost rises with the cube of the size or faster
/// (BENCHMARKS.md, "Robustness limits").
pub const LARGE_STEP_SYSTEM: usize = 100;

/// The unknowns of `spec`'s step with `lagrangian`, or `None` if its steps solve no Newton
/// system (an explicit step, or `exact`, whose shooting solves `n` unknowns).
pub fn step_unknowns<L: Lagrangian>(spec: &RunSpec, lagrangian: &L) -> Option<usize> {
    let rule = spec.integrator.method.rule()?;
    let action = rule.discretize(lagrangian);
    let d = spec.system.constraint.count();
    let forced = spec.system.force.is_active();
    let free = d == 0 && !forced && !spec.integrator.compensated;
    if free && spec.integrator.fast_paths && action.explicit().is_some() {
        return None;
    }
    let stages = match d {
        0 => 0,
        _ => action.constrained_stages().unwrap_or(0),
    };
    let shape = StepShape {
        n: action.dof(),
        s: action.internal_stages() + 1,
        d,
        forced,
        stages,
    };
    Some(shape.unknowns())
}

/// Memory assumed available when the system does not say (`/proc/meminfo` unreadable).
const ASSUMED_MEMORY: u64 = 8 << 30;

/// Bytes the dense Newton system of `unknowns` unknowns holds at once: the Jacobian and its LU
/// factors, two `unknowns × unknowns` matrices of `f64`.
pub fn step_system_bytes(unknowns: usize) -> u64 {
    let u = unknowns as u64;
    u.saturating_mul(u).saturating_mul(2 * 8)
}

/// The memory a run may take: `MemAvailable` of `/proc/meminfo`, or [`ASSUMED_MEMORY`].
pub fn available_memory() -> u64 {
    std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|text| {
            let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
            let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
            Some(kib.saturating_mul(1024))
        })
        .unwrap_or(ASSUMED_MEMORY)
}

/// Refuses a method whose step system cannot be held in `memory` bytes (the allocation would
/// abort the process): the size and what solves a smaller system, before anything is written.
///
/// # Errors
/// The diagnostic naming the unknowns, the bytes needed and the bytes available.
pub fn fits_in_memory<L: Lagrangian>(
    spec: &RunSpec,
    lagrangian: &L,
    memory: u64,
) -> Result<(), Diagnostic> {
    let Some(unknowns) = step_unknowns(spec, lagrangian) else {
        return Ok(());
    };
    let needed = step_system_bytes(unknowns);
    if needed <= memory {
        return Ok(());
    }
    let gib = |bytes: u64| bytes as f64 / f64::from(1u32 << 30);
    Err(Diagnostic::new(format!(
        "the method `{}` solves a dense Newton system of {unknowns} unknowns every step: its \
         Jacobian and LU factors need {:.1} GiB, more than the {:.1} GiB of memory available",
        spec.integrator.method,
        gib(needed),
        gib(memory)
    ))
    .at(spec.source.locate_opt(spec.spans.method.clone()))
    .help(
        "choose a composition of fewer substeps (triple-jump-4 instead of triple-jump-10), \
         gauss-s or lobatto-s with a smaller s, or midpoint/trapezoid (a system of n unknowns)",
    ))
}

/// A warning if `spec`'s method solves more than [`LARGE_STEP_SYSTEM`] unknowns per step,
/// stating the cost up front ([`StepCost`]): the unknowns, the bytes of the dense Jacobian and
/// its LU factors, and the work of one Newton iteration.
pub fn large_step_system<L: Lagrangian>(spec: &RunSpec, lagrangian: &L) -> Option<String> {
    let unknowns = step_unknowns(spec, lagrangian)?;
    let rule = spec.integrator.method.rule()?;
    (unknowns > LARGE_STEP_SYSTEM).then(|| {
        let cost = StepCost::of(rule, lagrangian.dof(), unknowns);
        format!(
            "the method `{}` solves a dense Newton system of {unknowns} unknowns every step \
             (more than {LARGE_STEP_SYSTEM}): {}; a composition of fewer substeps, or gauss-s \
             with a smaller s, solves a smaller one",
            spec.integrator.method,
            cost.describe()
        )
    })
}
