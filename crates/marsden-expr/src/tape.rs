//! [`Tape`]: several expressions over one inputs slice, with their common subexpressions
//! evaluated once, by a register machine.
//!
//! The folded trees of the outputs are merged into one directed acyclic graph by hash-consing
//! (a node equal to one already built is the same register; the operands of `+` and `·` are
//! ordered first, which is exact), then laid out as a straight-line program over registers
//! `[inputs | constants | one per operation]`. Evaluating copies the inputs and constants into
//! the registers and runs each operation once, in order: no stack, no repeated work. This is
//! the form of the symbolic gradient and Hessian of a potential, whose entries share most of
//! their terms (`r = √(x² + y²)` in every entry of the Kepler gradient).

use std::collections::HashMap;

use marsden::Scalar;

use crate::functions::{Unary, atan2, powd};
use crate::ir::{Arith, Node};

/// One operation; operands are register indices (all smaller than the operation's own).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Instr {
    Neg(u32),
    Add(u32, u32),
    Sub(u32, u32),
    Mul(u32, u32),
    Div(u32, u32),
    Square(u32),
    Call(Unary, u32),
    Powi(u32, i32),
    Powf(u32, f64),
    Powd(u32, u32),
    Atan2(u32, u32),
}

/// A register while the graph is built: inputs, constants and operations are numbered apart
/// and placed at the end.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
enum Ref {
    Input(u32),
    Const(u32),
    Op(u32),
}

/// The hash-consing key of an operation (constants by their bits).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
enum Key {
    Neg(Ref),
    Bin(u8, Ref, Ref),
    Call(u8, Ref),
    Powi(Ref, i32),
    Powf(Ref, u64),
    Powd(Ref, Ref),
    Atan2(Ref, Ref),
}

/// Straight-line code for several outputs sharing their common subexpressions.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Tape {
    inputs: usize,
    constants: Vec<f64>,
    instrs: Vec<Instr>,
    outputs: Vec<u32>,
}

impl Tape {
    /// Number of outputs.
    pub fn len(&self) -> usize {
        self.outputs.len()
    }

    /// Whether the tape has no outputs.
    pub fn is_empty(&self) -> bool {
        self.outputs.is_empty()
    }

    /// Number of operations (after sharing).
    pub fn op_count(&self) -> usize {
        self.instrs.len()
    }

    /// The minimum length of the inputs slice.
    pub fn input_len(&self) -> usize {
        self.inputs
    }

    /// Number of registers an evaluation uses (the length [`Tape::eval_into`] gives `regs`).
    pub fn registers(&self) -> usize {
        self.inputs + self.constants.len() + self.instrs.len()
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

    /// Runs the operations; `regs` holds exactly the inputs.
    #[inline]
    fn run<S: Scalar>(&self, regs: &mut Vec<S>, out: &mut [S]) {
        regs.extend(self.constants.iter().map(|&c| S::from(c)));
        for ins in &self.instrs {
            let r = |i: u32| regs[i as usize];
            let value = match *ins {
                Instr::Neg(a) => -r(a),
                Instr::Add(a, b) => r(a) + r(b),
                Instr::Sub(a, b) => r(a) - r(b),
                Instr::Mul(a, b) => r(a) * r(b),
                Instr::Div(a, b) => r(a) / r(b),
                Instr::Square(a) => r(a) * r(a),
                Instr::Call(f, a) => f.apply(r(a)),
                Instr::Powi(a, n) => r(a).powi(n),
                Instr::Powf(a, e) => crate::functions::powf(r(a), e),
                Instr::Powd(a, b) => powd(r(a), r(b)),
                Instr::Atan2(a, b) => atan2(r(a), r(b)),
            };
            regs.push(value);
        }
        for (slot, &reg) in out.iter_mut().zip(&self.outputs) {
            *slot = regs[reg as usize];
        }
    }
}

/// Builds a [`Tape`] output by output.
#[derive(Debug, Default)]
pub(crate) struct TapeBuilder {
    inputs: usize,
    constants: Vec<f64>,
    constant_index: HashMap<u64, u32>,
    ops: Vec<Key>,
    op_index: HashMap<Key, u32>,
    outputs: Vec<Ref>,
}

impl TapeBuilder {
    /// Adds `node` as the next output.
    pub(crate) fn output(&mut self, node: &Node) {
        let r = self.node(node);
        self.outputs.push(r);
    }

