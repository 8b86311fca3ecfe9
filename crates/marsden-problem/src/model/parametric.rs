//! [`ExprParametric`]: a problem file's Lagrangian, forces and constraints with some of its
//! parameters read as inputs, for their sensitivities ([`marsden::sensitivity::ParametricModel`]).
//!
//! The run itself compiles every parameter as a constant. To differentiate with respect to a
//! parameter `θ_j`, the same texts are compiled again with `θ_j` as an input slot after `t`,
//! `[q₁ … qₙ, q̇₁ … q̇ₙ, t, θ₁ … θ_P]`; the other parameters stay constants. At `θ` equal to
//! the file's values the model is the file's model, and the frozen-parameter step Jacobian of
//! [`marsden::sensitivity::ParametricIntegrator`] (with constraints, compiled over
//! `[q₁ … qₙ, θ₁ … θ_P]`, [`marsden::sensitivity::ConstrainedParametricIntegrator`]) gives `∂(q_{k+1}, p_{k+1})/∂θ` beside the
//! state columns ([MW01] §1.5: the step is the solution of the discrete Euler–Lagrange
//! equations; the implicit function theorem differentiates it).
//!
//! [MW01]: marsden#references

use marsden::Scalar;
use marsden::numerics::ad::{self, MultiFunction};
use marsden::numerics::scratch::with_slice;
use marsden::sensitivity::ParametricModel;
use marsden_expr::{Expr, Program, Symbols};

use crate::model::ForceInputs;
use crate::model::hamiltonian::cotangent_inputs;
use crate::model::slots::tangent_inputs;

/// A Lagrangian and forces compiled over `[q, q̇, t, θ]`.
#[derive(Debug, Clone, PartialEq)]
pub struct ExprParametric {
    dof: usize,
    names: Vec<String>,
    lagrangian: Program,
    forces: Vec<Program>,
    /// What the forces read: `[q, q̇, t, θ]`, or `[q, p, t, θ]` for forces written in the
    /// momenta (`f_L = f_H ∘ FL`, with `FL` the parametric Lagrangian's).
    force_inputs: ForceInputs,
    /// The constraints `φ(q; θ)`, compiled over `[q, θ]`.
    constraints: Vec<Program>,
}

/// The texts of a model and the names they are compiled against.
#[derive(Debug, Clone, Copy)]
pub struct ParametricTexts<'a> {
    /// The Lagrangian's text and the coordinate names it uses.
    pub lagrangian: (&'a str, &'a [String]),
    /// One force text per coordinate (empty: no force) and the coordinate names they use.
    pub forces: (&'a [&'a str], &'a [String]),
    /// Whether the force texts read the velocities or the momenta.
    pub force_inputs: ForceInputs,
    /// One text per holonomic constraint `φ(q) = 0` (empty: none), over the coordinates of
    /// the forces.
    pub constraints: &'a [&'a str],
    /// Every scalar parameter with its value.
    pub constants: &'a [(String, f64)],
}

impl ExprParametric {
    /// Compiles `texts` with the parameters `names` as inputs (in that order) and every other
    /// parameter as a constant.
    ///
    /// # Errors
    /// A text that does not parse or compile (it compiled with the parameters as constants,
    /// so this does not happen for a validated file).
    pub fn compile(texts: ParametricTexts<'_>, names: &[String]) -> Result<Self, String> {
        let (l_text, l_coordinates) = texts.lagrangian;
        let l_inputs = tangent_inputs(l_coordinates);
        let l_symbols = symbols(l_inputs, texts.constants, names)?;
        let lagrangian = compile(l_text, &l_symbols)?;
        let (f_texts, f_coordinates) = texts.forces;
        let f_inputs = match texts.force_inputs {
            ForceInputs::Velocities => tangent_inputs(f_coordinates),
            ForceInputs::Momenta => cotangent_inputs(f_coordinates),
        };
        let f_symbols = symbols(f_inputs, texts.constants, names)?;
        let forces = f_texts
            .iter()
            .map(|text| compile(text, &f_symbols))
            .collect::<Result<Vec<_>, _>>()?;
        let c_symbols = constraint_symbols(f_coordinates, texts.constants, names)?;
        let constraints = (texts.constraints.iter())
            .map(|text| compile(text, &c_symbols))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self {
            dof: l_coordinates.len(),
            names: names.to_vec(),
            lagrangian,
            forces,
            force_inputs: texts.force_inputs,
            constraints,
        })
    }

    /// Whether any force text reads parameter `name`.
    pub fn force_uses(&self, name: &str) -> bool {
        self.forces
            .iter()
            .any(|f| f.names().iter().any(|n| n == name))
    }
}

/// `inputs` (`[q, q̇, t]` or `[q, p, t]`), `names` as inputs after them, the other parameters
/// as constants.
fn symbols(
    inputs: Vec<String>,
    constants: &[(String, f64)],
    names: &[String],
) -> Result<Symbols, String> {
    let first = inputs.len();
    let mut symbols = Symbols::with_inputs(&inputs).map_err(|e| e.to_string())?;
    for (j, name) in names.iter().enumerate() {
        symbols
            .add_input(name, first + j)
            .map_err(|e| e.to_string())?;
    }
    for (name, value) in constants.iter().filter(|(c, _)| !names.contains(c)) {
        symbols
            .add_constant(name, *value)
            .map_err(|e| e.to_string())?;
    }
    Ok(symbols)
}

