//! Typed errors with source positions, rendered with a caret under the mistake.
//!
//! [`ExprError`] couples an [`ErrorKind`] (what went wrong) with the expression text and the
//! [`Span`] it refers to. Its `Display` renders a short report:
//!
//! ```text
//! error: expected an operand after '*'
//!   0.5*m*l^2*theta_dot^2 + * cos(theta)
//!                           ^
//! ```
//!
//! followed by optional `= help:` and `= note:` lines (suggestions, the list of known names).

use std::fmt;

/// A half-open range of byte offsets `start..end` into the expression text.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Span {
    /// Byte offset of the first character.
    pub start: usize,
    /// Byte offset one past the last character (`start == end` points between characters).
    pub end: usize,
}

impl Span {
    /// The span `start..end`.
    pub fn new(start: usize, end: usize) -> Self {
        Self { start, end }
    }

    /// The smallest span covering both `self` and `other`.
    pub fn to(self, other: Span) -> Span {
        Span::new(self.start.min(other.start), self.end.max(other.end))
    }
}

/// What went wrong while parsing or compiling an expression.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ErrorKind {
    /// The expression is empty or only whitespace.
    #[error("empty expression")]
    Empty,
    /// A binary or unary operator (or `(` / `,`) is not followed by an operand.
    #[error("expected an operand after '{after}', found {found}")]
    OperandAfter {
        /// The token the operand should follow.
        after: String,
        /// Description of what was found instead.
        found: String,
    },
    /// The expression starts with something that cannot begin an operand.
    #[error("expected an operand, found {found}")]
    ExpectedOperand {
        /// Description of what was found instead.
        found: String,
    },
    /// `**` was used for a power.
    #[error("use '^' for powers, not '**'")]
    DoubleStar,
    /// A specific token was expected (e.g. `)` or `,`).
    #[error("expected {expected}, found {found}")]
    Expected {
        /// What the parser expected.
        expected: String,
        /// Description of what was found instead.
        found: String,
    },
    /// A complete expression is followed by more input.
    #[error("unexpected {found} after the end of the expression")]
    Trailing {
        /// Description of the extra input.
        found: String,
        /// Whether the extra input starts an operand (so an operator is probably missing).
        missing_operator: bool,
    },
    /// Parentheses, calls, powers or unary minus nested deeper than the parser allows.
    #[error("expression is nested too deeply (more than {limit} levels)")]
    TooDeep {
        /// The nesting limit.
        limit: usize,
    },
    /// Operator chains and nesting together make the tree taller than the parser allows.
    #[error("expression is too large: its operations are chained more than {limit} deep")]
    TooTall {
        /// The height limit.
        limit: usize,
    },
    /// A text longer than the parser accepts (checked before anything else).
    #[error("expression is {length} bytes long, more than the limit of {limit}")]
    TooLong {
        /// The length of the text.
        length: usize,
        /// The limit.
        limit: usize,
    },
    /// An opening parenthesis is never closed.
    #[error("unclosed '(': the expression ends before its ')'")]
    UnclosedParen,
    /// A closing parenthesis has no matching opening one.
    #[error("unmatched ')'")]
    UnmatchedParen,
    /// A malformed number literal such as `1e` or `1.2.3`.
    #[error("invalid number `{text}`: {reason}")]
    InvalidNumber {
        /// The literal as written.
        text: String,
        /// Why it is invalid.
        reason: &'static str,
    },
    /// A character that is not part of the language.
    #[error("unexpected character '{0}'")]
    UnexpectedChar(char),
    /// A name that is neither in the symbol table nor a built-in constant.
    #[error("unknown name `{name}`")]
    UnknownName {
        /// The name as written.
        name: String,
        /// All names the expression may use (the caller's and `pi`), sorted.
        known: Vec<String>,
        /// A close known name (edit distance at most 2), if any.
        suggestion: Option<String>,
    },
    /// A call of a function that does not exist.
    #[error("unknown function `{name}`")]
    UnknownFunction {
        /// The function name as written.
        name: String,
        /// A close built-in function name, if any.
        suggestion: Option<String>,
    },
    /// A built-in function called with the wrong number of arguments.
    #[error("function `{name}` takes {expected} argument{s}, found {found}", s = plural(*expected))]
    WrongArity {
        /// The function name.
        name: &'static str,
        /// Number of arguments it takes.
        expected: usize,
        /// Number of arguments given.
        found: usize,
    },
    /// A declared name (or `pi`) used with call syntax, like `theta(1)`.
    #[error("`{name}` is not a function")]
    NotAFunction {
        /// The name as written.
        name: String,
    },
    /// A function name used without arguments, like `sin + 1`.
    #[error("function `{name}` must be called with arguments, as in `{name}(x)`")]
    MissingCall {
        /// The function name.
        name: &'static str,
    },
    /// A constant subexpression (after substituting parameters) is NaN or infinite.
    #[error("this constant subexpression evaluates to {value}, which is not a finite number")]
    NonFinite {
        /// The folded value.
        value: f64,
    },
    /// An error raised by the caller about a valid expression (see
    /// [`Expr::error_at`](crate::Expr::error_at)).
    #[error("{message}")]
    Custom {
        /// The message.
        message: String,
        /// An optional help line.
        help: Option<String>,
    },
}

