//! A rigid body's potential and external loads from compiled expressions: the core's
//! [`RigidPotential`] and [`ExternalLoads`] for a problem file's `potential`, `torques` and
//! `forces`.
//!
//! The expressions read one inputs slice, laid out `[R11 … R33, x, y, z, t]` ([`INPUTS`]): the
//! attitude's entries row-major (body → space), the centre of mass (zero for a body turning
//! about a fixed point, whose expressions may not name it) and the time. The potential is
//! evaluated at any [`Scalar`], so the body moment `M` comes from the core's automatic
//! differentiation of the expression ([`marsden::lie::potential`]).

use marsden::Scalar;
use marsden::lie::potential::{ExternalLoads, RigidPotential};
use std::cell::RefCell;

use marsden_expr::{Program, ProgramSet, Tape};

/// Input names in slot order: the attitude's entries, the centre of mass, the time.
pub const INPUTS: [&str; 13] = [
    "R11", "R12", "R13", "R21", "R22", "R23", "R31", "R32", "R33", "x", "y", "z", "t",
];

/// The slot of `t` in [`INPUTS`].
const T: usize = 12;

/// The inputs `[R, x, t]` of one body.
#[inline(always)]
fn inputs<S: Scalar>(t: S, rotation: &[S], position: &[S]) -> [S; 13] {
    let mut x = [t; 13];
    x[..9].copy_from_slice(&rotation[..9]);
    x[9..T].copy_from_slice(&position[..3]);
    x
}

/// `U(R, x, t)` from an expression (`None`: `U = 0`, a free rigid body), with its gradient
/// in `[R, x, t]` differentiated symbolically ([`Program::jet`]) for the body moment in closed
/// form: one pass over a short tape per step instead of dual numbers through the program.
#[derive(Debug, Clone, PartialEq)]
pub struct ExprRigidPotential {
    program: Option<Program>,
    /// `[U, ∂U/∂R11, …, ∂U/∂z, ∂U/∂t]` (`None` without a potential, or for a function
    /// without a symbolic derivative: then automatic differentiation).
    gradient: Option<Tape>,
    /// `[∂U/∂R11, …, ∂U/∂z]` when they are constants (a potential linear in `R` and `x`, such as
    /// a uniform field's `mgl*R33`): no evaluation per step.
    constant: Option<Vec<f64>>,
}

thread_local! {
    /// The registers of the gradient tape (one evaluation per step: no allocation).
    static REGISTERS: RefCell<Vec<f64>> = const { RefCell::new(Vec::new()) };
}

impl ExprRigidPotential {
    /// The potential of `program` over [`INPUTS`] (`None`: no potential).
    pub fn new(program: Option<Program>) -> Self {
        let constant = program.as_ref().and_then(|p| p.constant_gradient(T));
        // The gradient tape only where the gradient is not constant (a jet also derives the
        // Hessian: 91 second derivatives in 13 inputs, not built when unused).
        let gradient = match constant {
            Some(_) => None,
            None => (program.as_ref())
                .and_then(|p| p.jet(INPUTS.len()))
                .map(|jet| jet.first().clone()),
        };
        Self {
            program,
            gradient,
            constant,
        }
    }

    /// The expression's text, if there is one.
    pub fn text(&self) -> Option<&str> {
        self.program.as_ref().map(Program::text)
    }

    /// Whether `U` reads `t`.
    pub fn depends_on_time(&self) -> bool {
        (self.program.as_ref()).is_some_and(|p| p.inputs_used().contains(&T))
    }
}

impl RigidPotential for ExprRigidPotential {
    fn value<S: Scalar>(&self, t: S, rotations: &[S], positions: &[S]) -> S {
        match &self.program {
            Some(program) => program.eval(&inputs(t, rotations, positions)),
            None => S::from(0.0),
        }
    }

    fn gradient(
        &self,
        t: f64,
        rotations: &[f64],
        positions: &[f64],
        d_rotations: &mut [f64],
        d_positions: &mut [f64],
    ) -> bool {
        if let Some(g) = &self.constant {
            d_rotations[..9].copy_from_slice(&g[..9]);
            d_positions[..3].copy_from_slice(&g[9..T]);
            return true;
        }
        let Some(tape) = &self.gradient else {
            return false;
        };
        let x = inputs(t, rotations, positions);
        let mut out = [0.0; 14];
        REGISTERS.with_borrow_mut(|regs| tape.eval_into(&x, regs, &mut out));
        d_rotations[..9].copy_from_slice(&out[1..10]);
        d_positions[..3].copy_from_slice(&out[10..13]);
        true
    }
}

