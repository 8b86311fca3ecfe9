//! Reading a finished (or interrupted) run's CSV back into a [`Table`].

use std::fs::File;
use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};

use super::number::parse_f64;
use crate::error::{Error, Result};
use crate::sink::RowSink;
use crate::table::{Collector, Table, check_names};
use crate::thin::{Thinned, Thinner};

/// Reads a CSV file as written by [`CsvWriter`](crate::CsvWriter) into a table.
///
/// Accepts `\r\n` line ends, a missing final line end and ASCII spaces around numbers; rejects
/// quoted fields, blank lines between rows and rows of the wrong length, naming the line.
///
/// # Errors
/// An I/O error or [`Error::Parse`], both naming `path`.
pub fn read_csv(path: impl AsRef<Path>) -> Result<Table> {
    let path = path.as_ref();
    let file = File::open(path).map_err(|e| Error::io("open", path, e))?;
    read_csv_from(BufReader::new(file), path)
}

/// Reads CSV from any buffered reader; `path` only names the input in error messages.
///
/// # Errors
/// As [`read_csv`].
pub fn read_csv_from(reader: impl BufRead, path: impl Into<PathBuf>) -> Result<Table> {
    let path = path.into();
    let collector = stream_csv(reader, &path, |names| Ok(Collector::new(names)), false)?;
    collector
        .into_table()
        .map_err(|e| parse_error(&path, 1, format!("bad header: {e}")))
}

/// Reads a run's CSV into a bounded [`Thinned`] sketch for plots (see [`Thinner`]), keeping
/// the extremes of the `monitored` columns. Memory does not grow with the number of rows.
///
/// A last line without a line end is a row cut off by a killed run (the writer ends every
/// row) and is left out, so a half-written number is never drawn.
///
/// # Errors
/// As [`read_csv`].
pub fn read_csv_thinned(
    path: impl AsRef<Path>,
    monitored: &[&str],
    budget: usize,
) -> Result<Thinned> {
    let path = path.as_ref();
    let file = File::open(path).map_err(|e| Error::io("open", path, e))?;
    let thinner = stream_csv(
        BufReader::new(file),
        path,
        |names| Ok(Thinner::new(names, monitored, budget)),
        true,
    )?;
    thinner.finish_table()
}

/// The longest line read (16 MiB: a row of ten thousand columns is under 300 kB); a file
/// without line ends (`/dev/zero`) is refused instead of read until memory runs out.
pub const MAX_LINE: u64 = 16 << 20;

fn parse_error(path: &Path, line: u64, message: String) -> Error {
    Error::Parse {
        path: path.to_path_buf(),
        line,
        message,
    }
}

/// A read error of line `line`: bytes that are not UTF-8 are a parse error naming the file and
/// the line (a trajectory this crate wrote is ASCII), any other an I/O error naming the file.
fn not_text(path: &Path, line: u64, e: std::io::Error) -> Error {
    match e.kind() {
        std::io::ErrorKind::InvalidData => parse_error(
            path,
            line,
            "bytes that are not UTF-8 text: not a trajectory this crate wrote".to_owned(),
        ),
        _ => Error::io("read", path, e),
    }
}

/// Streams the rows of a CSV into the sink `make` builds from the header; with
/// `skip_cut_last`, a final line without a line end is dropped rather than read.
fn stream_csv<S: RowSink>(
    mut reader: impl BufRead,
    path: &Path,
    make: impl FnOnce(Vec<String>) -> Result<S>,
    skip_cut_last: bool,
) -> Result<S> {
    let parse_err = |line: u64, message: String| parse_error(path, line, message);
    let mut line = String::new();
    let mut line_no: u64 = 0;
    // Reads one line without its end; returns (any bytes read, the line had an end).
    let mut next_line = |line: &mut String, line_no: &mut u64| -> Result<(bool, bool)> {
        line.clear();
        *line_no += 1;
        let n = (&mut reader)
            .take(MAX_LINE)
            .read_line(line)
            .map_err(|e| not_text(path, *line_no, e))?;
        let ended = line.ends_with('\n');
        if !ended && n as u64 == MAX_LINE {
            return Err(parse_error(
                path,
                *line_no,
                format!("a line longer than {MAX_LINE} bytes: not a trajectory this crate wrote"),
            ));
        }
        let trimmed = line.trim_end_matches(['\n', '\r']).len();
        line.truncate(trimmed);
        Ok((n > 0, ended))
    };

    if !next_line(&mut line, &mut line_no)?.0 {
        return Err(parse_err(0, "empty file: no header line".into()));
    }
    let names: Vec<String> = line.split(',').map(str::to_owned).collect();
    if let Some(name) = names.iter().find(|n| n.contains('"')) {
        return Err(parse_err(
            1,
            format!("quoted column name {name:?} is not supported"),
        ));
    }
    check_names(names.iter().map(String::as_str))
        .map_err(|e| parse_err(1, format!("bad header: {e}")))?;
    let mut row = Vec::with_capacity(names.len());
    let mut sink = make(names.clone())?;

    let mut blank_at = None;
    loop {
        let (more, ended) = next_line(&mut line, &mut line_no)?;
        if !more || (skip_cut_last && !ended) {
            break;
        }
        if line.is_empty() {
            blank_at.get_or_insert(line_no);
            continue;
        }
        if let Some(blank) = blank_at {
            return Err(parse_err(blank, "blank line between rows".into()));
        }
        row.clear();
        let mut n = 0;
        for field in line.split(',') {
            if let Some(name) = names.get(n) {
                let x = parse_f64(field).ok_or_else(|| {
                    parse_err(
                        line_no,
                        format!("column `{name}`: {field:?} is not a number"),
                    )
                })?;
                row.push(x);
            }
            n += 1;
        }
        if n != names.len() {
            return Err(parse_err(
                line_no,
                format!("{n} fields, but the header has {} columns", names.len()),
            ));
        }
        sink.write_row(&row)?;
    }
    Ok(sink)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(s: &str) -> Result<Table> {
        read_csv_from(s.as_bytes(), "mem.csv")
    }

    #[test]
    fn reads_crlf_and_missing_final_newline() {
        let t = read("t,q_x\r\n0,1\r\n0.5,-0").unwrap();
        assert_eq!(t.values("t"), Some(&[0.0, 0.5][..]));
        assert_eq!(t.values("q_x").unwrap()[1].to_bits(), (-0.0f64).to_bits());
    }

    #[test]
    fn header_only_is_an_empty_table() {
        let t = read("t,energy\n").unwrap();
        assert_eq!(t.n_rows(), 0);
        assert_eq!(t.names().collect::<Vec<_>>(), ["t", "energy"]);
    }

    #[test]
    fn errors_name_file_and_line() {
        let e = read("t,q\n0,1\n1,2,3\n").unwrap_err().to_string();
        assert!(
            e.contains("mem.csv, line 3") && e.contains("3 fields"),
            "{e}"
        );
        let e = read("t,q\n0,1\n1\n").unwrap_err().to_string();
        assert!(e.contains("line 3") && e.contains("1 fields"), "{e}");
        let e = read("t,q\n0,abc\n").unwrap_err().to_string();
        assert!(e.contains("line 2") && e.contains("`q`"), "{e}");
        let e = read("t,q\n0,1\n\n1,2\n").unwrap_err().to_string();
        assert!(e.contains("line 3") && e.contains("blank"), "{e}");
        assert!(read("").is_err());
        assert!(read("t,t\n").is_err());
        assert!(read("\"t\",q\n").is_err());
        // Trailing blank lines are harmless.
        assert_eq!(read("t\n1\n\n").unwrap().n_rows(), 1);
    }
}
