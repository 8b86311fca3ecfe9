//! [`Tape`]: several expressions over one inputs slice, with their common subexpressions
//! evaluated once, by a register machine.
//!
//! The folded trees of the outputs are merged into one directed acyclic graph (`build`), then
//! laid out as a straight-line program over registers `[inputs | one per instruction]`
//! (`lower`). Evaluating runs each instruction once, in order: no stack, no repeated work, no
//! constant in a register (constant operands are part of the instructions), and the commonest
//! shapes of symbolic derivatives (`a·b + c`, `a² + b²`, `(a·b)/c`, …) as one instruction each. This is the
//! form of the symbolic gradient and Hessian of a potential, whose entries share most of their
//! terms (`r = √(x² + y²)` in every entry of the Kepler gradient).
//!
//! [`Tape::plain`] gives the same tape without the fused instructions (every constant loaded
//! into a register, one instruction per operation): the reference the fused layout is tested
//! against, bit for bit.

mod build;
mod lower;
mod view;

use marsden::Scalar;

use crate::functions::{Unary, atan2, powd, powf};

pub(crate) use build::TapeBuilder;
pub use view::{TapeOp, atan2_f64, call_f64, powd_f64, powf_f64, powi_f64};

/// One instruction; operands are register indices (all smaller than the instruction's own).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Instr {
    /// A constant (only where no constant form of the operation exists, or as an output).
    Load(f64),
    Neg(u32),
    Add(u32, u32),
    Sub(u32, u32),
    Mul(u32, u32),
    Div(u32, u32),
    /// `a + c`.
    AddC(u32, f64),
    /// `a − c`.
    SubC(u32, f64),
    /// `c − a`.
    CSub(f64, u32),
    /// `a · c`.
    MulC(u32, f64),
    /// `a / c`.
    DivC(u32, f64),
    /// `c / a`.
    CDiv(f64, u32),
    Square(u32),
    Call(Unary, u32),
    Powi(u32, i32),
    Powf(u32, f64),
    Powd(u32, u32),
    Atan2(u32, u32),
    /// `a · b + c` (the product rounded first).
    MulAdd(u32, u32, u32),
    /// `a² + b²`.
    SumSquares(u32, u32),
    /// `a · b − c`.
    MulSub(u32, u32, u32),
    /// `c − a · b` (operands in that order).
    SubMul(u32, u32, u32),
    /// `(a · b) · c`.
    Mul3(u32, u32, u32),
    /// `(a · b) / c`.
    MulDiv(u32, u32, u32),
}

/// Straight-line code for several outputs sharing their common subexpressions.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Tape {
    inputs: usize,
    instrs: Vec<Instr>,
    outputs: Vec<u32>,
    /// The same outputs without fused instructions ([`Tape::plain`]).
    plain: Option<Box<Tape>>,
}

impl Tape {
    /// The tape of `graph`: fused, with its plain layout kept for [`Tape::plain`].
    fn from_graph(graph: build::Graph) -> Tape {
        let (plain_instrs, plain_outputs) = lower::lower(&graph, false);
        let (instrs, outputs) = lower::lower(&graph, true);
        let plain = Tape {
            inputs: graph.inputs,
            instrs: plain_instrs,
            outputs: plain_outputs,
            plain: None,
        };
        Tape {
            inputs: graph.inputs,
            instrs,
            outputs,
            plain: Some(Box::new(plain)),
        }
    }

    /// The same outputs without fused instructions: every constant in a register, one
    /// instruction per operation (the layout the fused one is checked against; bit for bit
    /// the same values at `f64`).
    pub fn plain(&self) -> &Tape {
        self.plain.as_deref().unwrap_or(self)
    }

    /// Number of outputs.
    pub fn len(&self) -> usize {
        self.outputs.len()
    }

    /// Whether the tape has no outputs.
    pub fn is_empty(&self) -> bool {
        self.outputs.is_empty()
    }

    /// Number of instructions (after sharing and fusing).
    pub fn op_count(&self) -> usize {
        self.instrs.len()
    }