/// External loads from expressions: a body-frame torque and, for a body with a mass, a spatial
/// force on its centre of mass (three expressions each; `None`: zero).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ExprRigidLoads {
    /// `τ(R, x, t)`, body frame.
    pub torques: Option<ProgramSet>,
    /// `f(R, x, t)`, space frame.
    pub forces: Option<ProgramSet>,
}

impl ExternalLoads for ExprRigidLoads {
    fn is_active(&self) -> bool {
        self.torques.is_some() || self.forces.is_some()
    }

    fn loads(
        &self,
        t: f64,
        rotations: &[f64],
        positions: &[f64],
        torques: &mut [f64],
        forces: &mut [f64],
    ) {
        let x = inputs(t, rotations, positions);
        if let Some(set) = &self.torques {
            set.eval_into(&x, &mut torques[..3]);
        }
        if let Some(set) = &self.forces {
            set.eval_into(&x, &mut forces[..3]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use marsden_expr::Symbols;

    fn compile(text: &str) -> Program {
        let symbols = Symbols::with_inputs(INPUTS).unwrap();
        Program::compile(text, &symbols).unwrap()
    }

    #[test]
    fn reads_the_entries_row_major_then_the_position_and_time() {
        let r: Vec<f64> = (1..=9).map(f64::from).collect();
        let x = [10.0, 20.0, 30.0];
        let u = ExprRigidPotential::new(Some(compile("R12 + 100*R31 + y + 1000*t")));
        assert_eq!(u.value(0.5, &r, &x), 2.0 + 700.0 + 20.0 + 500.0);
        assert!(u.depends_on_time());
        assert_eq!(ExprRigidPotential::new(None).value(0.5, &r, &x), 0.0);
    }

    #[test]
    fn the_symbolic_gradient_is_the_derivative_in_each_entry() {
        let u = ExprRigidPotential::new(Some(compile("3*R33 + R12*R21 + z^2 + sin(t)")));
        let r: Vec<f64> = (1..=9).map(f64::from).collect();
        let (mut dr, mut dx) = ([0.0; 9], [0.0; 3]);
        assert!(u.gradient(0.0, &r, &[0.0, 0.0, 5.0], &mut dr, &mut dx));
        // ∂/∂R12 = R21 = 4, ∂/∂R21 = R12 = 2, ∂/∂R33 = 3, ∂/∂z = 2z = 10.
        assert_eq!(dr, [0.0, 4.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0, 3.0]);
        assert_eq!(dx, [0.0, 0.0, 10.0]);
        assert!(!ExprRigidPotential::new(None).gradient(0.0, &r, &[0.0; 3], &mut dr, &mut dx));
        // A uniform field: the constant gradient, the tape's numbers.
        let top = ExprRigidPotential::new(Some(compile("20*R33 + 2*9.81*z")));
        let (mut dr, mut dx) = ([0.0; 9], [0.0; 3]);
        assert!(top.constant.is_some());
        assert!(top.gradient(1.0, &r, &[0.0; 3], &mut dr, &mut dx));
        assert_eq!((dr[8], dx[2]), (20.0, 2.0 * 9.81));
    }

    #[test]
    fn torques_and_forces_fill_their_three_slots() {
        let symbols = Symbols::with_inputs(INPUTS).unwrap();
        let set = |t: [&str; 3]| ProgramSet::compile(t, &symbols).unwrap();
        let loads = ExprRigidLoads {
            torques: Some(set(["R11", "-t", "0"])),
            forces: Some(set(["0", "0", "-z"])),
        };
        let r = [2.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
        let (mut tau, mut f) = ([0.0; 3], [0.0; 3]);
        loads.loads(3.0, &r, &[0.0, 0.0, 4.0], &mut tau, &mut f);
        assert_eq!((tau, f), ([2.0, -3.0, 0.0], [0.0, 0.0, -4.0]));
    }
}
