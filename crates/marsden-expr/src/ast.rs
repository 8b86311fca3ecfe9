//! The parsed (unresolved) syntax tree: what the parser builds and lowering reads.

use crate::error::Span;
use crate::functions;

/// A binary arithmetic operator.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum BinOp {
    Add,
    Sub,
    Mul,
    Div,
    Pow,
}

/// A node of the syntax tree, with the span of the text it was parsed from.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Ast {
    pub(crate) kind: AstKind,
    pub(crate) span: Span,
    /// Height of the subtree (a leaf has depth 1); bounded by the parser.
    pub(crate) depth: usize,
}

/// The shape of a syntax-tree node.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum AstKind {
    Number(f64),
    Name(String),
    Neg(Box<Ast>),
    Binary(BinOp, Box<Ast>, Box<Ast>),
    Call {
        name: String,
        name_span: Span,
        args: Vec<Ast>,
    },
}

impl AstKind {
    /// The largest depth among the children (0 for a leaf).
    pub(crate) fn max_child_depth(&self) -> usize {
        match self {
            AstKind::Number(_) | AstKind::Name(_) => 0,
            AstKind::Neg(a) => a.depth,
            AstKind::Binary(_, a, b) => a.depth.max(b.depth),
            AstKind::Call { args, .. } => args.iter().map(|a| a.depth).max().unwrap_or(0),
        }
    }
}

impl Ast {
    /// Names used as values, in source order, without built-in constants.
    pub(crate) fn identifiers(&self) -> Vec<Identifier<'_>> {
        let mut out = Vec::new();
        self.visit_names(&mut out);
        out.retain(|id| functions::constant(id.name).is_none());
        out
    }

    /// The distinct names used as values, sorted, without built-in constants.
    pub(crate) fn sorted_names(&self) -> Vec<&str> {
        let mut names: Vec<&str> = self.identifiers().iter().map(|id| id.name).collect();
        names.sort_unstable();
        names.dedup();
        names
    }

    /// Visit every name used as a value (not function names), in source order.
    fn visit_names<'a>(&'a self, out: &mut Vec<Identifier<'a>>) {
        match &self.kind {
            AstKind::Number(_) => {}
            AstKind::Name(name) => out.push(Identifier {
                name,
                span: self.span,
            }),
            AstKind::Neg(a) => a.visit_names(out),
            AstKind::Binary(_, a, b) => {
                a.visit_names(out);
                b.visit_names(out);
            }
            AstKind::Call { args, .. } => args.iter().for_each(|a| a.visit_names(out)),
        }
    }
}

/// One occurrence of a name in an expression.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Identifier<'a> {
    /// The name as written.
    pub name: &'a str,
    /// Where it occurs.
    pub span: Span,
}
