//! `[system] hamiltonian = "…"`: `H(t, q, p)` written with the coordinates, their momenta
//! `p_<coordinate>` and `t`, compiled and turned into the Lagrangian the run uses
//! ([`crate::model::hamiltonian`]).
//!
//! The Lagrangian of a general `H` is `L = ⟨p, v⟩ − H` at `∂H/∂p = v`, each evaluation an inner
//! Newton solve. A separable `H = ½ pᵀ K p + V(t, q)` (a constant symmetric positive definite
//! `K`, no term linear in `p`; recognised exactly by [`Program::separable`]) has the closed
//! form `L = ½ vᵀ K⁻¹ v − V(t, q)` ([MW01] §1.5: `FL` is the inverse of `FH = K p`): that `L` is
//! compiled as an expression Lagrangian, `V = H(t, q, 0)`, and the run takes the separable fast
//! paths of any other expression `L` — the same map of `T*Q`, to round-off, at a fraction of
//! the cost.
//!
//! [MW01]: marsden#references

use toml::Spanned;

use super::check::Checker;
use super::parameters::{self, Parameters};
use super::raw::RawSystem;
use super::resolved::{Resolved, symbols};
use super::spec::{HamiltonianSpec, LagrangianSpec};
use crate::error::Diagnostic;
use crate::model::hamiltonian::{cotangent_inputs, momentum_name};
use crate::model::slots::{tangent_inputs, velocity_name};
use crate::model::{ExprHamiltonian, ExprLagrangian};
use marsden::hamiltonian::HamiltonianLagrangian;
use marsden::numerics::dense::Lu;
use marsden_expr::{Program, Symbols};

/// Validates and compiles `hamiltonian = "…"` (with `coordinates` and number parameters).
pub(super) fn expression(
    ck: &Checker<'_>,
    text: &Spanned<String>,
    system: &RawSystem,
    params: &Parameters,
) -> Result<Resolved, Diagnostic> {
    let help = "e.g. `coordinates = [\"theta\"]`; momenta are then named `p_theta`";
    let coordinates = parameters::expression_coordinates(ck, "hamiltonian", text, system, help)?;
    params.numbers_only(ck, "an expression Hamiltonian")?;
    let constants: Vec<(String, f64)> = params
        .numbers
        .iter()
        .map(|w| (w.name.clone(), w.value))
        .collect();
    let expr = ck.parse_expr("[system] hamiltonian", text)?;
    let symbols = symbols(ck, cotangent_inputs(&coordinates), &constants, params)?;
    let program: Program = expr
        .compile(&symbols)
        .map_err(|e| ck.expr_error("[system] hamiltonian", text, &e))?;
    let n = coordinates.len();
    let reads_momenta = (n..2 * n).all(|slot| program.inputs_used().contains(&slot));
    if !reads_momenta {
        return Err(ck
            .error(
                Some(text.span()),
                "the Hamiltonian is not regular: some momentum `p_<coordinate>` does not appear in it",
            )
            .help("∂²H/∂p² must be invertible for the run to go through L = ⟨p, v⟩ − H"));
    }
    let separable = separable_lagrangian(text.get_ref(), &program, &coordinates, &constants);
    let general = HamiltonianLagrangian::new(ExprHamiltonian::new(program, n));
    let h = LagrangianSpec::Hamiltonian(Box::new(HamiltonianSpec { general, separable }));
    Ok(Resolved::expression(h, coordinates, constants))
}

/// For a separable `H = ½ pᵀ K p + V(t, q)`: `L = ½ vᵀ K⁻¹ v − V(t, q)` compiled as an expression
/// Lagrangian (`V` is `H`'s own text with every momentum a constant 0); `None` for any other `H`,
/// or if `K` cannot be inverted (the run then goes through `L = ⟨p, v⟩ − H`).
fn separable_lagrangian(
    text: &str,
    program: &Program,
    coordinates: &[String],
    constants: &[(String, f64)],
) -> Option<ExprLagrangian> {
    let n = coordinates.len();
    let form = program.separable(n)?;
    let inverse = inverse(form.mass(), n)?;
    let velocities: Vec<String> = coordinates.iter().map(|c| velocity_name(c)).collect();
    let kinetic: Vec<String> = (0..n)
        .flat_map(|i| (0..n).map(move |j| (i, j)))
        .filter(|&(i, j)| inverse[i * n + j] != 0.0)
        .map(|(i, j)| {
            let (entry, vi, vj) = (inverse[i * n + j], &velocities[i], &velocities[j]);
            format!("({entry:e})*{vi}*{vj}")
        })
        .collect();
    let lagrangian = format!("0.5*({}) - ({text})", kinetic.join(" + "));
    let mut symbols = Symbols::with_inputs(tangent_inputs(coordinates)).ok()?;
    let momenta = coordinates.iter().map(|c| (momentum_name(c), 0.0));
    for (name, value) in constants.iter().cloned().chain(momenta) {
        symbols.add_constant(&name, value).ok()?;
    }
    let program = Program::compile(&lagrangian, &symbols).ok()?;
    Some(ExprLagrangian::new(program, n))
}

/// `K⁻¹` of the `n × n` row-major `k`, column by column from its LU factors; `None` if singular.
fn inverse(k: &[f64], n: usize) -> Option<Vec<f64>> {
    let mut lu = Lu::new();
    lu.factor(k, n).ok()?;
    let (mut inverse, mut scratch) = (vec![0.0; n * n], Vec::with_capacity(n));
    for j in 0..n {
        let mut column: Vec<f64> = (0..n).map(|i| f64::from(u8::from(i == j))).collect();
        lu.solve(&mut column, &mut scratch);
        for (i, x) in column.into_iter().enumerate() {
            inverse[i * n + j] = x;
        }
    }
    Some(inverse)
}
