//! Errors of setting up an optimal control problem. A solve that starts but does not converge
//! is not an error: it returns its last iterate with a [`crate::Status`] saying so.

use thiserror::Error;

/// What is wrong with the problem as given (nothing was solved).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ControlError {
    /// A vector has the wrong number of components.
    #[error("{what} has {got} components, expected {expected}")]
    Length {
        /// Which input.
        what: &'static str,
        /// Its length.
        got: usize,
        /// The length the problem needs.
        expected: usize,
    },
    /// A lower bound above its upper bound.
    #[error("{what} bounds: component {index} has lower {lower} > upper {upper}")]
    Bounds {
        /// Which bounds (controls or states).
        what: &'static str,
        /// The component.
        index: usize,
        /// Its lower bound.
        lower: f64,
        /// Its upper bound.
        upper: f64,
    },
    /// A boundary value or bound that is NaN, or a fixed value that is infinite.
    #[error("{what}: component {index} is {value}")]
    NotFinite {
        /// Which input.
        what: &'static str,
        /// The component.
        index: usize,
        /// The value.
        value: f64,
    },
    /// A boundary velocity with some components free: the momentum `∂L/∂v` of a fixed
    /// component needs every component of `v`.
    #[error(
        "{which} velocity: components {free:?} are free and others fixed; give momenta instead"
    )]
    PartialVelocity {
        /// "start" or "end".
        which: &'static str,
        /// The free components.
        free: Vec<usize>,
    },
    /// The horizon: `T ≤ 0`, not finite, or no steps.
    #[error("horizon: duration {duration} with {steps} steps (need T > 0 finite, N ≥ 1)")]
    Horizon {
        /// `T`.
        duration: f64,
        /// `N`.
        steps: usize,
    },
    /// The transcription cannot take this rule.
    #[error("rule {rule} cannot be used for optimal control: {reason}")]
    UnsupportedRule {
        /// The rule's name.
        rule: String,
        /// Why.
        reason: String,
    },
    /// An initial guess with the wrong number of nodes.
    #[error("initial guess: {what} has {got} nodes, expected {expected}")]
    Guess {
        /// `q` or `u`.
        what: &'static str,
        /// Nodes given.
        got: usize,
        /// Nodes needed.
        expected: usize,
    },
    /// Invalid solver options.
    #[error("solver option {name} = {value}: {reason}")]
    Option {
        /// The option.
        name: &'static str,
        /// Its value.
        value: f64,
        /// Why it is refused.
        reason: &'static str,
    },
}
