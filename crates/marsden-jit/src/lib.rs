//! Native code for [`marsden_expr::Tape`]s, compiled at run time with Cranelift.
//!
//! A tape is a straight-line register program (the symbolic gradient or Hessian of a
//! potential); [`CompiledTape::compile`] translates it instruction by instruction into one
//! native function `(inputs, outputs)`, with every register an SSA value that the register
//! allocator keeps in machine registers where it can. The values are those of the tape's
//! interpreter bit for bit: the arithmetic is the same IEEE 754 operations in the same order
//! (a fused `a · b + c` rounds the product first; no fused multiply–add is ever emitted), `√`
//! is the correctly rounded machine instruction, and every other function (`sin`, `xⁿ`,
//! `atan2`, …) is a call to the very `f64` function the interpreter calls
//! ([`marsden_expr::tape_f64`]).
//!
//! [`CompiledVerlet`] compiles a whole velocity Störmer–Verlet run of a separable Lagrangian
//! with a diagonal mass, the gradient tape inside its loop (`marsden::mechanics::kernel`): the
//! state stays in registers from step to step, and the numbers are the generic Rust loop's bit
//! for bit.
//!
//! Where Cranelift has no back end for the host, or compilation fails, [`CompiledTape::compile`]
//! returns a [`JitError`] and the caller keeps the interpreter.
//!
//! ```
//! use marsden_expr::{Program, Symbols};
//! use marsden_jit::CompiledTape;
//!
//! let symbols = Symbols::with_inputs(["x", "y", "x_dot", "y_dot", "t"]).unwrap();
//! let program = Program::compile("0.5*(x_dot^2 + y_dot^2) + 1/sqrt(x^2 + y^2)", &symbols).unwrap();
//! let form = program.separable(2).unwrap();
//! let tape = form.gradient().unwrap();
//! let (mut regs, mut expected) = (Vec::new(), vec![0.0_f64; 2]);
//! tape.eval_into(&[0.6, 0.8, 0.0], &mut regs, &mut expected);
//! if let Ok(native) = CompiledTape::compile(tape) {
//!     let mut grad = [0.0; 2];
//!     native.eval(&[0.6, 0.8, 0.0], &mut grad);
//!     assert_eq!(grad.map(f64::to_bits), [expected[0].to_bits(), expected[1].to_bits()]);
//! }
//! ```

mod compile;
mod functions;
mod native;
mod timing;
mod verlet;

pub use compile::JitError;
pub use native::{CompiledTape, CompiledVerlet, VerletGrid};
pub use timing::compile_seconds;
