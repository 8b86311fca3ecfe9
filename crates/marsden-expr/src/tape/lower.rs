//! The merged graph ([`Graph`]) laid out as straight-line instructions over registers
//! `[inputs | one per instruction]`.
//!
//! Fused (the default), constants never occupy a register: an operation with a constant operand
//! becomes its constant form (`x·c`, `c/x`, …), and an operation whose operand is a product or a
//! square used nowhere else becomes one superinstruction (`a·b + c`, `a² + b²`, `a·b − c`,
//! `c − a·b`, `(a·b)·c`, `(a·b)/c`). Each keeps the rounding of the operations it replaces
//! (`a·b` is rounded first, no fused multiply–add; `+` and `·` commute exactly, so
//! `c·(a·b) = (a·b)·c` bit for bit), so the values are bit for bit those of the plain
//! layout, where every constant is loaded into a register once and every operation is one
//! instruction.

use crate::ir::Arith;

use super::Instr;
use super::build::{Graph, Key, Ref, UNARIES, arith};

/// Sentinel for "no register yet".
const NONE: u32 = u32::MAX;

/// How an operation is emitted when it absorbs a product (or square) operand.
#[derive(Debug, Clone, Copy)]
enum Super {
    /// `a² + b²`.
    SumSquares(Ref, Ref),
    /// `a·b + c`.
    MulAdd(Ref, Ref, Ref),
    /// `a·b − c`.
    MulSub(Ref, Ref, Ref),
    /// `c − a·b` (operands in that order).
    SubMul(Ref, Ref, Ref),
    /// `(a·b)·c`.
    Mul3(Ref, Ref, Ref),
    /// `(a·b)/c`.
    MulDiv(Ref, Ref, Ref),
}

/// The instructions of `graph` and the registers of its outputs.
pub(super) fn lower(graph: &Graph, fuse: bool) -> (Vec<Instr>, Vec<u32>) {
    let (absorbed, fused) = if fuse {
        superinstructions(graph)
    } else {
        (vec![false; graph.ops.len()], vec![None; graph.ops.len()])
    };
    let mut l = Lowering {
        graph,
        fuse,
        op_reg: vec![NONE; graph.ops.len()],
        const_reg: vec![NONE; graph.constants.len()],
        instrs: Vec::with_capacity(graph.ops.len()),
    };
    for (k, key) in graph.ops.iter().enumerate() {
        if absorbed[k] {
            continue;
        }
        let instr = match fused[k] {
            Some(s) => l.superinstruction(s),
            None => l.instr(*key),
        };
        l.op_reg[k] = l.emit(instr);
    }
    let outputs = graph.outputs.iter().map(|&r| l.operand(r)).collect();
    (l.instrs, outputs)
}

/// The operations emitted as superinstructions, and the products they absorb (used once, by
/// that operation, and not outputs).
fn superinstructions(graph: &Graph) -> (Vec<bool>, Vec<Option<Super>>) {
    let n = graph.ops.len();
    let mut uses = vec![0_u32; n];
    let mut count = |r: Ref| {
        if let Ref::Op(k) = r {
            uses[k as usize] += 1;
        }
    };
    for key in &graph.ops {
        match *key {
            Key::Neg(a) | Key::Call(_, a) | Key::Powi(a, _) | Key::Powf(a, _) => count(a),
            Key::Bin(_, a, b) | Key::Powd(a, b) | Key::Atan2(a, b) => {
                count(a);
                count(b);
            }
        }
    }
    graph.outputs.iter().for_each(|&r| count(r));
    let (mut absorbed, mut fused) = (vec![false; n], vec![None::<Super>; n]);
    for (k, key) in graph.ops.iter().enumerate() {
        let Key::Bin(op, a, b) = *key else { continue };
        if !variable(a) || !variable(b) {
            continue;
        }
        // The factors of a product or square operand that only this operation reads (and
        // that is not itself a superinstruction).
        let product = |r: Ref, absorbed: &[bool], fused: &[Option<Super>]| match r {
            Ref::Op(j) if uses[j as usize] == 1 && !absorbed[j as usize] => {
                match (graph.ops[j as usize], fused[j as usize]) {
                    (Key::Powi(x, 2), None) if variable(x) => Some((j, x, x)),
                    (Key::Bin(m, x, y), None)
                        if arith(m) == Arith::Mul && variable(x) && variable(y) =>
                    {
                        Some((j, x, y))
                    }
                    _ => None,
                }
            }
            _ => None,
        };
        let (pa, pb) = (product(a, &absorbed, &fused), product(b, &absorbed, &fused));
        let (choice, taken) = match (arith(op), pa, pb) {
            (Arith::Add, Some((i, x, x2)), Some((j, y, y2))) if x == x2 && y == y2 && i != j => {
                absorbed[j as usize] = true;
                (Super::SumSquares(x, y), i)
            }
            (Arith::Add, Some((i, x, y)), _) => (Super::MulAdd(x, y, b), i),
            (Arith::Add, None, Some((j, x, y))) => (Super::MulAdd(x, y, a), j),
            (Arith::Sub, Some((i, x, y)), _) => (Super::MulSub(x, y, b), i),
            (Arith::Sub, None, Some((j, x, y))) => (Super::SubMul(a, x, y), j),
            (Arith::Mul, Some((i, x, y)), _) => (Super::Mul3(x, y, b), i),
            (Arith::Mul, None, Some((j, x, y))) => (Super::Mul3(x, y, a), j),
            (Arith::Div, Some((i, x, y)), _) => (Super::MulDiv(x, y, b), i),
            _ => continue,
        };
        absorbed[taken as usize] = true;
        fused[k] = Some(choice);
    }
    (absorbed, fused)
}

