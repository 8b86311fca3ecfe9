//! [`ExprForce`]: a generalised force, one expression per coordinate, written either in the
//! velocities (`f_L(t, q, q̇)`) or in the momenta (`f_H(t, q, p)`, names `p_<coordinate>`).
//!
//! A Hamiltonian force `f_H` is the same physical force as the Lagrangian force
//! `f_L = f_H ∘ FL`, i.e. `f_L(t, q, v) = f_H(t, q, ∂L/∂v(t, q, v))` ([MW01] §3.1): the run
//! evaluates it through the core's [`FromHamiltonian`], which computes the momenta by automatic
//! differentiation of `L` at the force's evaluation point, so the step's Newton Jacobian sees
//! the exact derivatives of `f_H(q, FL(q, v))`. A force is therefore only a [`Force`] once it is
//! attached to its Lagrangian ([`ExprForce::on`]).
//!
//! [MW01]: marsden#references

use marsden::forces::{FromHamiltonian, HamiltonianForce};
use marsden::{Force, Lagrangian, Scalar};

use std::sync::Arc;

use super::control_table::{ControlTable, with_controls};
use super::inputs::with_inputs;
use marsden_expr::ProgramSet;

/// What the expressions of a force read besides the coordinates and `t`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ForceInputs {
    /// Compiled against `[q, q̇, t]`: `f_L(t, q, q̇)`.
    #[default]
    Velocities,
    /// Compiled against `[q, p, t]`: `f_H(t, q, p)`.
    Momenta,
}

/// A generalised force given as expressions; the empty set is no force (its [`Force`] is
/// inactive, so the integrator skips all force work).
///
/// ```
/// use marsden::Force;
/// use marsden::systems::HarmonicOscillator;
/// use marsden_expr::{ProgramSet, Symbols};
/// use marsden_problem::model::{ExprForce, ForceInputs};
///
/// let mut symbols = Symbols::with_inputs(["x", "x_dot", "t"]).unwrap();
/// symbols.add_constant("c", 0.5).unwrap();
/// let force = ExprForce::new(ProgramSet::compile(["-c*x_dot"], &symbols).unwrap());
/// let osc = HarmonicOscillator { m: 2.0, k: 1.0 };
/// let mut f = [0.0];
/// force.on(&osc).force(0.0, &[1.0], &[2.0], &mut f);
/// assert_eq!(f, [-1.0]);
///
/// // The same damping in the momenta: p = m v.
/// let mut symbols = Symbols::with_inputs(["x", "p_x", "t"]).unwrap();
/// symbols.add_constant("c", 0.5).unwrap();
/// symbols.add_constant("m", 2.0).unwrap();
/// let programs = ProgramSet::compile(["-c*p_x/m"], &symbols).unwrap();
/// let force = ExprForce::with_inputs(programs, ForceInputs::Momenta);
/// force.on(&osc).force(0.0, &[1.0], &[2.0], &mut f);
/// assert_eq!(f, [-1.0]);
/// ```
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ExprForce {
    components: ProgramSet,
    inputs: ForceInputs,
    controls: Option<Arc<ControlTable>>,
}

impl ExprForce {
    /// Wraps one program per coordinate, compiled against `[q, q̇, t]`.
    pub fn new(components: ProgramSet) -> Self {
        Self::with_inputs(components, ForceInputs::Velocities)
    }

    /// Wraps one program per coordinate, compiled against `[q, q̇, t]` or `[q, p, t]`.
    pub fn with_inputs(components: ProgramSet, inputs: ForceInputs) -> Self {
        Self {
            components,
            inputs,
            controls: None,
        }
    }

    /// The same force with its expressions reading the controls of `table` after
    /// `[q, q̇, t]` (or `[q, p, t]`): programs compiled with the controls as those inputs.
    pub fn with_control_table(mut self, table: ControlTable) -> Self {
        self.controls = Some(Arc::new(table));
        self
    }

