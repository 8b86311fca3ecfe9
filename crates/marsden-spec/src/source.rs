//! The problem file's text, and locations in it (from the byte spans `toml` reports).

use std::fmt;
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

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let number = self.line.to_string();
        let gutter = " ".repeat(number.len());
        let pad: String = self
            .source_line
            .chars()
            .take(self.column - 1)
            .map(|c| if c == '\t' { '\t' } else { ' ' })
            .collect();
        write!(
            f,
            "{gutter}--> {}:{}:{}\n{gutter} |\n{number} | {}\n{gutter} | {pad}{}",
            self.path.display(),
            self.line,
            self.column,
            self.source_line,
            "^".repeat(self.width)
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