    /// The finished tape.
    pub(crate) fn finish(self) -> Tape {
        let (inputs, consts) = (self.inputs as u32, self.constants.len() as u32);
        let place = |r: Ref| match r {
            Ref::Input(i) => i,
            Ref::Const(c) => inputs + c,
            Ref::Op(k) => inputs + consts + k,
        };
        let instrs = self.ops.iter().map(|key| relocate(*key, place)).collect();
        Tape {
            inputs: self.inputs,
            constants: self.constants,
            instrs,
            outputs: self.outputs.into_iter().map(place).collect(),
        }
    }

    fn constant(&mut self, c: f64) -> Ref {
        let next = self.constants.len() as u32;
        let index = *self.constant_index.entry(c.to_bits()).or_insert(next);
        if index == next {
            self.constants.push(c);
        }
        Ref::Const(index)
    }

    fn op(&mut self, key: Key) -> Ref {
        let next = self.ops.len() as u32;
        let index = *self.op_index.entry(key).or_insert(next);
        if index == next {
            self.ops.push(key);
        }
        Ref::Op(index)
    }

    fn node(&mut self, node: &Node) -> Ref {
        match node {
            Node::Const(c) => self.constant(*c),
            Node::Input(slot) => {
                self.inputs = self.inputs.max(slot + 1);
                Ref::Input(*slot as u32)
            }
            Node::Neg(a) => {
                let a = self.node(a);
                self.op(Key::Neg(a))
            }
            Node::Bin(op, a, b) => {
                let (mut a, mut b) = (self.node(a), self.node(b));
                let commutes = matches!(op, Arith::Add | Arith::Mul);
                if commutes && b < a {
                    std::mem::swap(&mut a, &mut b);
                }
                self.op(Key::Bin(*op as u8, a, b))
            }
            Node::Unary(f, a) => {
                let a = self.node(a);
                self.op(Key::Call(unary_code(*f), a))
            }
            Node::Powi(a, n) => {
                let a = self.node(a);
                self.op(Key::Powi(a, *n))
            }
            Node::Powf(a, e) => {
                let a = self.node(a);
                self.op(Key::Powf(a, e.to_bits()))
            }
            Node::Powd(a, b) => {
                let (a, b) = (self.node(a), self.node(b));
                self.op(Key::Powd(a, b))
            }
            Node::Atan2(y, x) => {
                let (y, x) = (self.node(y), self.node(x));
                self.op(Key::Atan2(y, x))
            }
        }
    }
}

/// The unary functions in a fixed order (their code in a [`Key`]).
const UNARIES: [Unary; 13] = [
    Unary::Sin,
    Unary::Cos,
    Unary::Tan,
    Unary::Asin,
    Unary::Acos,
    Unary::Atan,
    Unary::Sinh,
    Unary::Cosh,
    Unary::Tanh,
    Unary::Exp,
    Unary::Ln,
    Unary::Sqrt,
    Unary::Abs,
];

fn unary_code(f: Unary) -> u8 {
    UNARIES.iter().position(|&u| u == f).unwrap_or(0) as u8
}

/// The instruction of `key` with its operands placed in the register file.
fn relocate(key: Key, place: impl Fn(Ref) -> u32) -> Instr {
    match key {
        Key::Neg(a) => Instr::Neg(place(a)),
        Key::Bin(op, a, b) => {
            let (a, b) = (place(a), place(b));
            match op {
                o if o == Arith::Add as u8 => Instr::Add(a, b),
                o if o == Arith::Sub as u8 => Instr::Sub(a, b),
                o if o == Arith::Mul as u8 => Instr::Mul(a, b),
                _ => Instr::Div(a, b),
            }
        }
        Key::Call(f, a) => Instr::Call(UNARIES[usize::from(f)], place(a)),
        Key::Powi(a, 2) => Instr::Square(place(a)),
        Key::Powi(a, n) => Instr::Powi(place(a), n),
        Key::Powf(a, e) => Instr::Powf(place(a), f64::from_bits(e)),
        Key::Powd(a, b) => Instr::Powd(place(a), place(b)),
        Key::Atan2(y, x) => Instr::Atan2(place(y), place(x)),
    }
}
