//! Recursive-descent parser: tokens to an [`Ast`], following the grammar in the module docs.
//!
//! Each grammar rule is one method. Errors about a missing operand look at the token before the
//! current one, so they can say "after '+'" without threading context through the rules.

use crate::ast::{Ast, AstKind, BinOp};
use crate::error::{ErrorKind, ExprError, Span};
use crate::lexer::{Tok, Token, tokenize};

/// Maximum nesting of parentheses, calls, powers and unary operators.
pub(crate) const MAX_DEPTH: usize = 256;

/// Maximum height of the tree: nesting plus the length of operator chains such as a flat sum
/// `a + b + c + …` (each term one level), bounded so that the recursive passes over the tree
/// (lowering, differentiation, code generation) stay well within a thread's stack.
pub(crate) const MAX_HEIGHT: usize = 2048;

/// Maximum length of an expression, in bytes.
pub(crate) const MAX_LENGTH: usize = 64 * 1024;

/// Parse a whole expression.
pub(crate) fn parse(text: &str) -> Result<Ast, ExprError> {
    if text.len() > MAX_LENGTH {
        let kind = ErrorKind::TooLong {
            length: text.len(),
            limit: MAX_LENGTH,
        };
        let mut end = MAX_LENGTH;
        while !text.is_char_boundary(end) {
            end -= 1;
        }
        return Err(ExprError::new(kind, text, Span::new(end, text.len())));
    }
    let tokens = tokenize(text)?;
    let mut parser = Parser {
        text,
        tokens,
        pos: 0,
        nesting: 0,
    };
    if parser.peek().tok == Tok::Eof {
        return Err(parser.error(ErrorKind::Empty, Span::new(0, 0)));
    }
    let ast = parser.expr()?;
    parser.end()?;
    Ok(ast)
}

struct Parser<'a> {
    text: &'a str,
    tokens: Vec<Token>,
    pos: usize,
    nesting: usize,
}

