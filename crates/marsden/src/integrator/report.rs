//! What a step cost and how well it converged, and the work counters of an integrator.

/// What one step cost and how well it converged.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct StepReport {
    /// Newton updates applied.
    pub iterations: usize,
    /// Final Newton residual (max-norm).
    pub residual: f64,
}

/// Work counters accumulated over the integrator's life (pinned by tests).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Statistics {
    /// Steps completed.
    pub steps: usize,
    /// Newton updates (linear solves) over all steps.
    pub newton_iterations: usize,
    /// Largest number of Newton updates in one step.
    pub max_newton_iterations: usize,
    /// Evaluations of the step system (residual and Jacobian together).
    pub system_evaluations: usize,
    /// Dual-number evaluations of the discrete action (one per AD chunk pair).
    pub action_evaluations: usize,
    /// Steps whose Newton iteration failed.
    pub failed_steps: usize,
    /// Steps taken by an explicit formula (no Newton iteration).
    pub explicit_steps: usize,
    /// Newton Jacobians factored: one per update on the general and the small path; on the
    /// separable path ([`crate::separable::alpha`]) only fresh ones, a reused Jacobian is not counted.
    pub jacobian_factorizations: usize,
    /// Gradients `∇V` of a separable potential evaluated by the structure-aware paths (the
    /// explicit step reuses the last step's gradient: one per step in a run).
    pub potential_gradients: usize,
}
