//! The expression language of problem files: Lagrangians, Hamiltonians, forces, constraints
//! and symmetry generators written as formulas, compiled once and evaluated generically over
//! [`marsden::Scalar`] (at `f64` for values, at num-dual's dual numbers for exact derivatives).
//!
//! # Grammar
//!
//! ```ebnf
//! expr    = term , { ( "+" | "-" ) , term } ;
//! term    = unary , { ( "*" | "/" ) , unary } ;
//! unary   = ( "-" | "+" ) , unary | power ;
//! power   = primary , [ "^" , unary ] ;            (* right-associative: 2^3^2 = 2^9 *)
//! primary = number | call | name | "(" , expr , ")" ;
//! call    = name , "(" , [ expr , { "," , expr } ] , ")" ;
//! number  = ( digits , [ "." , [ digits ] ] | "." , digits ) , [ exponent ] ;
//! exponent = ( "e" | "E" ) , [ "+" | "-" ] , digits ;
//! name    = ( letter | "_" ) , { letter | digit | "_" } ;
//! ```
//!
//! Whitespace may appear between tokens. Because `power` binds tighter than `unary`,
//! `-x^2 = -(x^2)` and `-2^2 = -4`; the exponent may itself be signed (`2^-1 = 0.5`).
//! There is no implicit multiplication (`2x` is an error).
//!
//! Built-ins: the constant `pi`, and the functions `sin cos tan asin acos atan atan2 sinh cosh
//! tanh exp log sqrt abs pow`. `atan2(y, x)` and `pow(x, y)` take two arguments, the others
//! one; `log` is the natural logarithm. Every other name is looked up in a caller-supplied
//! [`Symbols`] table, where it is either an input slot (a coordinate, velocity, momentum or
//! time, supplied at evaluation) or a constant (a parameter, folded at compile time).
//!
//! # Evaluation model
//!
//! [`Expr::parse`] builds a syntax tree; [`Expr::compile`] resolves names, folds constants
//! (parameters and numeric subexpressions, merged across products and sums, see `ir`) and
//! generates a short instruction list for an accumulator machine. Integer constant powers
//! become `powi` (exact and cheap for duals and negative bases), `x^0.5` becomes `sqrt`, other
//! constant exponents `powf`, and variable exponents `powd` (`exp(y ln x)` for dual numbers, so
//! the base must be positive where derivatives are taken).
//! [`Program::eval`] runs the instructions for any `S: Scalar`: no strings, no lookups, and no
//! allocation for programs whose stack depth (computed at compile time) is at most 16.
//!
//! # Errors
//!
//! [`ExprError`] carries an [`ErrorKind`], the text and the [`Span`] at fault; its `Display`
//! shows the expression with a caret under the mistake, plus "did you mean" suggestions and
//! the list of known names or functions where that helps.
//!
//! # Example: a Lagrangian from a problem file
//!
//! ```
//! use marsden_expr::{Expr, Symbols};
//!
//! // [problem] coordinates = ["theta"], parameters = { m = 1.0, l = 0.5, g = 9.81 }
//! let coords = ["theta"];
//! let inputs = coords.iter().map(|q| q.to_string())
//!     .chain(coords.iter().map(|q| format!("{q}_dot")));
//! let mut symbols = Symbols::with_inputs(inputs).unwrap();   // theta → 0, theta_dot → 1
//! for (name, value) in [("m", 1.0), ("l", 0.5), ("g", 9.81)] {
//!     symbols.add_constant(name, value).unwrap();
//! }
//! let expr = Expr::parse("0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)").unwrap();
//! let lagrangian = expr.compile(&symbols).unwrap();
//! let l: f64 = lagrangian.eval(&[0.3, 2.0]);
//! assert!((l - (0.5 * 0.25 * 4.0 + 9.81 * 0.5 * 0.3_f64.cos())).abs() < 1e-12);
//!
//! // Errors point at the mistake:
//! let err = Expr::parse("0.5*m*l^2*theta_dot^2 + * cos(theta)").unwrap_err();
//! assert_eq!(err.to_string(), "\
//! error: expected an operand after '+', found '*'
//!   0.5*m*l^2*theta_dot^2 + * cos(theta)
//!                           ^");
//! ```

//! # Map of the crate
//!
//! Text flows down; every module imports only modules below it.
//!
//! | stage | module | what |
//! |---|---|---|
//! | entry points | `pipeline` | [`Expr::parse`], [`Expr::compile`], [`Program::compile`] |
//! | several expressions | `set` | [`ProgramSet`]: one inputs slice, one output slice |
//! | compiled program | `program` | [`Program`]: evaluate, inspect, list the instructions |
//! | structure | `separable`, `quadratic` | [`SeparableForm`]: `L = ½ vᵀMv − V` recognised exactly |
//! | two-point expressions | `displacement` | [`DisplacementForm`]: `L_d(q₀, q₁)` in `(q₀, q₁ − q₀)`, as the rules evaluate it |
//! | symbolic derivatives | `derive`, `tape` | `∇V`, `∇²V` as a [`Tape`]: shared subexpressions, registers, fused constants and superinstructions |
//! | interpreter | `eval` | the accumulator machine over any `S: Scalar`, no allocation |
//! | code generation | `codegen`, `ops` | folded tree → instructions (Sethi–Ullman order, fused pairs) |
//! | lowering | `lower`, `ir` | names resolved, constants folded (the normal form of `ir`) |
//! | parsing | `parser`, `ast`, `lexer` | text → tokens → syntax tree with spans |
//! | names | `symbols`, `functions` | [`Symbols`] (inputs and constants), built-ins, [`is_reserved`] |
//! | errors | `error`, `suggest` | [`ExprError`] with the caret; [`closest`] for "did you mean" |

mod ast;
mod codegen;
mod derive;
mod displacement;
mod error;
mod eval;
mod functions;
mod ir;
mod jet;
mod lexer;
mod lower;
mod ops;
mod parser;
mod pipeline;
mod program;
mod quadratic;
mod separable;
mod set;
mod suggest;
mod symbols;
mod tape;

pub use ast::Identifier;
pub use displacement::DisplacementForm;
pub use error::{ErrorKind, EvalError, ExprError, Span, SymbolError};
pub use functions::{CONSTANTS, Function, is_reserved};
pub use jet::Jet;
pub use pipeline::Expr;
pub use program::Program;
pub use separable::SeparableForm;
pub use set::ProgramSet;
pub use suggest::closest;
pub use symbols::{Symbol, Symbols, is_identifier};
pub use tape::{Tape, TapeOp};

/// The `f64` functions a [`Tape`]'s interpreter calls, for code generators that must match it.
pub mod tape_f64 {
    pub use crate::tape::{atan2_f64, call_f64, powd_f64, powf_f64, powi_f64};
}
