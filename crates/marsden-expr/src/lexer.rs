//! Lexer: expression text to a list of tokens with byte spans.

use crate::error::{ErrorKind, ExprError, Span};

/// The kind of a token.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Tok {
    /// A numeric literal.
    Number(f64),
    /// An identifier (its text is the token's span).
    Ident,
    Plus,
    Minus,
    Star,
    Slash,
    Caret,
    LParen,
    RParen,
    Comma,
    /// End of input; its span is empty and sits after the last non-whitespace character.
    Eof,
}

/// A token and where it is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Token {
    pub(crate) tok: Tok,
    pub(crate) span: Span,
}

/// Whether `c` may start an identifier.
pub(crate) fn is_ident_start(c: char) -> bool {
    c.is_alphabetic() || c == '_'
}

/// Whether `c` may continue an identifier.
pub(crate) fn is_ident_continue(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// Split `text` into tokens, ending with [`Tok::Eof`].
pub(crate) fn tokenize(text: &str) -> Result<Vec<Token>, ExprError> {
    let mut lexer = Lexer { text, pos: 0 };
    let mut tokens = Vec::new();
    loop {
        let token = lexer.next_token()?;
        tokens.push(token);
        if token.tok == Tok::Eof {
            return Ok(tokens);
        }
    }
}

struct Lexer<'a> {
    text: &'a str,
    pos: usize,
}

impl Lexer<'_> {
    fn peek(&self) -> Option<char> {
        self.text[self.pos..].chars().next()
    }

    fn peek_at(&self, offset: usize) -> Option<char> {
        self.text.get(self.pos + offset..)?.chars().next()
    }

    fn bump_while(&mut self, pred: impl Fn(char) -> bool) {
        while let Some(c) = self.peek().filter(|&c| pred(c)) {
            self.pos += c.len_utf8();
        }
    }

    fn error(&self, kind: ErrorKind, start: usize, end: usize) -> ExprError {
        ExprError::new(kind, self.text, Span::new(start, end))
    }

    fn next_token(&mut self) -> Result<Token, ExprError> {
        self.bump_while(char::is_whitespace);
        let start = self.pos;
        let Some(c) = self.peek() else {
            // Point end-of-input errors just after the last visible character.
            let end = self.text.trim_end().len();
            return Ok(Token {
                tok: Tok::Eof,
                span: Span::new(end, end),
            });
        };
        let tok = match c {
            '0'..='9' | '.' => return self.number(),
            c if is_ident_start(c) => {
                self.bump_while(is_ident_continue);
                Tok::Ident
            }
            '+' => Tok::Plus,
            '-' => Tok::Minus,
            '*' => Tok::Star,
            '/' => Tok::Slash,
            '^' => Tok::Caret,
            '(' => Tok::LParen,
            ')' => Tok::RParen,
            ',' => Tok::Comma,
            other => {
                let end = start + other.len_utf8();
                return Err(self.error(ErrorKind::UnexpectedChar(other), start, end));
            }
        };
        if tok != Tok::Ident {
            self.pos += c.len_utf8();
        }
        Ok(Token {
            tok,
            span: Span::new(start, self.pos),
        })
    }

    /// Lex `digits [. digits] [(e|E) [+|-] digits]` or `. digits [exponent]`.
    fn number(&mut self) -> Result<Token, ExprError> {
        let start = self.pos;
        let is_digit = |c: char| c.is_ascii_digit();
        self.bump_while(is_digit);
        let int_digits = self.pos - start;
        if self.peek() == Some('.') {
            self.pos += 1;
            let frac_start = self.pos;
            self.bump_while(is_digit);
            if int_digits == 0 && self.pos == frac_start {
                return Err(self.invalid(start, "a '.' must be followed by digits"));
            }
        }
        if matches!(self.peek(), Some('e' | 'E')) {
            self.exponent(start)?;
        }
        if self.peek() == Some('.') {
            self.bump_while(|c| c.is_ascii_digit() || c == '.');
            return Err(self.invalid(start, "more than one decimal point"));
        }
        self.finish_number(start)
    }

    /// Lex the exponent part of a number whose mantissa started at `start`.
    fn exponent(&mut self, start: usize) -> Result<(), ExprError> {
        let sign = usize::from(matches!(self.peek_at(1), Some('+' | '-')));
        if !self.peek_at(1 + sign).is_some_and(|c| c.is_ascii_digit()) {
            self.pos += 1 + sign;
            return Err(self.invalid(start, "the exponent after 'e' has no digits"));
        }
        self.pos += 1 + sign;
        self.bump_while(|c| c.is_ascii_digit());
        Ok(())
    }

    fn finish_number(&self, start: usize) -> Result<Token, ExprError> {
        let text = &self.text[start..self.pos];
        match text.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(Token {
                tok: Tok::Number(v),
                span: Span::new(start, self.pos),
            }),
            Ok(_) => Err(self.invalid(start, "too large for a 64-bit float")),
            Err(_) => Err(self.invalid(start, "not a number")),
        }
    }

    fn invalid(&self, start: usize, reason: &'static str) -> ExprError {
        let text = self.text[start..self.pos].to_owned();
        self.error(ErrorKind::InvalidNumber { text, reason }, start, self.pos)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kinds(text: &str) -> Vec<Tok> {
        tokenize(text).unwrap().into_iter().map(|t| t.tok).collect()
    }

    #[test]
    fn numbers_in_all_forms() {
        for (text, value) in [
            ("1", 1.0),
            ("2.5", 2.5),
            ("1e-3", 1e-3),
            (".5", 0.5),
            ("3.", 3.0),
            ("2E+2", 200.0),
        ] {
            assert_eq!(kinds(text), vec![Tok::Number(value), Tok::Eof], "{text}");
        }
    }

    #[test]
    fn operators_and_identifiers() {
        let toks = tokenize("theta_dot^2 * (θ + x1)").unwrap();
        let spans: Vec<_> = toks.iter().map(|t| (t.span.start, t.span.end)).collect();
        assert_eq!(toks[0].tok, Tok::Ident);
        assert_eq!(spans[0], (0, 9));
        assert_eq!(toks[1].tok, Tok::Caret);
        assert_eq!(toks[5].tok, Tok::Ident);
        assert_eq!(spans[5], (15, 17)); // 'θ' is two bytes
        assert_eq!(toks.last().unwrap().tok, Tok::Eof);
    }

    #[test]
    fn malformed_numbers() {
        let err = tokenize("1e").unwrap_err();
        assert_eq!(err.span(), Span::new(0, 2));
        let err = tokenize("x + 1.2.3").unwrap_err();
        assert_eq!(err.span(), Span::new(4, 9));
        let err = tokenize("1e999").unwrap_err();
        assert!(err.to_string().contains("too large"));
    }

    #[test]
    fn exponent_letter_without_digits_is_an_error() {
        assert!(matches!(
            tokenize("2e+x").unwrap_err().kind(),
            ErrorKind::InvalidNumber {
                reason: "the exponent after 'e' has no digits",
                ..
            }
        ));
    }
}