/// Whether `r` is held in a register (not a constant).
fn variable(r: Ref) -> bool {
    !matches!(r, Ref::Const(_))
}

struct Lowering<'g> {
    graph: &'g Graph,
    fuse: bool,
    op_reg: Vec<u32>,
    const_reg: Vec<u32>,
    instrs: Vec<Instr>,
}

impl Lowering<'_> {
    /// Appends `instr`; returns its register.
    fn emit(&mut self, instr: Instr) -> u32 {
        self.instrs.push(instr);
        (self.graph.inputs + self.instrs.len() - 1) as u32
    }

    /// The register holding `r` (a constant is loaded on first use).
    fn operand(&mut self, r: Ref) -> u32 {
        match r {
            Ref::Input(i) => i,
            Ref::Op(k) => self.op_reg[k as usize],
            Ref::Const(c) => {
                if self.const_reg[c as usize] == NONE {
                    let value = self.graph.constants[c as usize];
                    self.const_reg[c as usize] = self.emit(Instr::Load(value));
                }
                self.const_reg[c as usize]
            }
        }
    }

    fn superinstruction(&mut self, s: Super) -> Instr {
        match s {
            Super::SumSquares(a, b) => Instr::SumSquares(self.operand(a), self.operand(b)),
            Super::MulAdd(a, b, c) => {
                Instr::MulAdd(self.operand(a), self.operand(b), self.operand(c))
            }
            Super::MulSub(a, b, c) => {
                Instr::MulSub(self.operand(a), self.operand(b), self.operand(c))
            }
            Super::SubMul(c, a, b) => {
                Instr::SubMul(self.operand(c), self.operand(a), self.operand(b))
            }
            Super::Mul3(a, b, c) => Instr::Mul3(self.operand(a), self.operand(b), self.operand(c)),
            Super::MulDiv(a, b, c) => {
                Instr::MulDiv(self.operand(a), self.operand(b), self.operand(c))
            }
        }
    }

    fn instr(&mut self, key: Key) -> Instr {
        match key {
            Key::Neg(a) => Instr::Neg(self.operand(a)),
            Key::Bin(op, a, b) => self.binary(arith(op), a, b),
            Key::Call(f, a) => Instr::Call(UNARIES[usize::from(f)], self.operand(a)),
            Key::Powi(a, 2) => Instr::Square(self.operand(a)),
            Key::Powi(a, n) => Instr::Powi(self.operand(a), n),
            Key::Powf(a, e) => Instr::Powf(self.operand(a), f64::from_bits(e)),
            Key::Powd(a, b) => Instr::Powd(self.operand(a), self.operand(b)),
            Key::Atan2(y, x) => Instr::Atan2(self.operand(y), self.operand(x)),
        }
    }

    /// `a op b`, in its constant form when one operand is a constant and fusing is on.
    fn binary(&mut self, op: Arith, a: Ref, b: Ref) -> Instr {
        let constant = |r: Ref| match r {
            Ref::Const(c) => Some(self.graph.constants[c as usize]),
            _ => None,
        };
        match (self.fuse, constant(a), constant(b)) {
            (true, None, Some(c)) => {
                let a = self.operand(a);
                match op {
                    Arith::Add => Instr::AddC(a, c),
                    Arith::Sub => Instr::SubC(a, c),
                    Arith::Mul => Instr::MulC(a, c),
                    Arith::Div => Instr::DivC(a, c),
                }
            }
            (true, Some(c), None) => {
                let b = self.operand(b);
                match op {
                    Arith::Add => Instr::AddC(b, c),
                    Arith::Sub => Instr::CSub(c, b),
                    Arith::Mul => Instr::MulC(b, c),
                    Arith::Div => Instr::CDiv(c, b),
                }
            }
            _ => {
                let (a, b) = (self.operand(a), self.operand(b));
                match op {
                    Arith::Add => Instr::Add(a, b),
                    Arith::Sub => Instr::Sub(a, b),
                    Arith::Mul => Instr::Mul(a, b),
                    Arith::Div => Instr::Div(a, b),
                }
            }
        }
    }
}
