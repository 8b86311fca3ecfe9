//! The problem file's text, and locations in it (from the byte spans `toml` reports).

use std::fmt;
use std::io::Read as _;
use std::ops::Range;
use std::path::{Path, PathBuf};

use sha2::{Digest, Sha256};

/// A problem file read into memory: its path (as given), its text and its SHA-256.
#[derive(Debug, Clone, PartialEq)]
pub struct SourceFile {
    path: PathBuf,
    text: String,
    sha256: String,
}

impl SourceFile {
    /// Wraps text read from `path`.
    pub fn new(path: impl Into<PathBuf>, text: String) -> Self {
        let sha256 = hex(&Sha256::digest(text.as_bytes()));
        Self {
            path: path.into(),
            text,
            sha256,
        }
    }

    /// The path as given on the command line.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The file's text.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// SHA-256 of the file's bytes, lower-case hex (the provenance of a run).
    pub fn sha256(&self) -> &str {
        &self.sha256
    }

    /// The location of a byte span, with the source line it starts on.
    pub fn locate(&self, span: Range<usize>) -> Location {
        let start = floor_char_boundary(&self.text, span.start);
        let end = floor_char_boundary(&self.text, span.end.max(start));
        let line_start = self.text[..start].rfind('\n').map_or(0, |i| i + 1);
        let line_end = self.text[start..]
            .find('\n')
            .map_or(self.text.len(), |i| start + i);
        let line_text = self.text[line_start..line_end].trim_end_matches('\r');
        let column = self.text[line_start..start].chars().count();
        let width = self.text[start..end.min(line_end)].chars().count().max(1);
        Location {
            path: self.path.clone(),
            line: self.text[..start].matches('\n').count() + 1,
            column: column + 1,
            source_line: line_text.to_owned(),
            width,
        }
    }

    /// [`SourceFile::locate`] of an optional span.
    pub fn locate_opt(&self, span: Option<Range<usize>>) -> Option<Location> {
        span.map(|s| self.locate(s))
    }
}

/// Largest problem file read, in bytes (a problem file is a few kilobytes; an N-body file of
/// 10⁵ bodies a few megabytes).
pub const MAX_FILE_BYTES: u64 = 16 * 1024 * 1024;

/// Reads the text of `path` if it is a regular file of at most [`MAX_FILE_BYTES`] bytes in
/// UTF-8 (never more is read; a device such as `/dev/zero` is refused without reading).
///
/// # Errors
/// A message naming `what` and the path: not a regular file, too large, not UTF-8 (with the
/// byte offset of the first bad byte), or the I/O error.
pub fn read_bounded(path: &Path, what: &str) -> Result<String, String> {
    let cannot = |e: &dyn fmt::Display| format!("cannot read the {what} {}: {e}", path.display());
    let file = std::fs::File::open(path).map_err(|e| cannot(&e))?;
    let meta = file.metadata().map_err(|e| cannot(&e))?;
    if !meta.is_file() {
        return Err(cannot(&"it is not a regular file"));
    }
    let too_large = |n: u64| {
        format!(
            "the {what} {} is {n} bytes, more than the limit of {MAX_FILE_BYTES} bytes",
            path.display()
        )
    };
    if meta.len() > MAX_FILE_BYTES {
        return Err(too_large(meta.len()));
    }
    let mut bytes = Vec::new();
    file.take(MAX_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| cannot(&e))?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(too_large(bytes.len() as u64));
    }
    String::from_utf8(bytes).map_err(|e| {
        let at = e.utf8_error().valid_up_to();
        cannot(&format!(
            "it is not UTF-8 text (invalid byte at offset {at})"
        ))
    })
}

/// `text` cut to at most `limit` characters, the cut marked `…` (messages quote values).
pub fn shorten(text: &str, limit: usize) -> String {
    match text.char_indices().nth(limit) {
        Some((i, _)) => format!("{}…", &text[..i]),
        None => text.to_owned(),
    }
}

fn floor_char_boundary(text: &str, offset: usize) -> usize {
    let mut i = offset.min(text.len());
    while !text.is_char_boundary(i) {
        i -= 1;
    }
    i
}

fn hex(bytes: &[u8]) -> String {
    use fmt::Write as _;
    bytes.iter().fold(String::new(), |mut s, b| {
        let _ = write!(s, "{b:02x}");
        s
    })
}

/// A place in a problem file: `path:line:column`, the line's text and how many characters to
/// underline. Displayed as
///
/// ```text
///   --> examples/pendulum.toml:12:5
///    |
/// 12 | h = -0.05
///    |     ^^^^^
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// The file.
    pub path: PathBuf,
    /// 1-based line number.
    pub line: usize,
    /// 1-based column, in characters.
    pub column: usize,
    /// The text of that line.
    pub source_line: String,
    /// Number of characters to underline (at least 1; the span is cut at the line's end).
    pub width: usize,
}

/// Lines longer than this (in characters) are shown as a window around the column.
const LINE_LIMIT: usize = 120;

/// Characters shown on either side of the column in a long line.
const WINDOW: usize = 50;

impl Location {
    /// The line to show and the characters before the caret: the whole line, or a window of
    /// [`WINDOW`] characters on either side of the column with the cuts marked `…`.
    fn window(&self) -> (String, String) {
        let chars: Vec<char> = self.source_line.chars().collect();
        let column = (self.column - 1).min(chars.len());
        let (from, to) = if chars.len() > LINE_LIMIT {
            (
                column.saturating_sub(WINDOW),
                (column + WINDOW).min(chars.len()),
            )
        } else {
            (0, chars.len())
        };
        let head = if from > 0 { "…" } else { "" };
        let tail = if to < chars.len() { "…" } else { "" };
        let shown: String = chars[from..to].iter().collect();
        let pad = head
            .chars()
            .chain(chars[from..column].iter().copied())
            .map(|c| if c == '\t' { '\t' } else { ' ' })
            .collect();
        (format!("{head}{shown}{tail}"), pad)
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let number = self.line.to_string();
        let gutter = " ".repeat(number.len());
        let (line, pad) = self.window();
        let width = self.width.min(WINDOW + 1);
        write!(
            f,
            "{gutter}--> {}:{}:{}\n{gutter} |\n{number} | {}\n{gutter} | {pad}{}",
            self.path.display(),
            self.line,
            self.column,
            line,
            "^".repeat(width)
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn locates_spans_by_line_and_character_column() {
        let src = SourceFile::new("p.toml", "[integrator]\nméthod = 1\nh = -0.5\n".into());
        let at = src.text().find("-0.5").unwrap();
        let loc = src.locate(at..at + 4);
        assert_eq!((loc.line, loc.column, loc.width), (3, 5, 4));
        assert_eq!(
            loc.to_string(),
            " --> p.toml:3:5\n  |\n3 | h = -0.5\n  |     ^^^^"
        );
        let at = src.text().find("= 1").unwrap();
        assert_eq!(src.locate(at..at + 1).column, 8);
    }

    #[test]
    fn hashes_the_text() {
        let src = SourceFile::new("x", "abc".into());
        assert_eq!(
            src.sha256(),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
    }
}
