//! [`TapeBuilder`]: the outputs' folded trees merged into one directed acyclic graph by
//! hash-consing (a node equal to one already built is the same operation; the operands of `+`
//! and `·` are ordered first, which is exact).

use std::collections::HashMap;

use crate::functions::Unary;
use crate::ir::{Arith, Node};

use super::Tape;

/// An operand while the graph is built: an input slot, a constant or an earlier operation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub(super) enum Ref {
    Input(u32),
    Const(u32),
    Op(u32),
}

/// One operation of the graph (its hash-consing key; constants by their index).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(super) enum Key {
    Neg(Ref),
    Bin(u8, Ref, Ref),
    Call(u8, Ref),
    Powi(Ref, i32),
    Powf(Ref, u64),
    Powd(Ref, Ref),
    Atan2(Ref, Ref),
}

/// The merged graph: what [`super::lower`] turns into instructions.
#[derive(Debug, Default)]
pub(super) struct Graph {
    pub(super) inputs: usize,
    pub(super) constants: Vec<f64>,
    pub(super) ops: Vec<Key>,
    pub(super) outputs: Vec<Ref>,
}

/// Builds a [`Tape`] output by output.
#[derive(Debug, Default)]
pub(crate) struct TapeBuilder {
    graph: Graph,
    constant_index: HashMap<u64, u32>,
    op_index: HashMap<Key, u32>,
}

impl TapeBuilder {
    /// Adds `node` as the next output.
    pub(crate) fn output(&mut self, node: &Node) {
        let r = self.node(node);
        self.graph.outputs.push(r);
    }

    /// The finished tape.
    pub(crate) fn finish(self) -> Tape {
        Tape::from_graph(self.graph)
    }

    fn constant(&mut self, c: f64) -> Ref {
        let next = self.graph.constants.len() as u32;
        let index = *self.constant_index.entry(c.to_bits()).or_insert(next);
        if index == next {
            self.graph.constants.push(c);
        }
        Ref::Const(index)
    }

    fn op(&mut self, key: Key) -> Ref {
        let next = self.graph.ops.len() as u32;
        let index = *self.op_index.entry(key).or_insert(next);
        if index == next {
            self.graph.ops.push(key);
        }
        Ref::Op(index)
    }

    fn node(&mut self, node: &Node) -> Ref {
        match node {
            Node::Const(c) => self.constant(*c),
            Node::Input(slot) => {
                self.graph.inputs = self.graph.inputs.max(slot + 1);
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
pub(super) const UNARIES: [Unary; 13] = [
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

/// The [`Arith`] of a `Key::Bin` code.
pub(super) fn arith(code: u8) -> Arith {
    match code {
        o if o == Arith::Add as u8 => Arith::Add,
        o if o == Arith::Sub as u8 => Arith::Sub,
        o if o == Arith::Mul as u8 => Arith::Mul,
        _ => Arith::Div,
    }
}
