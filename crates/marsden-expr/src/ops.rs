//! Instructions of the compiled program.
//!
//! The machine has an accumulator (the value of the last completed subexpression) and a stack
//! of pending left operands. A program is a first [`Leaf`] loaded into the accumulator followed
//! by [`Op`]s. Binary operations whose right operand is an input or a constant read it directly
//! (`MulConst`, `AddInput`, …), so most leaves never touch the stack.

use std::fmt;

use crate::functions::Unary;

/// The value first loaded into the accumulator.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Leaf {
    Input(usize),
    Const(f64),
}

/// One instruction. `acc` is the accumulator, `pop` the value popped from the stack.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Op {
    /// push acc; acc = inputs[i]
    PushInput(usize),
    /// push acc; acc = c
    PushConst(f64),
    /// acc = pop + acc
    Add,
    /// acc = pop - acc
    Sub,
    /// acc = pop * acc
    Mul,
    /// acc = pop / acc
    Div,
    /// acc = acc + inputs[i]
    AddInput(usize),
    /// acc = acc - inputs[i]
    SubInput(usize),
    /// acc = acc * inputs[i]
    MulInput(usize),
    /// acc = acc / inputs[i]
    DivInput(usize),
    /// acc = acc + c
    AddConst(f64),
    /// acc = acc * c
    MulConst(f64),
    /// acc = acc / c
    DivConst(f64),
    /// acc = c - acc
    ConstSub(f64),
    /// acc = c / acc
    ConstDiv(f64),
    /// acc = -acc
    Neg,
    /// acc = f(acc)
    Call(Unary),
    /// acc = acc^n
    Powi(i32),
    /// acc = acc * acc (`powi(2)`, the most common power)
    Square,
    /// acc = pop + acc * c (fused `MulConst(c)`, `Add`)
    MulConstAdd(f64),
    /// push acc; acc = f(inputs[i]) (fused `PushInput(i)`, `Call(f)`)
    PushCall(usize, Unary),
    /// push acc; acc = inputs[i]^2 (fused `PushInput(i)`, `Square`)
    PushSquare(usize),
    /// acc = acc^e
    Powf(f64),
    /// acc = pop^acc
    Powd,
    /// acc = atan2(pop, acc)
    Atan2,
}

/// A compiled expression: first leaf, instructions, and the stack depth they need.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Code {
    pub(crate) first: Leaf,
    pub(crate) ops: Vec<Op>,
    pub(crate) depth: usize,
}

impl fmt::Display for Leaf {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Leaf::Input(i) => write!(f, "load in[{i}]"),
            Leaf::Const(c) => write!(f, "load {c}"),
        }
    }
}

impl fmt::Display for Op {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Op::PushInput(i) => write!(f, "push; load in[{i}]"),
            Op::PushConst(c) => write!(f, "push; load {c}"),
            Op::Add | Op::Sub | Op::Mul | Op::Div | Op::Powd | Op::Atan2 => {
                write!(f, "{} pop", format!("{self:?}").to_lowercase())
            }
            Op::AddInput(i) => write!(f, "add in[{i}]"),
            Op::SubInput(i) => write!(f, "sub in[{i}]"),
            Op::MulInput(i) => write!(f, "mul in[{i}]"),
            Op::DivInput(i) => write!(f, "div in[{i}]"),
            Op::AddConst(c) => write!(f, "add {c}"),
            Op::MulConst(c) => write!(f, "mul {c}"),
            Op::DivConst(c) => write!(f, "div {c}"),
            Op::ConstSub(c) => write!(f, "rsub {c}"),
            Op::ConstDiv(c) => write!(f, "rdiv {c}"),
            Op::Neg => write!(f, "neg"),
            Op::Call(u) => write!(f, "{}", u.name()),
            Op::Powi(n) => write!(f, "powi {n}"),
            Op::Square => write!(f, "square"),
            Op::MulConstAdd(c) => write!(f, "mul {c}; add pop"),
            Op::PushCall(i, u) => write!(f, "push; load {}(in[{i}])", u.name()),
            Op::PushSquare(i) => write!(f, "push; load in[{i}]^2"),
            Op::Powf(e) => write!(f, "powf {e}"),
        }
    }
}
