//! The pipeline entry points: [`Expr::parse`] (lexer → parser → syntax tree) and
//! [`Expr::compile`] / [`Program::compile`] (lowering and constant folding → code generation →
//! [`Program`]).
//!
//! This module sits above the stages it chains, so each stage imports only modules below it:
//! `lexer` → `parser` → `ast`; `lower` → `ir` → `codegen` → `ops`; `program` → `eval`.

use crate::ast::{Ast, Identifier};
use crate::codegen::generate;
use crate::error::{ErrorKind, ExprError, Span};
use crate::ir::Node;
use crate::lower::lower;
use crate::parser::parse;
use crate::program::Program;
use crate::symbols::Symbols;

/// A parsed expression, not yet bound to a symbol table.
///
/// Parse with [`Expr::parse`], inspect the names it uses with [`Expr::names`], then compile it
/// against a [`Symbols`] table with [`Expr::compile`].
#[derive(Debug, Clone, PartialEq)]
pub struct Expr {
    text: String,
    root: Ast,
}

impl Expr {
    /// Parse `text`. Errors point at the offending position.
    ///
    /// ```
    /// use marsden_expr::Expr;
    /// let e = Expr::parse("0.5*m*v^2 - k*x").unwrap();
    /// assert_eq!(e.names(), ["k", "m", "v", "x"]);
    /// ```
    pub fn parse(text: &str) -> Result<Expr, ExprError> {
        let root = parse(text)?;
        Ok(Expr {
            text: text.to_owned(),
            root,
        })
    }

    /// The source text.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// Every occurrence of a name used as a value, in source order (built-in constants such as
    /// `pi` and function names are not included).
    pub fn identifiers(&self) -> Vec<Identifier<'_>> {
        self.root.identifiers()
    }

    /// The distinct names the expression uses as values, sorted (without `pi`).
    pub fn names(&self) -> Vec<&str> {
        self.root.sorted_names()
    }

    /// Build an error about this expression pointing at `span`, rendered like parse errors.
    /// Use it for checks the caller makes, e.g. a constraint that uses a velocity.
    pub fn error_at(
        &self,
        span: Span,
        message: impl Into<String>,
        help: Option<String>,
    ) -> ExprError {
        let kind = ErrorKind::Custom {
            message: message.into(),
            help,
        };
        ExprError::new(kind, &self.text, span)
    }

    /// Resolve names against `symbols`, fold constants and compile to a [`Program`].
    pub fn compile(&self, symbols: &Symbols) -> Result<Program, ExprError> {
        let node = lower(&self.text, &self.root, symbols)?;
        let mut inputs_used = Vec::new();
        collect_inputs(&node, &mut inputs_used);
        inputs_used.sort_unstable();
        inputs_used.dedup();
        let names = self
            .root
            .sorted_names()
            .into_iter()
            .filter(|n| symbols.get(n).is_some())
            .map(str::to_owned)
            .collect();
        Ok(Program::new(
            generate(&node),
            node,
            &self.text,
            names,
            inputs_used,
        ))
    }
}

impl Program {
    /// Parse `text` and compile it against `symbols`.
    ///
    /// ```
    /// use marsden_expr::{Program, Symbols};
    /// let symbols = Symbols::with_inputs(["x"]).unwrap();
    /// let square = Program::compile("x^2", &symbols).unwrap();
    /// assert_eq!(square.eval(&[3.0]), 9.0);
    /// ```
    pub fn compile(text: &str, symbols: &Symbols) -> Result<Program, ExprError> {
        Expr::parse(text)?.compile(symbols)
    }
}

/// The input slots `node` reads, in tree order (with repetitions).
pub(crate) fn collect_inputs(node: &Node, out: &mut Vec<usize>) {
    match node {
        Node::Const(_) => {}
        Node::Input(slot) => out.push(*slot),
        Node::Neg(a) | Node::Unary(_, a) | Node::Powi(a, _) | Node::Powf(a, _) => {
            collect_inputs(a, out)
        }
        Node::Bin(_, a, b) | Node::Powd(a, b) | Node::Atan2(a, b) => {
            collect_inputs(a, out);
            collect_inputs(b, out);
        }
    }
}
