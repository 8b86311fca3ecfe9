//! Errors of the command: a [`Diagnostic`] (what went wrong, where, what to do) and the exit
//! status it maps to.
//!
//! Every mistake in a problem file becomes one diagnostic, rendered in the same plain style as
//! the expression errors of [`crate::expr`]:
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
use std::process::ExitCode;

use crate::source::Location;

/// The exit status of `marsden` (part of the command's contract).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    /// 0: the command completed (for `run`: every requested step was taken).
    Completed,
    /// 1: the simulation failed; the partial trajectory and the summary were still written.
    Failed,
    /// 2: a bad problem file or bad usage; nothing was run.
    BadInput,
}

impl Status {
    /// The numeric exit code.
    pub fn code(self) -> u8 {
        match self {
            Status::Completed => 0,
            Status::Failed => 1,
            Status::BadInput => 2,
        }
    }
}

impl From<Status> for ExitCode {
    fn from(status: Status) -> Self {
        ExitCode::from(status.code())
    }
}

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

/// A command that could not do its job: the report and the exit status.
#[derive(Debug, Clone, PartialEq)]
pub struct CliError {
    /// What to print on stderr.
    pub diagnostic: Diagnostic,
    /// How the process ends.
    pub status: Status,
}

impl CliError {
    /// A bad problem file or bad usage (exit status 2).
    pub fn bad_input(diagnostic: Diagnostic) -> Self {
        Self {
            diagnostic,
            status: Status::BadInput,
        }
    }

    /// A failure while running (exit status 1).
    pub fn failed(diagnostic: Diagnostic) -> Self {
        Self {
            diagnostic,
            status: Status::Failed,
        }
    }
}

impl From<Diagnostic> for CliError {
    fn from(diagnostic: Diagnostic) -> Self {
        Self::bad_input(diagnostic)
    }
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.diagnostic.fmt(f)
    }
}

impl std::error::Error for CliError {}

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
        assert_eq!(CliError::from(d).status.code(), 2);
    }
}
