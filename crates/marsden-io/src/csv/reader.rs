//! Reading a finished (or interrupted) run's CSV back into a [`Table`].

use std::fs::File;
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};

use super::number::parse_f64;
use crate::error::{Error, Result};
use crate::table::{Column, Table};

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
pub fn read_csv_from(mut reader: impl BufRead, path: impl Into<PathBuf>) -> Result<Table> {
    let path = path.into();
    let parse_err = |line: u64, message: String| Error::Parse {
        path: path.clone(),
        line,
        message,
    };
    let mut line = String::new();
    let mut line_no: u64 = 0;
    let mut next_line = |line: &mut String, line_no: &mut u64| -> Result<bool> {
        line.clear();
        let n = reader
            .read_line(line)
            .map_err(|e| Error::io("read", &path, e))?;
        *line_no += 1;
        let trimmed = line.trim_end_matches(['\n', '\r']).len();
        line.truncate(trimmed);
        Ok(n > 0)
    };

    if !next_line(&mut line, &mut line_no)? {
        return Err(parse_err(0, "empty file: no header line".into()));
    }
    let mut columns: Vec<Column> = line
        .split(',')
        .map(|name| Column::new(name, Vec::new()))
        .collect();
    if let Some(c) = columns.iter().find(|c| c.name.contains('"')) {
        return Err(parse_err(
            1,
            format!("quoted column name {:?} is not supported", c.name),
        ));
    }

    let mut blank_at = None;
    while next_line(&mut line, &mut line_no)? {
        if line.is_empty() {
            blank_at.get_or_insert(line_no);
            continue;
        }
        if let Some(blank) = blank_at {
            return Err(parse_err(blank, "blank line between rows".into()));
        }
        let mut n = 0;
        for field in line.split(',') {
            let Some(col) = columns.get_mut(n) else {
                n += 1;
                continue;
            };
            let x = parse_f64(field).ok_or_else(|| {
                parse_err(
                    line_no,
                    format!("column `{}`: {field:?} is not a number", col.name),
                )
            })?;
            col.values.push(x);
            n += 1;
        }
        if n != columns.len() {
            return Err(parse_err(
                line_no,
                format!("{n} fields, but the header has {} columns", columns.len()),
            ));
        }
    }
    Table::new(columns).map_err(|e| parse_err(1, format!("bad header: {e}")))
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
