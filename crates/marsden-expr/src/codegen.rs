//! Code generation: the folded tree to accumulator-machine instructions.
//!
//! Operands that are inputs or constants are folded into the instruction that consumes them
//! (`MulConst`, `AddInput`, …). For `+` and `*` the operand needing more stack is evaluated
//! first (Sethi–Ullman order), which keeps the stack shallow. A final peephole pass fuses
//! frequent instruction pairs (see [`fuse`]).

use crate::ir::{Arith, Node};
use crate::ops::{Code, Leaf, Op};

/// Generate code for `node`.
pub(crate) fn generate(node: &Node) -> Code {
    let mut g = Gen {
        first: None,
        ops: Vec::new(),
        sp: 0,
        depth: 0,
    };
    g.emit(node);
    Code {
        first: g.first.unwrap_or(Leaf::Const(f64::NAN)),
        ops: fuse(g.ops),
        depth: g.depth,
    }
}

struct Gen {
    first: Option<Leaf>,
    ops: Vec<Op>,
    sp: usize,
    depth: usize,
}

impl Gen {
    fn leaf(&mut self, leaf: Leaf) {
        if self.first.is_none() {
            self.first = Some(leaf);
            return;
        }
        self.ops.push(match leaf {
            Leaf::Input(i) => Op::PushInput(i),
            Leaf::Const(c) => Op::PushConst(c),
        });
        self.sp += 1;
        self.depth = self.depth.max(self.sp);
    }

    /// Emit an instruction that pops one stack value.
    fn pop_op(&mut self, op: Op) {
        self.ops.push(op);
        self.sp -= 1;
    }

    fn emit(&mut self, node: &Node) {
        match node {
            Node::Const(c) => self.leaf(Leaf::Const(*c)),
            Node::Input(i) => self.leaf(Leaf::Input(*i)),
            Node::Neg(a) => self.then(a, Op::Neg),
            Node::Unary(f, a) => self.then(a, Op::Call(*f)),
            Node::Powi(a, 2) => self.then(a, Op::Square),
            Node::Powi(a, n) => self.then(a, Op::Powi(*n)),
            Node::Powf(a, e) => self.then(a, Op::Powf(*e)),
            Node::Powd(a, b) => self.both(a, b, Op::Powd),
            Node::Atan2(a, b) => self.both(a, b, Op::Atan2),
            Node::Bin(op, a, b) => self.binary(*op, a, b),
        }
    }

    /// Evaluate `a` into the accumulator, then apply `op`.
    fn then(&mut self, a: &Node, op: Op) {
        self.emit(a);
        self.ops.push(op);
    }

    /// Evaluate `a` then `b` (pushing `a`), then apply the popping `op`.
    fn both(&mut self, a: &Node, b: &Node, op: Op) {
        self.emit(a);
        self.emit(b);
        self.pop_op(op);
    }

    fn binary(&mut self, op: Arith, a: &Node, b: &Node) {
        let commutes = matches!(op, Arith::Add | Arith::Mul);
        match (a, b) {
            (_, Node::Const(c)) => self.then(a, const_rhs(op, *c)),
            (_, Node::Input(i)) => self.then(a, input_rhs(op, *i)),
            (Node::Const(c), _) => self.then(b, const_lhs(op, *c)),
            (Node::Input(i), _) if commutes => self.then(b, input_rhs(op, *i)),
            // Evaluating the hungrier operand first keeps the stack shallow (Sethi–Ullman);
            // swapping the operands of `+` and `*` is exact.
            _ if commutes && need(b) > need(a) => self.both(b, a, stack_op(op)),
            _ => self.both(a, b, stack_op(op)),
        }
    }
}

/// Stack slots needed to evaluate `node` while the accumulator holds a live value.
fn need(node: &Node) -> usize {
    match node {
        Node::Const(_) | Node::Input(_) => 1,
        Node::Neg(a) | Node::Unary(_, a) | Node::Powi(a, _) | Node::Powf(a, _) => need(a),
        Node::Bin(_, a, b) if is_leaf(b) => need(a),
        Node::Bin(_, a, b) if is_leaf(a) => need(b),
        Node::Bin(Arith::Add | Arith::Mul, a, b) => {
            let (x, y) = (need(a), need(b));
            x.max(y).max(1 + x.min(y))
        }
        Node::Bin(_, a, b) | Node::Powd(a, b) | Node::Atan2(a, b) => need(a).max(1 + need(b)),
    }
}

fn is_leaf(node: &Node) -> bool {
    matches!(node, Node::Const(_) | Node::Input(_))
}

/// `acc = acc op c`
fn const_rhs(op: Arith, c: f64) -> Op {
    match op {
        Arith::Add => Op::AddConst(c),
        Arith::Sub => Op::AddConst(-c),
        Arith::Mul => Op::MulConst(c),
        Arith::Div => Op::DivConst(c),
    }
}

/// `acc = c op acc`
fn const_lhs(op: Arith, c: f64) -> Op {
    match op {
        Arith::Add => Op::AddConst(c),
        Arith::Sub => Op::ConstSub(c),
        Arith::Mul => Op::MulConst(c),
        Arith::Div => Op::ConstDiv(c),
    }
}

/// `acc = acc op inputs[i]`
fn input_rhs(op: Arith, i: usize) -> Op {
    match op {
        Arith::Add => Op::AddInput(i),
        Arith::Sub => Op::SubInput(i),
        Arith::Mul => Op::MulInput(i),
        Arith::Div => Op::DivInput(i),
    }
}

/// `acc = pop op acc`
fn stack_op(op: Arith) -> Op {
    match op {
        Arith::Add => Op::Add,
        Arith::Sub => Op::Sub,
        Arith::Mul => Op::Mul,
        Arith::Div => Op::Div,
    }
}

/// Fuse frequent instruction pairs into single instructions (fewer dispatches per evaluation).
fn fuse(ops: Vec<Op>) -> Vec<Op> {
    let mut out: Vec<Op> = Vec::with_capacity(ops.len());
    for op in ops {
        let fused = match (out.last(), op) {
            (Some(&Op::MulConst(c)), Op::Add) => Some(Op::MulConstAdd(c)),
            (Some(&Op::PushInput(i)), Op::Call(f)) => Some(Op::PushCall(i, f)),
            (Some(&Op::PushInput(i)), Op::Square) => Some(Op::PushSquare(i)),
            _ => None,
        };
        match fused {
            Some(fused) => {
                out.pop();
                out.push(fused);
            }
            None => out.push(op),
        }
    }
    out
}
