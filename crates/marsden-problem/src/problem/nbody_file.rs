//! `[initial] file = "bodies.txt"`: masses, positions and velocities of `builtin = "nbody"`
//! from a file in the benchmark format (first line `N`, then `m x y z vx vy vz` per body),
//! read with the core's loader ([`marsden::systems::nbody::parse_file`]). The path is relative
//! to the problem file; every mistake in the file names its line.

use std::ops::Range;
use std::path::PathBuf;

use marsden::systems::nbody::{NBodyData, parse_file};
use toml::Spanned;

use super::check::Checker;
use super::raw::RawInitial;
use crate::error::Diagnostic;

/// The bodies read from the file, with the span of the `file` value.
#[derive(Debug, Clone, PartialEq)]
pub struct BodiesFile {
    /// Masses, positions and velocities.
    pub data: NBodyData,
    /// Where `file = "…"` is written.
    pub span: Range<usize>,
    /// The path as resolved (relative to the problem file).
    pub path: PathBuf,
}

/// Most bodies an N-body file may hold.
pub const MAX_BODIES: usize = 100_000;

/// Checks the body count `N` on the first line before anything is allocated for it: at most
/// [`MAX_BODIES`], and no more than the lines that follow.
fn check_count(text: &str) -> Result<(), String> {
    let mut lines = (text.lines().map(str::trim)).filter(|l| !l.is_empty() && !l.starts_with('#'));
    let Some(first) = lines.next() else {
        return Ok(());
    };
    let Ok(n) = first.parse::<u64>() else {
        return Ok(()); // the loader names the mistake
    };
    if n > MAX_BODIES as u64 {
        return Err(format!("{n} bodies is more than the limit of {MAX_BODIES}"));
    }
    let given = lines.count() as u64;
    if n > given {
        return Err(format!(
            "the first line says {n} bodies, but {given} line{} follow",
            if given == 1 { "" } else { "s" }
        ));
    }
    Ok(())
}

/// Reads `[initial] file` if it is given.
///
/// # Errors
/// The file cannot be read, or a line of it is malformed (the message has its line number).
pub fn read(
    ck: &Checker<'_>,
    initial: Option<&Spanned<RawInitial>>,
) -> Result<Option<BodiesFile>, Diagnostic> {
    let Some(file) = initial.and_then(|i| i.get_ref().file.as_ref()) else {
        return Ok(None);
    };
    let span = file.span();
    let base = ck.source.path().parent().map(PathBuf::from);
    // Text without a file of its own (`from_toml_str` with a bare name) has no directory: its
    // paths are relative to the working directory, and the message says so.
    let relative_to = match base.as_ref().is_some_and(|b| !b.as_os_str().is_empty()) {
        true => "the path is relative to the problem file's directory",
        false => "the path is relative to the working directory (the problem text has no file)",
    };
    let path = base.unwrap_or_default().join(file.get_ref());
    let text = crate::source::read_bounded(&path, "N-body file")
        .map_err(|m| ck.error(Some(span.clone()), m).help(relative_to))?;
    check_count(&text).map_err(|m| {
        ck.error(Some(span.clone()), format!("in {}: {m}", path.display()))
            .note("format: first line N, then one line `m x y z vx vy vz` per body")
    })?;
    let data = parse_file(&text).map_err(|e| {
        ck.error(Some(span.clone()), format!("in {}: {e}", path.display()))
            .note("format: first line N, then one line `m x y z vx vy vz` per body")
    })?;
    Ok(Some(BodiesFile { data, span, path }))
}
