//! A multibody file's `potential`: `U` as an expression over every body's and particle's
//! entries, the core's [`RigidPotential`] beside the field and the springs.
//!
//! The expression reads one inputs slice ([`inputs`]): each body's attitude `<b>_R11 …
//! <b>_R33` (row-major, body → space; particles have none), then every centre `<b>_x, <b>_y,
//! <b>_z` (bodies, then particles), then the parameters as constants. It is evaluated at any
//! [`Scalar`], so the bodies' moments `M_i` and forces `−∂U/∂x_i` come from the core's automatic
//! differentiation ([`marsden::lie::potential`]).

use marsden::Scalar;
use marsden::lie::potential::RigidPotential;
use marsden::numerics::scratch::with_slice;
use marsden_expr::Program;

/// The input names of `members` (name, particle) in slot order: the bodies' attitudes, then
/// every centre.
pub fn inputs(members: &[(String, bool)]) -> Vec<String> {
    let attitudes = (members.iter().filter(|m| !m.1)).flat_map(|(b, _)| {
        [
            "R11", "R12", "R13", "R21", "R22", "R23", "R31", "R32", "R33",
        ]
        .map(|e| format!("{b}_{e}"))
    });
    let centres = (members.iter()).flat_map(|(b, _)| ["x", "y", "z"].map(|a| format!("{b}_{a}")));
    attitudes.chain(centres).collect()
}

/// `U` from an expression over [`inputs`] (`None`: no potential).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ExprMultibodyPotential {
    /// The compiled potential, if the file gives one.
    pub program: Option<Program>,
    /// Which members are particles (no attitude slots), in the core's body order.
    pub particles: Vec<bool>,
}

impl RigidPotential for ExprMultibodyPotential {
    fn value<S: Scalar>(&self, _t: S, rotations: &[S], positions: &[S]) -> S {
        let Some(program) = &self.program else {
            return S::from(0.0);
        };
        let turning = self.particles.iter().filter(|p| !**p).count();
        let len = 9 * turning + positions.len();
        with_slice(len, S::from(0.0), |x| {
            let mut slot = 0;
            for (i, _) in self.particles.iter().enumerate().filter(|p| !*p.1) {
                x[slot..slot + 9].copy_from_slice(&rotations[9 * i..9 * i + 9]);
                slot += 9;
            }
            x[slot..].copy_from_slice(positions);
            program.eval(x)
        })
    }

    fn gradient(
        &self,
        _t: f64,
        _rotations: &[f64],
        _positions: &[f64],
        _d_rotations: &mut [f64],
        _d_positions: &mut [f64],
    ) -> bool {
        // No potential: the gradient is zero (the buffers arrive zeroed); else by AD.
        self.program.is_none()
    }
}
