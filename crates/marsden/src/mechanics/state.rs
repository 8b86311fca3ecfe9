//! Points of phase space and initial data.
//!
//! A [`State`] `(t, q, p)` is what the discrete Hamiltonian map `F̃_{L_d}: (q_k, p_k) ↦ (q_{k+1},
//! p_{k+1})` advances ([MW01] §1.5); [`Initial`] is how a user gives the start of a run, as
//! positions with velocities `(q₀, v₀)` or with momenta `(q₀, p₀)` — the two are related by the
//! Legendre transform `p = ∂L/∂v` ([`crate::mechanics::momentum`], [`crate::mechanics::velocity`]).
//!
//! [MW01]: crate#references

/// A point of phase space `(t, q, p)`.
#[derive(Debug, PartialEq)]
pub struct State {
    /// Time.
    pub t: f64,
    /// Positions (length n).
    pub q: Vec<f64>,
    /// Momenta (length n).
    pub p: Vec<f64>,
}

/// `clone_from` copies into the vectors already held (no allocation when the lengths agree),
/// so a loop that keeps states can reuse them.
impl Clone for State {
    fn clone(&self) -> Self {
        Self {
            t: self.t,
            q: self.q.clone(),
            p: self.p.clone(),
        }
    }

    fn clone_from(&mut self, source: &Self) {
        self.t = source.t;
        self.q.clone_from(&source.q);
        self.p.clone_from(&source.p);
    }
}

/// Initial data, given as velocities or as momenta.
#[derive(Debug, Clone, PartialEq)]
pub enum Initial {
    /// `(q₀, v₀)`; the momenta are `p₀ = ∂L/∂v(t₀, q₀, v₀)`.
    Velocity {
        /// Positions.
        q: Vec<f64>,
        /// Velocities.
        v: Vec<f64>,
    },
    /// `(q₀, p₀)`; the velocities are found by inverting the Legendre transform.
    Momentum {
        /// Positions.
        q: Vec<f64>,
        /// Momenta.
        p: Vec<f64>,
    },
}

impl Initial {
    /// Initial positions and velocities.
    pub fn velocity(q: &[f64], v: &[f64]) -> Self {
        Self::Velocity {
            q: q.to_vec(),
            v: v.to_vec(),
        }
    }

    /// Initial positions and momenta.
    pub fn momentum(q: &[f64], p: &[f64]) -> Self {
        Self::Momentum {
            q: q.to_vec(),
            p: p.to_vec(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::State;

    /// `clone_from` gives an equal state in the vectors the target already held.
    #[test]
    fn clone_from_reuses_the_vectors() {
        let source = State {
            t: 0.5,
            q: vec![1.0, 2.0],
            p: vec![3.0, 4.0],
        };
        let mut target = State {
            t: 0.0,
            q: vec![0.0; 2],
            p: vec![0.0; 2],
        };
        let (q, p) = (target.q.as_ptr(), target.p.as_ptr());
        target.clone_from(&source);
        assert_eq!(target, source);
        assert_eq!((target.q.as_ptr(), target.p.as_ptr()), (q, p));
    }
}
