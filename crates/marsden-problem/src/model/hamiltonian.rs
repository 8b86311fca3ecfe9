//! [`ExprHamiltonian`]: `H(t, q, p)` from a compiled expression, and the Lagrangian a run uses
//! for it, `L = ⟨p, v⟩ − H` at `∂H/∂p = v` (the core's
//! [`marsden::hamiltonian::HamiltonianLagrangian`]).
//!
//! A variational integrator discretises a Lagrangian; a Hamiltonian given in a problem file
//! reaches every method through the inverse Legendre transform. For a hyperregular `H` the
//! Legendre transform `FL` of that `L` is the inverse of `FH = ∂H/∂p`, so the discrete
//! Hamiltonian map of `L_d` is the same map of `T*Q` whichever of `L` and `H` was written
//! ([MW01] Thm 1.5.2 and §2.6); the stored momenta are the `p` of `H`.
//!
//! [MW01]: marsden#references

use marsden::Scalar;
use marsden::hamiltonian::{Hamiltonian, HamiltonianLagrangian};
use marsden_expr::Program;

use super::inputs::with_inputs;

/// A Hamiltonian given as an expression over `[q, p, t]` (names `theta`, `p_theta`, `t`).
///
/// ```
/// use marsden::hamiltonian::Hamiltonian;
/// use marsden_expr::{Program, Symbols};
/// use marsden_problem::model::ExprHamiltonian;
///
/// let symbols = Symbols::with_inputs(["theta", "p_theta", "t"]).unwrap();
/// let program = Program::compile("0.5*p_theta^2 - cos(theta)", &symbols).unwrap();
/// let h = ExprHamiltonian::new(program, 1);
/// assert_eq!(h.hamiltonian(0.0, &[0.0], &[2.0]), 1.0);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ExprHamiltonian {
    program: Program,
    dof: usize,
}

impl ExprHamiltonian {
    /// Wraps a program compiled against the inputs `[q₁ … qₙ, p₁ … pₙ, t]` (n = `dof`).
    pub fn new(program: Program, dof: usize) -> Self {
        Self { program, dof }
    }

    /// The compiled expression.
    pub fn program(&self) -> &Program {
        &self.program
    }
}

impl Hamiltonian for ExprHamiltonian {
    fn dof(&self) -> usize {
        self.dof
    }

    #[inline]
    fn hamiltonian<S: Scalar>(&self, t: S, q: &[S], p: &[S]) -> S {
        with_inputs(q, p, t, |x| self.program.eval(x))
    }
}

/// The Lagrangian of a problem file's Hamiltonian.
pub type HamiltonianExprLagrangian = HamiltonianLagrangian<ExprHamiltonian>;

/// The momentum name of a coordinate: `theta` → `p_theta`.
pub fn momentum_name(coordinate: &str) -> String {
    format!("p_{coordinate}")
}

/// Input names of a Hamiltonian in slot order: the coordinates, their momenta, then `t`.
pub fn cotangent_inputs(coordinates: &[String]) -> Vec<String> {
    coordinates
        .iter()
        .cloned()
        .chain(coordinates.iter().map(|c| momentum_name(c)))
        .chain(std::iter::once("t".to_owned()))
        .collect()
}
