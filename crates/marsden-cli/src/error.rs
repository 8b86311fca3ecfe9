//! The exit statuses of `marsden` and the error a command ends with.
//!
//! The reports themselves are [`marsden_spec::Diagnostic`]s (plain text, identical on a
//! terminal, in a log and in the tests); this module only decides the exit status.

use std::fmt;
use std::process::ExitCode;

use marsden_spec::{Diagnostic, ErrorKind};

/// The exit status of `marsden` (part of the command's contract).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    /// 0: the command completed (for `run`: every requested step was taken).
    Completed,
    /// 1: the simulation failed or was interrupted; the partial trajectory and the summary
    /// were still written.
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

impl From<marsden_spec::Error> for CliError {
    fn from(e: marsden_spec::Error) -> Self {
        let status = match e.kind {
            ErrorKind::BadInput => Status::BadInput,
            ErrorKind::Failed => Status::Failed,
        };
        Self {
            diagnostic: e.diagnostic,
            status,
        }
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
    fn statuses_follow_the_error_kind() {
        let d = Diagnostic::new("unknown method `midpiont`");
        assert_eq!(CliError::from(d.clone()).status.code(), 2);
        let failed = marsden_spec::Error::failed(d);
        assert_eq!(CliError::from(failed).status.code(), 1);
    }
}