impl Parser<'_> {
    fn peek(&self) -> Token {
        // `tokenize` always ends with Eof and `bump` never moves past it.
        self.tokens[self.pos.min(self.tokens.len() - 1)]
    }

    fn bump(&mut self) -> Token {
        let token = self.peek();
        if token.tok != Tok::Eof {
            self.pos += 1;
        }
        token
    }

    fn error(&self, kind: ErrorKind, span: Span) -> ExprError {
        ExprError::new(kind, self.text, span)
    }

    /// How a token is named in messages.
    fn describe(&self, token: Token) -> String {
        match token.tok {
            Tok::Eof => "the end of the expression".to_owned(),
            _ => format!("'{}'", &self.text[token.span.start..token.span.end]),
        }
    }

    /// Build a node, enforcing the height limit.
    fn node(&self, kind: AstKind, span: Span) -> Result<Ast, ExprError> {
        let depth = 1 + kind.max_child_depth();
        if depth > MAX_HEIGHT {
            return Err(self.error(ErrorKind::TooTall { limit: MAX_HEIGHT }, span));
        }
        Ok(Ast { kind, span, depth })
    }

    /// Run `rule` one nesting level deeper, failing beyond [`MAX_DEPTH`].
    fn nested<T>(
        &mut self,
        at: Span,
        rule: impl FnOnce(&mut Self) -> Result<T, ExprError>,
    ) -> Result<T, ExprError> {
        if self.nesting >= MAX_DEPTH {
            return Err(self.error(ErrorKind::TooDeep { limit: MAX_DEPTH }, at));
        }
        self.nesting += 1;
        let result = rule(self);
        self.nesting -= 1;
        result
    }

    fn binary(&self, op: BinOp, lhs: Ast, rhs: Ast) -> Result<Ast, ExprError> {
        let span = lhs.span.to(rhs.span);
        self.node(AstKind::Binary(op, Box::new(lhs), Box::new(rhs)), span)
    }

    /// `expr = term { ("+" | "-") term }`
    fn expr(&mut self) -> Result<Ast, ExprError> {
        let mut lhs = self.term()?;
        loop {
            let op = match self.peek().tok {
                Tok::Plus => BinOp::Add,
                Tok::Minus => BinOp::Sub,
                _ => return Ok(lhs),
            };
            self.bump();
            let rhs = self.term()?;
            lhs = self.binary(op, lhs, rhs)?;
        }
    }

    /// `term = unary { ("*" | "/") unary }`
    fn term(&mut self) -> Result<Ast, ExprError> {
        let mut lhs = self.unary()?;
        loop {
            let op = match self.peek().tok {
                Tok::Star => BinOp::Mul,
                Tok::Slash => BinOp::Div,
                _ => return Ok(lhs),
            };
            self.bump();
            let rhs = self.unary()?;
            lhs = self.binary(op, lhs, rhs)?;
        }
    }

    /// `unary = ("-" | "+") unary | power`
    fn unary(&mut self) -> Result<Ast, ExprError> {
        let token = self.peek();
        match token.tok {
            Tok::Minus => {
                self.bump();
                let operand = self.nested(token.span, Self::unary)?;
                let span = token.span.to(operand.span);
                self.node(AstKind::Neg(Box::new(operand)), span)
            }
            Tok::Plus => {
                self.bump();
                self.nested(token.span, Self::unary)
            }
            _ => self.power(),
        }
    }

    /// `power = primary [ "^" unary ]` (right-associative through `unary`).
    fn power(&mut self) -> Result<Ast, ExprError> {
        let base = self.primary()?;
        let token = self.peek();
        if token.tok != Tok::Caret {
            return Ok(base);
        }
        self.bump();
        let exponent = self.nested(token.span, Self::unary)?;
        self.binary(BinOp::Pow, base, exponent)
    }

    /// `primary = number | name | call | "(" expr ")"`
    fn primary(&mut self) -> Result<Ast, ExprError> {
        let token = self.peek();
        match token.tok {
            Tok::Number(value) => {
                self.bump();
                self.node(AstKind::Number(value), token.span)
            }
            Tok::Ident => {
                self.bump();
                let name = self.text[token.span.start..token.span.end].to_owned();
                if self.peek().tok == Tok::LParen {
                    self.nested(token.span, |p| p.call(name, token.span))
                } else {
                    self.node(AstKind::Name(name), token.span)
                }
            }
            Tok::LParen => {
                self.bump();
                self.nested(token.span, |p| p.parenthesized(token.span))
            }
            _ => Err(self.missing_operand(token)),
        }
    }

    /// The error for a token that cannot start an operand.
    fn missing_operand(&self, found: Token) -> ExprError {
        let Some(prev) = self.pos.checked_sub(1).map(|i| self.tokens[i]) else {
            let kind = ErrorKind::ExpectedOperand {
                found: self.describe(found),
            };
            return self.error(kind, found.span);
        };
        if prev.tok == Tok::Star && found.tok == Tok::Star && prev.span.end == found.span.start {
            return self.error(ErrorKind::DoubleStar, prev.span.to(found.span));
        }
        let after = self.text[prev.span.start..prev.span.end].to_owned();
        let kind = ErrorKind::OperandAfter {
            after,
            found: self.describe(found),
        };
        self.error(kind, found.span)
    }

    /// The rest of `"(" expr ")"` after the opening parenthesis at `open`.
    fn parenthesized(&mut self, open: Span) -> Result<Ast, ExprError> {
        let inner = self.expr()?;
        let close = self.bump();
        match close.tok {
            Tok::RParen => Ok(Ast {
                span: open.to(close.span),
                ..inner
            }),
            Tok::Eof => Err(self.error(ErrorKind::UnclosedParen, open)),
            _ => Err(self.expected("an operator or ')'", close)),
        }
    }

    /// `call = name "(" [ expr { "," expr } ] ")"`; the name is already consumed.
    fn call(&mut self, name: String, name_span: Span) -> Result<Ast, ExprError> {
        let open = self.bump().span;
        let mut args = Vec::new();
        let close = if self.peek().tok == Tok::RParen {
            self.bump()
        } else {
            loop {
                args.push(self.expr()?);
                let token = self.bump();
                match token.tok {
                    Tok::Comma => continue,
                    Tok::RParen => break token,
                    Tok::Eof => return Err(self.error(ErrorKind::UnclosedParen, open)),
                    _ => return Err(self.expected("',' or ')'", token)),
                }
            }
        };
        let span = name_span.to(close.span);
        self.node(
            AstKind::Call {
                name,
                name_span,
                args,
            },
            span,
        )
    }

    fn expected(&self, expected: &str, found: Token) -> ExprError {
        let kind = ErrorKind::Expected {
            expected: expected.to_owned(),
            found: self.describe(found),
        };
        self.error(kind, found.span)
    }

    /// After a complete expression only the end of input may follow.
    fn end(&mut self) -> Result<(), ExprError> {
        let token = self.peek();
        let kind = match token.tok {
            Tok::Eof => return Ok(()),
            Tok::RParen => ErrorKind::UnmatchedParen,
            tok => ErrorKind::Trailing {
                found: self.describe(token),
                missing_operator: matches!(tok, Tok::Number(_) | Tok::Ident | Tok::LParen),
            },
        };
        Err(self.error(kind, token.span))
    }
}
