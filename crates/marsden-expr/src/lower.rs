//! Lowering: resolve names against the symbol table and fold constants (AST to [`Node`]).

use crate::ast::{Ast, AstKind, BinOp};
use crate::error::{ErrorKind, ExprError, Span};
use crate::functions::{self, Function};
use crate::ir::{self, Node};
use crate::suggest::closest;
use crate::symbols::{Symbol, Symbols};

/// Resolve and fold `ast` (parsed from `text`).
pub(crate) fn lower(text: &str, ast: &Ast, symbols: &Symbols) -> Result<Node, ExprError> {
    Lowerer { text, symbols }.lower(ast)
}

struct Lowerer<'a> {
    text: &'a str,
    symbols: &'a Symbols,
}

impl Lowerer<'_> {
    fn error(&self, kind: ErrorKind, span: Span) -> ExprError {
        ExprError::new(kind, self.text, span)
    }

    fn lower(&self, ast: &Ast) -> Result<Node, ExprError> {
        let node = match &ast.kind {
            AstKind::Number(value) => Node::Const(*value),
            AstKind::Name(name) => self.name(name, ast.span)?,
            AstKind::Neg(operand) => ir::neg(self.lower(operand)?),
            AstKind::Binary(op, lhs, rhs) => binary(*op, self.lower(lhs)?, self.lower(rhs)?),
            AstKind::Call {
                name,
                name_span,
                args,
            } => self.call(name, *name_span, args)?,
        };
        match node.as_const() {
            Some(value) if !value.is_finite() => {
                Err(self.error(ErrorKind::NonFinite { value }, ast.span))
            }
            _ => Ok(node),
        }
    }

    /// A name used as a value.
    fn name(&self, name: &str, span: Span) -> Result<Node, ExprError> {
        if let Some(symbol) = self.symbols.get(name) {
            return Ok(match symbol {
                Symbol::Input(slot) => Node::Input(slot),
                Symbol::Constant(value) => Node::Const(value),
            });
        }
        if let Some(value) = functions::constant(name) {
            return Ok(Node::Const(value));
        }
        if let Some(function) = Function::lookup(name) {
            return Err(self.error(
                ErrorKind::MissingCall {
                    name: function.name(),
                },
                span,
            ));
        }
        let mut known: Vec<String> = self.symbols.names().map(str::to_owned).collect();
        known.extend(functions::CONSTANTS.iter().map(|(c, _)| (*c).to_owned()));
        known.sort_unstable();
        let suggestion = closest(name, known.iter().map(String::as_str)).map(str::to_owned);
        let kind = ErrorKind::UnknownName {
            name: name.to_owned(),
            known,
            suggestion,
        };
        Err(self.error(kind, span))
    }

    /// A function call `name(args…)`.
    fn call(&self, name: &str, name_span: Span, args: &[Ast]) -> Result<Node, ExprError> {
        let Some(function) = Function::lookup(name) else {
            let declared = self.symbols.get(name).is_some() || functions::constant(name).is_some();
            let kind = if declared {
                ErrorKind::NotAFunction {
                    name: name.to_owned(),
                }
            } else {
                let suggestion = Function::alias(name)
                    .map(Function::name)
                    .or_else(|| closest(name, Function::sorted_names()))
                    .map(str::to_owned);
                ErrorKind::UnknownFunction {
                    name: name.to_owned(),
                    suggestion,
                }
            };
            return Err(self.error(kind, name_span));
        };
        if args.len() != function.arity() {
            let kind = ErrorKind::WrongArity {
                name: function.name(),
                expected: function.arity(),
                found: args.len(),
            };
            return Err(self.error(kind, name_span));
        }
        let mut lowered = Vec::with_capacity(args.len());
        for arg in args {
            lowered.push(self.lower(arg)?);
        }
        Ok(apply(function, lowered))
    }
}

fn binary(op: BinOp, a: Node, b: Node) -> Node {
    match op {
        BinOp::Add => ir::add(a, b),
        BinOp::Sub => ir::sub(a, b),
        BinOp::Mul => ir::mul(a, b),
        BinOp::Div => ir::div(a, b),
        BinOp::Pow => ir::pow(a, b),
    }
}

/// Apply `function` to arguments whose count has been checked.
fn apply(function: Function, args: Vec<Node>) -> Node {
    let mut args = args.into_iter();
    let first = args.next().unwrap_or(Node::Const(f64::NAN));
    if let Some(unary) = function.unary() {
        return ir::unary(unary, first);
    }
    let second = args.next().unwrap_or(Node::Const(f64::NAN));
    match function {
        Function::Atan2 => ir::atan2_node(first, second),
        _ => ir::pow(first, second),
    }
}