fn plural(n: usize) -> &'static str {
    if n == 1 { "" } else { "s" }
}

impl ErrorKind {
    /// A `help:` line for the report, if this kind has one.
    pub fn help(&self) -> Option<String> {
        match self {
            ErrorKind::UnknownName {
                suggestion: Some(s),
                ..
            }
            | ErrorKind::UnknownFunction {
                suggestion: Some(s),
                ..
            } => Some(format!("did you mean `{s}`?")),
            ErrorKind::Trailing {
                missing_operator: true,
                ..
            } => Some("there is no implicit multiplication: write '*' between factors".into()),
            ErrorKind::Custom { help, .. } => help.clone(),
            _ => None,
        }
    }

    /// A `note:` line for the report, if this kind has one.
    pub fn note(&self) -> Option<String> {
        match self {
            ErrorKind::UnknownName { known, .. } if known.is_empty() => {
                Some("no names are defined for this expression".into())
            }
            ErrorKind::UnknownName { known, .. } => {
                Some(format!("known names: {}", known.join(", ")))
            }
            ErrorKind::UnknownFunction { .. } => Some(format!(
                "functions: {}",
                crate::functions::Function::sorted_names().join(", ")
            )),
            _ => None,
        }
    }
}

/// An error in an expression: what went wrong, where, and the text it refers to.
#[derive(Debug, Clone, PartialEq)]
pub struct ExprError(Box<Details>);

/// The contents of an [`ExprError`], boxed to keep `Result`s small.
#[derive(Debug, Clone, PartialEq)]
struct Details {
    kind: ErrorKind,
    text: String,
    span: Span,
    context: Option<String>,
}

impl ExprError {
    /// An error of `kind` at `span` of the expression `text`.
    pub fn new(kind: ErrorKind, text: &str, span: Span) -> Self {
        Self(Box::new(Details {
            kind,
            text: text.to_owned(),
            span,
            context: None,
        }))
    }

    /// Attach a label for where the expression came from (e.g. `lagrangian` or
    /// `constraints[1]`); it is shown in the first line of the report.
    #[must_use]
    pub fn with_context(mut self, context: impl Into<String>) -> Self {
        self.0.context = Some(context.into());
        self
    }

    /// What went wrong.
    pub fn kind(&self) -> &ErrorKind {
        &self.0.kind
    }

    /// The byte range of the expression text the error points at.
    pub fn span(&self) -> Span {
        self.0.span
    }

    /// The full expression text.
    pub fn text(&self) -> &str {
        &self.0.text
    }

    /// The context label set with [`ExprError::with_context`], if any.
    pub fn context(&self) -> Option<&str> {
        self.0.context.as_deref()
    }

    /// Zero-based (line, column) of the span start, the column counted in characters.
    pub fn line_column(&self) -> (usize, usize) {
        let start = self.clamped(self.0.span.start);
        let before = &self.0.text[..start];
        let line = before.matches('\n').count();
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        (line, before[line_start..].chars().count())
    }

