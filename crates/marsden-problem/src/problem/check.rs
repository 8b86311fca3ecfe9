//! Shared checks of stage 2, each producing a diagnostic that points at the value at fault.

use std::ops::Range;

use toml::Spanned;

use super::raw::SpannedList;
use crate::error::Diagnostic;
use crate::source::SourceFile;
use marsden_expr::{Expr, ExprError, ProgramSet, Symbols};

/// Validation context: the file, to turn spans into locations.
#[derive(Debug, Clone, Copy)]
pub struct Checker<'a> {
    /// The problem file.
    pub source: &'a SourceFile,
}

impl<'a> Checker<'a> {
    /// A checker for `source`.
    pub fn new(source: &'a SourceFile) -> Self {
        Self { source }
    }

    /// A diagnostic pointing at `span`.
    pub fn error(&self, span: Option<Range<usize>>, message: impl Into<String>) -> Diagnostic {
        Diagnostic::new(message).at(self.source.locate_opt(span))
    }

    /// A finite number, or an error naming `what`.
    pub fn finite(&self, what: &str, value: &Spanned<f64>) -> Result<f64, Diagnostic> {
        let v = *value.get_ref();
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.error(
                Some(value.span()),
                format!("{what} is not a finite number ({v})"),
            ))
        }
    }

    /// A vector of `n` finite numbers (one per coordinate, named in the message).
    pub fn vector(
        &self,
        what: &str,
        list: &SpannedList<f64>,
        coordinates: &[String],
    ) -> Result<Vec<f64>, Diagnostic> {
        let values = list.get_ref();
        if values.len() != coordinates.len() {
            return Err(self.error(
                Some(list.span()),
                format!(
                    "{what} has {} value{}, but the system has {}",
                    values.len(),
                    plural(values.len()),
                    count_coordinates(coordinates)
                ),
            ));
        }
        values
            .iter()
            .enumerate()
            .map(|(i, v)| self.finite(&format!("{what}[{i}]"), v))
            .collect()
    }

    /// Checks that a list of expressions has one per coordinate.
    pub fn one_per_coordinate(
        &self,
        what: &str,
        list: &SpannedList<String>,
        coordinates: &[String],
    ) -> Result<(), Diagnostic> {
        let len = list.get_ref().len();
        if len == coordinates.len() {
            return Ok(());
        }
        Err(self
            .error(
                Some(list.span()),
                format!(
                    "{what} has {len} expression{}, but the system has {}",
                    plural(len),
                    count_coordinates(coordinates)
                ),
            )
            .help("give one expression per coordinate, in the order of `coordinates`"))
    }

    /// Parses an expression written at `value`, reporting errors at their place in the file.
    pub fn parse_expr(&self, context: &str, value: &Spanned<String>) -> Result<Expr, Diagnostic> {
        Expr::parse(value.get_ref()).map_err(|e| self.expr_error(context, value, &e))
    }

    /// Compiles a list of parsed expressions against `symbols`.
    pub fn compile_all(
        &self,
        context: &str,
        list: &SpannedList<String>,
        parsed: &[Expr],
        symbols: &Symbols,
    ) -> Result<ProgramSet, Diagnostic> {
        let programs = parsed
            .iter()
            .zip(list.get_ref())
            .enumerate()
            .map(|(i, (expr, value))| {
                expr.compile(symbols)
                    .map_err(|e| self.expr_error(&format!("{context}[{i}]"), value, &e))
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(ProgramSet::from_programs(programs))
    }

    /// An expression error as a diagnostic. When the expression is a plain TOML string, the
    /// caret points into the file's line; otherwise the expression is shown with its caret.
    pub fn expr_error(&self, context: &str, value: &Spanned<String>, e: &ExprError) -> Diagnostic {
        let d = Diagnostic::new(format!("in {context}: {}", e.kind()));
        let mut d = match self.span_in_file(value, e) {
            Some(span) => d.at(Some(self.source.locate(span))),
            None => {
                let d = d.at(Some(self.source.locate(value.span())));
                let shown = e.to_string();
                let snippet: Vec<&str> = shown.lines().skip(1).take(2).collect();
                d.detail(snippet.join("\n"))
            }
        };
        d.help.extend(e.kind().help());
        d.notes.extend(e.kind().note());
        d
    }

    /// The file span of the expression error, if the value is written verbatim in quotes.
    fn span_in_file(&self, value: &Spanned<String>, e: &ExprError) -> Option<Range<usize>> {
        let span = value.span();
        let text = self.source.text();
        let inner = text.get(span.start + 1..span.end.checked_sub(1)?)?;
        if inner != value.get_ref() {
            return None;
        }
        let start = span.start + 1 + e.span().start;
        Some(start..span.start + 1 + e.span().end.max(e.span().start))
    }
}

/// `"1 coordinate (theta)"`, `"2 coordinates (x, y)"`.
pub fn count_coordinates(coordinates: &[String]) -> String {
    format!(
        "{} coordinate{} ({})",
        coordinates.len(),
        plural(coordinates.len()),
        coordinates.join(", ")
    )
}

/// `"s"` unless `n == 1`.
pub fn plural(n: usize) -> &'static str {
    if n == 1 { "" } else { "s" }
}
