//! [`ProgramSet`]: several expressions over the same inputs, evaluated into a slice.

use marsden::Scalar;

use crate::error::{EvalError, ExprError};
use crate::program::Program;
use crate::symbols::Symbols;

/// Several compiled expressions that share one symbol table and one inputs slice: the
/// components of a force, a list of constraints, the components of a symmetry generator.
///
/// ```
/// use marsden_expr::{ProgramSet, Symbols};
/// let mut symbols = Symbols::with_inputs(["x", "y"]).unwrap();
/// symbols.add_constant("k", 2.0).unwrap();
/// let force = ProgramSet::compile(["-k*x", "-k*y"], &symbols).unwrap();
/// let mut out = [0.0; 2];
/// force.eval_into(&[1.0, 3.0], &mut out);
/// assert_eq!(out, [-2.0, -6.0]);
/// ```
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ProgramSet {
    programs: Vec<Program>,
}

impl ProgramSet {
    /// Compile every text against `symbols`. An error is labelled `expression [i]` with the
    /// index of the failing text (relabel it with [`ExprError::with_context`]).
    pub fn compile<I>(texts: I, symbols: &Symbols) -> Result<ProgramSet, ExprError>
    where
        I: IntoIterator,
        I::Item: AsRef<str>,
    {
        let programs = texts
            .into_iter()
            .enumerate()
            .map(|(i, text)| {
                Program::compile(text.as_ref(), symbols)
                    .map_err(|e| e.with_context(format!("expression [{i}]")))
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(ProgramSet { programs })
    }

    /// A set made of already compiled programs.
    pub fn from_programs(programs: Vec<Program>) -> ProgramSet {
        ProgramSet { programs }
    }

    /// Number of expressions (the length of the output).
    pub fn len(&self) -> usize {
        self.programs.len()
    }

    /// Whether the set has no expressions.
    pub fn is_empty(&self) -> bool {
        self.programs.is_empty()
    }

    /// The compiled expressions, in order.
    pub fn programs(&self) -> &[Program] {
        &self.programs
    }

    /// The minimum length of the inputs slice over all expressions.
    pub fn input_len(&self) -> usize {
        self.programs
            .iter()
            .map(Program::input_len)
            .max()
            .unwrap_or(0)
    }

    /// The declared names used by any expression, sorted and without duplicates.
    pub fn names(&self) -> Vec<&str> {
        let mut names: Vec<&str> = self
            .programs
            .iter()
            .flat_map(|p| p.names())
            .map(String::as_str)
            .collect();
        names.sort_unstable();
        names.dedup();
        names
    }

    /// Evaluate every expression at `inputs`, writing expression `i` to `out[i]`.
    ///
    /// # Panics
    ///
    /// If `out.len() != self.len()` or `inputs` is shorter than [`ProgramSet::input_len`];
    /// [`ProgramSet::try_eval_into`] reports these as errors instead.
    #[inline]
    pub fn eval_into<S: Scalar>(&self, inputs: &[S], out: &mut [S]) {
        assert_eq!(
            out.len(),
            self.len(),
            "output slice length must equal the number of expressions"
        );
        for (program, slot) in self.programs.iter().zip(out) {
            *slot = program.eval(inputs);
        }
    }

    /// Evaluate every expression at `inputs` into `out`, or report a length mismatch.
    pub fn try_eval_into<S: Scalar>(&self, inputs: &[S], out: &mut [S]) -> Result<(), EvalError> {
        if out.len() != self.len() {
            return Err(EvalError::OutputLength {
                needed: self.len(),
                given: out.len(),
            });
        }
        for (program, slot) in self.programs.iter().zip(out) {
            *slot = program.try_eval(inputs)?;
        }
        Ok(())
    }

    /// Evaluate every expression at `inputs` into a new vector.
    ///
    /// # Panics
    ///
    /// If `inputs` is shorter than [`ProgramSet::input_len`].
    pub fn eval<S: Scalar>(&self, inputs: &[S]) -> Vec<S> {
        self.programs.iter().map(|p| p.eval(inputs)).collect()
    }
}