    /// Clamp a byte offset into the text and onto a character boundary.
    fn clamped(&self, offset: usize) -> usize {
        let mut i = offset.min(self.0.text.len());
        while !self.0.text.is_char_boundary(i) {
            i -= 1;
        }
        i
    }

    /// The source line containing the span start, and the caret line under it; a line longer
    /// than [`LINE_LIMIT`] characters is cut to a window of [`WINDOW`] characters on either
    /// side of the span start, the cuts marked `…`.
    fn snippet(&self) -> (String, String) {
        let text = &self.0.text;
        let start = self.clamped(self.0.span.start);
        let end = self.clamped(self.0.span.end.max(start));
        let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
        let line_end = text[start..].find('\n').map_or(text.len(), |i| start + i);
        let (mut from, mut to) = (line_start, line_end);
        let (mut head, mut tail) = ("", "");
        if text[line_start..line_end].chars().count() > LINE_LIMIT {
            from = back(text, start, WINDOW).max(line_start);
            to = forward(text, start, WINDOW).min(line_end);
            head = if from > line_start { "…" } else { "" };
            tail = if to < line_end { "…" } else { "" };
        }
        let line = format!("{head}{}{tail}", &text[from..to]);
        let pad: String = head
            .chars()
            .chain(text[from..start].chars())
            .map(|c| if c == '\t' { '\t' } else { ' ' })
            .collect();
        let width = text[start..end.min(to)].chars().count().max(1);
        (line, format!("{pad}{}", "^".repeat(width)))
    }
}

/// Lines longer than this (in characters) are shown as a window around the error.
const LINE_LIMIT: usize = 120;

/// Characters shown on either side of the error in a long line.
const WINDOW: usize = 50;

/// The byte offset `n` characters before `at` (or 0).
fn back(text: &str, at: usize, n: usize) -> usize {
    text[..at]
        .char_indices()
        .rev()
        .nth(n.saturating_sub(1))
        .map_or(0, |(i, _)| i)
}

/// The byte offset `n` characters after `at` (or the end).
fn forward(text: &str, at: usize, n: usize) -> usize {
    text[at..]
        .char_indices()
        .nth(n)
        .map_or(text.len(), |(i, _)| at + i)
}

impl fmt::Display for ExprError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.0.context {
            Some(ctx) => writeln!(f, "error in {ctx}: {}", self.0.kind)?,
            None => writeln!(f, "error: {}", self.0.kind)?,
        }
        let (line, carets) = self.snippet();
        write!(f, "  {line}\n  {carets}")?;
        if let Some(help) = self.0.kind.help() {
            write!(f, "\n  = help: {help}")?;
        }
        if let Some(note) = self.0.kind.note() {
            write!(f, "\n  = note: {note}")?;
        }
        Ok(())
    }
}

impl std::error::Error for ExprError {}

/// An error while declaring a name in a [`Symbols`](crate::Symbols) table.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SymbolError {
    /// The name was already declared.
    #[error("`{0}` is declared twice")]
    Duplicate(String),
    /// The name is a built-in function or constant.
    #[error("`{0}` is a built-in function or constant and cannot be used as a name")]
    Reserved(String),
    /// The name is not an identifier of the expression language.
    #[error(
        "`{0}` is not a valid name: names start with a letter or '_' and contain only \
         letters, digits and '_'"
    )]
    Invalid(String),
    /// A constant declared with a NaN or infinite value.
    #[error("the value of `{name}` is {value}, which is not a finite number")]
    NonFinite {
        /// The constant's name.
        name: String,
        /// Its value.
        value: f64,
    },
}

/// An evaluation was called with slices of the wrong length.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum EvalError {
    /// The inputs slice is shorter than the program needs.
    #[error("the expression needs {needed} inputs, but {given} were given")]
    TooFewInputs {
        /// Minimum length of the inputs slice (largest used slot + 1).
        needed: usize,
        /// Length that was passed.
        given: usize,
    },
    /// The output slice of a [`ProgramSet`](crate::ProgramSet) has the wrong length.
    #[error("{needed} outputs are computed, but the output slice has length {given}")]
    OutputLength {
        /// Number of expressions in the set.
        needed: usize,
        /// Length that was passed.
        given: usize,
    },
}