    /// The minimum length of the inputs slice.
    pub fn input_len(&self) -> usize {
        self.inputs
    }

    /// Number of registers an evaluation uses (the length [`Tape::eval_into`] gives `regs`).
    pub fn registers(&self) -> usize {
        self.inputs + self.instrs.len()
    }

    /// Evaluates every output at `inputs` into `out` (length [`Tape::len`]); `regs` is
    /// workspace (keep it between calls to avoid allocating).
    ///
    /// # Panics
    ///
    /// If `inputs` is shorter than [`Tape::input_len`].
    #[inline]
    pub fn eval_into<S: Scalar>(&self, inputs: &[S], regs: &mut Vec<S>, out: &mut [S]) {
        regs.clear();
        regs.extend_from_slice(&inputs[..self.inputs]);
        self.run(regs, out);
    }

    /// [`Tape::eval_into`] with the inputs already in `regs` (at least [`Tape::input_len`]
    /// values; the rest is overwritten), which saves a copy.
    ///
    /// # Panics
    ///
    /// If `regs` is shorter than [`Tape::input_len`].
    #[inline]
    pub fn eval_in_place<S: Scalar>(&self, regs: &mut Vec<S>, out: &mut [S]) {
        assert!(
            regs.len() >= self.inputs,
            "a tape needs {} inputs",
            self.inputs
        );
        regs.truncate(self.inputs);
        self.run(regs, out);
    }

    /// Runs the instructions; `regs` holds exactly the inputs.
    #[inline]
    fn run<S: Scalar>(&self, regs: &mut Vec<S>, out: &mut [S]) {
        regs.reserve(self.instrs.len());
        for ins in &self.instrs {
            let value = step(*ins, regs);
            regs.push(value);
        }
        for (slot, &reg) in out.iter_mut().zip(&self.outputs) {
            *slot = regs[reg as usize];
        }
    }
}

/// The value of one instruction over the registers computed so far.
#[inline(always)]
fn step<S: Scalar>(ins: Instr, regs: &[S]) -> S {
    let r = |i: u32| regs[i as usize];
    match ins {
        Instr::Load(c) => S::from(c),
        Instr::Neg(a) => -r(a),
        Instr::Add(a, b) => r(a) + r(b),
        Instr::Sub(a, b) => r(a) - r(b),
        Instr::Mul(a, b) => r(a) * r(b),
        Instr::Div(a, b) => r(a) / r(b),
        Instr::AddC(a, c) => {
            let mut v = r(a);
            v += c;
            v
        }
        Instr::SubC(a, c) => {
            let mut v = r(a);
            v -= c;
            v
        }
        Instr::CSub(c, a) => S::from(c) - r(a),
        Instr::MulC(a, c) => {
            let mut v = r(a);
            v *= c;
            v
        }
        // Not `v /= c`: num-dual divides by an `f64` as a product with its reciprocal, which
        // rounds differently from the division the plain layout does.
        Instr::DivC(a, c) => r(a) / S::from(c),
        Instr::CDiv(c, a) => S::from(c) / r(a),
        Instr::Square(a) => r(a) * r(a),
        Instr::Call(f, a) => f.apply(r(a)),
        Instr::Powi(a, n) => r(a).powi(n),
        Instr::Powf(a, e) => powf(r(a), e),
        Instr::Powd(a, b) => powd(r(a), r(b)),
        Instr::Atan2(a, b) => atan2(r(a), r(b)),
        Instr::MulAdd(a, b, c) => r(a) * r(b) + r(c),
        Instr::SumSquares(a, b) => r(a) * r(a) + r(b) * r(b),
        Instr::MulSub(a, b, c) => r(a) * r(b) - r(c),
        Instr::SubMul(c, a, b) => r(c) - r(a) * r(b),
        Instr::Mul3(a, b, c) => r(a) * r(b) * r(c),
        Instr::MulDiv(a, b, c) => r(a) * r(b) / r(c),
    }
}
