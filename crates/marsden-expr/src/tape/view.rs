//! A read-only view of a [`Tape`]'s instructions ([`TapeOp`]) and the `f64` functions its
//! interpreter calls ([`call_f64`], [`powi_f64`], …), for code generators that must give the
//! same values bit for bit: the same operations in the same order, with the same rounding.

use marsden::Scalar;

use crate::functions::{Function, Unary, atan2, powd, powf};

use super::{Instr, Tape};

/// One instruction of a [`Tape`]: registers are numbered `[inputs | one per instruction]`,
/// instruction `k` writes register `inputs + k`, and its operands are all smaller.
///
/// Every operation rounds as the `f64` operation it names, in the order written (no fused
/// multiply–add: `a · b + c` rounds the product first).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TapeOp {
    /// The constant.
    Load(f64),
    /// `−a`.
    Neg(u32),
    /// `a + b`.
    Add(u32, u32),
    /// `a − b`.
    Sub(u32, u32),
    /// `a · b`.
    Mul(u32, u32),
    /// `a / b`.
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
    /// `a · a`.
    Square(u32),
    /// A one-argument built-in function ([`call_f64`]; never [`Function::Atan2`] or
    /// [`Function::Pow`]).
    Call(Function, u32),
    /// `aⁿ` ([`powi_f64`]).
    Powi(u32, i32),
    /// `a^e` for a constant `e` ([`powf_f64`]).
    Powf(u32, f64),
    /// `a^b` ([`powd_f64`]).
    Powd(u32, u32),
    /// `atan2(a, b)` ([`atan2_f64`]).
    Atan2(u32, u32),
    /// `a · b + c`.
    MulAdd(u32, u32, u32),
    /// `a · a + b · b`.
    SumSquares(u32, u32),
    /// `a · b − c`.
    MulSub(u32, u32, u32),
    /// `c − a · b`, written `SubMul(c, a, b)`.
    SubMul(u32, u32, u32),
    /// `(a · b) · c`.
    Mul3(u32, u32, u32),
    /// `(a · b) / c`.
    MulDiv(u32, u32, u32),
}

impl Tape {
    /// The instructions, in order (see [`TapeOp`] for the register numbering).
    pub fn instructions(&self) -> impl ExactSizeIterator<Item = TapeOp> + '_ {
        self.instrs.iter().map(|&ins| view(ins))
    }

    /// The register of each output, in order.
    pub fn outputs(&self) -> &[u32] {
        &self.outputs
    }
}

/// The public form of one instruction.
fn view(ins: Instr) -> TapeOp {
    match ins {
        Instr::Load(c) => TapeOp::Load(c),
        Instr::Neg(a) => TapeOp::Neg(a),
        Instr::Add(a, b) => TapeOp::Add(a, b),
        Instr::Sub(a, b) => TapeOp::Sub(a, b),
        Instr::Mul(a, b) => TapeOp::Mul(a, b),
        Instr::Div(a, b) => TapeOp::Div(a, b),
        Instr::AddC(a, c) => TapeOp::AddC(a, c),
        Instr::SubC(a, c) => TapeOp::SubC(a, c),
        Instr::CSub(c, a) => TapeOp::CSub(c, a),
        Instr::MulC(a, c) => TapeOp::MulC(a, c),
        Instr::DivC(a, c) => TapeOp::DivC(a, c),
        Instr::CDiv(c, a) => TapeOp::CDiv(c, a),
        Instr::Square(a) => TapeOp::Square(a),
        Instr::Call(f, a) => TapeOp::Call(f.function(), a),
        Instr::Powi(a, n) => TapeOp::Powi(a, n),
        Instr::Powf(a, e) => TapeOp::Powf(a, e),
        Instr::Powd(a, b) => TapeOp::Powd(a, b),
        Instr::Atan2(a, b) => TapeOp::Atan2(a, b),
        Instr::MulAdd(a, b, c) => TapeOp::MulAdd(a, b, c),
        Instr::SumSquares(a, b) => TapeOp::SumSquares(a, b),
        Instr::MulSub(a, b, c) => TapeOp::MulSub(a, b, c),
        Instr::SubMul(c, a, b) => TapeOp::SubMul(c, a, b),
        Instr::Mul3(a, b, c) => TapeOp::Mul3(a, b, c),
        Instr::MulDiv(a, b, c) => TapeOp::MulDiv(a, b, c),
    }
}

/// The one-argument built-in `f` at `x`, as the interpreter computes it; `NaN` for the
/// two-argument functions ([`Function::Atan2`], [`Function::Pow`]), which take [`atan2_f64`]
/// and [`powd_f64`].
#[inline]
pub fn call_f64(f: Function, x: f64) -> f64 {
    match f.unary() {
        Some(u) => Unary::apply(u, x),
        None => f64::NAN,
    }
}

/// `xⁿ` as the interpreter computes it.
#[inline]
pub fn powi_f64(x: f64, n: i32) -> f64 {
    powi(x, n)
}

/// The interpreter's `powi` (generic, instantiated at `f64` above).
#[inline(always)]
fn powi<S: Scalar>(x: S, n: i32) -> S {
    x.powi(n)
}

/// `x^e` for a constant exponent, as the interpreter computes it.
#[inline]
pub fn powf_f64(x: f64, e: f64) -> f64 {
    powf(x, e)
}

/// `x^y` for a variable exponent, as the interpreter computes it.
#[inline]
pub fn powd_f64(x: f64, y: f64) -> f64 {
    powd(x, y)
}

/// `atan2(y, x)` as the interpreter computes it.
#[inline]
pub fn atan2_f64(y: f64, x: f64) -> f64 {
    atan2(y, x)
}