/// `[q]` as inputs, `names` after them, the other parameters as constants.
fn constraint_symbols(
    coordinates: &[String],
    constants: &[(String, f64)],
    names: &[String],
) -> Result<Symbols, String> {
    let mut symbols = Symbols::with_inputs(coordinates).map_err(|e| e.to_string())?;
    for (j, name) in names.iter().enumerate() {
        symbols
            .add_input(name, coordinates.len() + j)
            .map_err(|e| e.to_string())?;
    }
    for (name, value) in constants.iter().filter(|(c, _)| !names.contains(c)) {
        symbols
            .add_constant(name, *value)
            .map_err(|e| e.to_string())?;
    }
    Ok(symbols)
}

fn compile(text: &str, symbols: &Symbols) -> Result<Program, String> {
    Expr::parse(text)
        .and_then(|e| e.compile(symbols))
        .map_err(|e| format!("`{text}`: {e}"))
}

/// Calls `body` with `[q, v, t, θ]`.
fn with_parametric_inputs<S: Scalar, R>(
    q: &[S],
    v: &[S],
    t: S,
    theta: &[S],
    body: impl FnOnce(&[S]) -> R,
) -> R {
    let n = q.len();
    with_slice(2 * n + 1 + theta.len(), t, |x| {
        x[..n].copy_from_slice(q);
        x[n..2 * n].copy_from_slice(v);
        x[2 * n + 1..].copy_from_slice(theta);
        body(x)
    })
}

/// The parametric Lagrangian as a function of all its inputs `z = [q, q̇, t, θ]`, for the
/// nested-dual gradient `p = ∂L/∂q̇(t, q, q̇; θ)` at any scalar type (θ's duals included).
struct OnInputs<'a>(&'a ExprParametric);

impl MultiFunction for OnInputs<'_> {
    fn inputs(&self) -> usize {
        2 * self.0.dof + 1 + self.0.names.len()
    }
    fn outputs(&self) -> usize {
        1
    }
    fn eval<S: Scalar>(&self, z: &[S], out: &mut [S]) {
        out[0] = self.0.lagrangian.eval(z);
    }
}

impl ExprParametric {
    /// `f_L(t, q, q̇; θ) = f_H(t, q, FL(t, q, q̇; θ); θ)` of forces written in the momenta: the
    /// momenta are the parametric Lagrangian's (`f_L = f_H ∘ FL`, [MW01] §3.1), so a
    /// parameter of `L` reaches the force through `p` as well.
    ///
    /// [MW01]: marsden#references
    fn momentum_force<S: Scalar>(&self, theta: &[S], t: S, q: &[S], v: &[S], out: &mut [S]) {
        let n = q.len();
        let mut p = vec![S::from(0.0); n];
        with_parametric_inputs(q, v, t, theta, |z| {
            ad::nested_gradient(&OnInputs(self), z, n..2 * n, &mut p);
        });
        with_parametric_inputs(q, &p, t, theta, |x| {
            for (f, program) in out.iter_mut().zip(&self.forces) {
                *f = program.eval(x);
            }
        });
    }
}

impl ParametricModel for ExprParametric {
    fn dof(&self) -> usize {
        self.dof
    }

    fn parameter_names(&self) -> Vec<String> {
        self.names.clone()
    }

    fn lagrangian_with<S: Scalar>(&self, theta: &[S], t: S, q: &[S], v: &[S]) -> S {
        with_parametric_inputs(q, v, t, theta, |x| self.lagrangian.eval(x))
    }

    fn force_with<S: Scalar>(&self, theta: &[S], t: S, q: &[S], v: &[S], out: &mut [S]) {
        if self.forces.is_empty() {
            out.iter_mut().for_each(|f| *f = S::from(0.0));
            return;
        }
        if self.force_inputs == ForceInputs::Momenta {
            return self.momentum_force(theta, t, q, v, out);
        }
        with_parametric_inputs(q, v, t, theta, |x| {
            for (f, program) in out.iter_mut().zip(&self.forces) {
                *f = program.eval(x);
            }
        });
    }

    fn is_forced(&self) -> bool {
        !self.forces.is_empty()
    }

    fn constraints(&self) -> usize {
        self.constraints.len()
    }

    fn constraint_with<S: Scalar>(&self, theta: &[S], q: &[S], out: &mut [S]) {
        let n = q.len();
        let fill = q.first().or(theta.first()).copied().unwrap_or(S::from(0.0));
        with_slice(n + theta.len(), fill, |x| {
            x[..n].copy_from_slice(q);
            x[n..].copy_from_slice(theta);
            for (phi, program) in out.iter_mut().zip(&self.constraints) {
                *phi = program.eval(x);
            }
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parameters_become_inputs_after_t() {
        let coordinates = vec!["x".to_owned()];
        let constants = vec![("k".to_owned(), 4.0), ("c".to_owned(), 0.5)];
        let texts = ParametricTexts {
            lagrangian: ("0.5*x_dot^2 - 0.5*k*x^2", &coordinates),
            forces: (&["-c*x_dot"], &coordinates),
            force_inputs: ForceInputs::Velocities,
            constraints: &["x^2 - k"],
            constants: &constants,
        };
        let model = ExprParametric::compile(texts, &["k".to_owned()]).unwrap();
        // L(t, x = 1, v = 2; k = 9) = 2 − 4.5; the force keeps c = 0.5 as a constant.
        assert_eq!(model.lagrangian_with(&[9.0], 0.0, &[1.0], &[2.0]), -2.5);
        let mut f = [0.0];
        model.force_with(&[9.0], 0.0, &[1.0], &[2.0], &mut f);
        assert_eq!(f, [-1.0]);
        assert!(!model.force_uses("k"));
        // φ(x = 3; k = 9) = 0 over `[x, k]`.
        let mut phi = [1.0];
        model.constraint_with(&[9.0], &[3.0], &mut phi);
        assert_eq!(phi, [0.0]);
    }
}