    /// The control table the force reads, if any.
    pub fn control_table(&self) -> Option<&ControlTable> {
        self.controls.as_deref()
    }

    /// No force.
    pub fn none() -> Self {
        Self::default()
    }

    /// The compiled components.
    pub fn components(&self) -> &ProgramSet {
        &self.components
    }

    /// Whether the expressions read velocities or momenta.
    pub fn inputs(&self) -> ForceInputs {
        self.inputs
    }

    /// Whether any force acts.
    pub fn is_active(&self) -> bool {
        !self.components.is_empty()
    }

    /// The Lagrangian force `f_L` of these expressions for the Lagrangian `lagrangian`.
    pub fn on<'a, L: Lagrangian>(&'a self, lagrangian: &'a L) -> LagrangianForce<'a, L> {
        let controls = self.controls.as_deref();
        match self.inputs {
            ForceInputs::Velocities => {
                LagrangianForce::Velocities(Velocities(&self.components, controls))
            }
            ForceInputs::Momenta => LagrangianForce::Momenta(FromHamiltonian::new(
                lagrangian,
                Momenta(&self.components, controls),
            )),
        }
    }
}

/// Expressions over `[q, q̇, t]` (then the controls of the table, if any) as a force.
#[derive(Debug, Clone, Copy)]
pub struct Velocities<'a>(&'a ProgramSet, Option<&'a ControlTable>);

/// Expressions over `[q, p, t]` (then the controls of the table, if any) as a Hamiltonian
/// force.
#[derive(Debug, Clone, Copy)]
pub struct Momenta<'a>(&'a ProgramSet, Option<&'a ControlTable>);

/// `f_L` of a problem file's force: the expressions themselves, or `f_H ∘ FL`.
#[derive(Debug)]
pub enum LagrangianForce<'a, L> {
    /// `f_L(t, q, q̇)` as written.
    Velocities(Velocities<'a>),
    /// `f_H(t, q, ∂L/∂v(t, q, q̇))`.
    Momenta(FromHamiltonian<&'a L, Momenta<'a>>),
}

impl<L> Clone for LagrangianForce<'_, L> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<L> Copy for LagrangianForce<'_, L> {}

impl Force for Velocities<'_> {
    #[inline]
    fn force<S: Scalar>(&self, t: S, q: &[S], v: &[S], out: &mut [S]) {
        match (self.0.is_empty(), self.1) {
            (true, _) => out.iter_mut().for_each(|f| *f = S::from(0.0)),
            (false, None) => with_inputs(q, v, t, |x| self.0.eval_into(x, out)),
            (false, Some(u)) => with_controls(q, v, t, u, |x| self.0.eval_into(x, out)),
        }
    }

    fn is_active(&self) -> bool {
        !self.0.is_empty()
    }
}

impl HamiltonianForce for Momenta<'_> {
    #[inline]
    fn hamiltonian_force<S: Scalar>(&self, t: S, q: &[S], p: &[S], out: &mut [S]) {
        match self.1 {
            None => with_inputs(q, p, t, |x| self.0.eval_into(x, out)),
            Some(u) => with_controls(q, p, t, u, |x| self.0.eval_into(x, out)),
        }
    }
}

impl<L: Lagrangian> Force for LagrangianForce<'_, L> {
    #[inline]
    fn force<S: Scalar>(&self, t: S, q: &[S], v: &[S], out: &mut [S]) {
        match self {
            Self::Velocities(f) => f.force(t, q, v, out),
            Self::Momenta(f) => f.force(t, q, v, out),
        }
    }

    fn is_active(&self) -> bool {
        match self {
            Self::Velocities(f) => f.is_active(),
            Self::Momenta(f) => !f.force.0.is_empty(),
        }
    }

    fn validate(&self, dof: usize) -> Result<(), marsden::Error> {
        match self {
            Self::Velocities(f) => f.validate(dof),
            Self::Momenta(f) => f.validate(dof),
        }
    }
}
