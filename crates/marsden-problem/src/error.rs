//! Errors of the problem-file layer: a [`Diagnostic`] (what went wrong, where, what to do) and
//! an [`Error`] that says whether anything ran ([`ErrorKind`]; the command maps it to its exit
//! status).
//!
//! Every mistake in a problem file becomes one diagnostic, rendered in the same plain style as
//! the expression errors of [`marsden_expr`]:
//!
//! ```text
//! error: unknown key `lagrangain` in [system]
//!   --> examples/pendulum.toml:5:1
//!    |
//!  5 | lagrangain = "0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)"
//!    | ^^^^^^^^^^
//!   = help: did you mean `lagrangian`?
//!   = note: valid keys in [system]: builtin, constraints, coordinates, forces, …
//! ```
//!
//! Plain text (no colours, no terminal detection) keeps the messages identical on a terminal,
//! in a log and in the tests that assert them.

use std::fmt;

use crate::source::Location;

/// One error report: a message, optionally where it happened in the problem file, a detail
/// block (such as an expression with a caret), and help and note lines.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Diagnostic {
    /// The headline, without the `error: ` prefix.
    pub message: String,
    /// Where in the problem file, with the source line to show (boxed: keeps `Result`s small).
    pub location: Option<Box<Location>>,
    /// A preformatted block shown under the location (already indented).
    pub detail: Option<String>,
    /// `= help:` lines: what to do about it.
    pub help: Vec<String>,
    /// `= note:` lines: context, such as the list of valid names.
    pub notes: Vec<String>,
}

impl Diagnostic {
    /// A diagnostic with just a message.
    pub fn new(message: impl Into<String>) -> Self {
        Self {
            message: message.into(),
            ..Self::default()
        }
    }

    /// Points the diagnostic at a place in the problem file.
    #[must_use]
    pub fn at(mut self, location: Option<Location>) -> Self {
        self.location = location.map(Box::new);
        self
    }

    /// Adds a detail block.
    #[must_use]
    pub fn detail(mut self, detail: impl Into<String>) -> Self {
        self.detail = Some(detail.into());
        self
    }

    /// Adds a help line.
    #[must_use]
    pub fn help(mut self, help: impl Into<String>) -> Self {
        self.help.push(help.into());
        self
    }

    /// Adds a note line.
    #[must_use]
    pub fn note(mut self, note: impl Into<String>) -> Self {
        self.notes.push(note.into());
        self
    }

    /// Adds `did you mean …?` if `suggestion` is some.
    #[must_use]
    pub fn suggest(self, suggestion: Option<&str>) -> Self {
        match suggestion {
            Some(s) => self.help(format!("did you mean `{s}`?")),
            None => self,
        }
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "error: {}", self.message)?;
        if let Some(location) = &self.location {
            write!(f, "\n{location}")?;
        }
        if let Some(detail) = &self.detail {
            write!(f, "\n{detail}")?;
        }
        for help in &self.help {
            write!(f, "\n  = help: {help}")?;
        }
        for note in &self.notes {
            write!(f, "\n  = note: {note}")?;
        }
        Ok(())
    }
}

impl std::error::Error for Diagnostic {}

/// Whether an error came before anything ran, or while running and writing results.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ErrorKind {
    /// A bad problem file, bad arguments, or a problem the core refuses to start; nothing was
    /// run (the command exits with status 2).
    BadInput,
    /// The work started but could not be finished or written up (status 1).
    Failed,
}

/// An error of the problem-file layer: the report and its [`ErrorKind`].
#[derive(Debug, Clone, PartialEq)]
pub struct Error {
    /// What to show.
    pub diagnostic: Diagnostic,
    /// Before or after anything ran.
    pub kind: ErrorKind,
}

impl Error {
    /// A bad problem file or bad arguments: nothing was run.
    pub fn bad_input(diagnostic: Diagnostic) -> Self {
        Self {
            diagnostic,
            kind: ErrorKind::BadInput,
        }
    }

    /// A failure while running or writing the results.
    pub fn failed(diagnostic: Diagnostic) -> Self {
        Self {
            diagnostic,
            kind: ErrorKind::Failed,
        }
    }
}

impl From<Diagnostic> for Error {
    fn from(diagnostic: Diagnostic) -> Self {
        Self::bad_input(diagnostic)
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.diagnostic.fmt(f)
    }
}

impl std::error::Error for Error {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn renders_message_help_and_notes_in_order() {
        let d = Diagnostic::new("unknown method `midpiont`")
            .suggest(Some("midpoint"))
            .note("methods: midpoint, trapezoid");
        assert_eq!(
            d.to_string(),
            "error: unknown method `midpiont`\n  = help: did you mean `midpoint`?\n  \
             = note: methods: midpoint, trapezoid"
        );
        assert_eq!(Error::from(d).kind, ErrorKind::BadInput);
    }
}
