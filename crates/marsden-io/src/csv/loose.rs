//! Reading the numeric columns of a CSV file written by others (a sweep's `sweep.csv`, with a
//! quoted error message per row): RFC 4180 quoting, text columns left out.

use std::fs::File;
use std::io::{BufRead, BufReader};
use std::path::Path;

use super::number::parse_f64;
use crate::error::{Error, Result};
use crate::table::{Column, Table};

/// Reads the columns of a CSV file whose every non-empty field is a number (an empty field
/// reads as NaN); columns holding text (`status`, `error`) or nothing at all are left out.
///
/// Fields may be quoted (`"a, b"`, with `""` for a quote inside); a quoted field may not span
/// lines. Rows shorter or longer than the header are an error naming the line.
///
/// # Errors
/// An I/O error, or [`Error::Parse`] naming `path` and the line.
pub fn read_csv_numeric(path: impl AsRef<Path>) -> Result<Table> {
    let path = path.as_ref();
    let file = File::open(path).map_err(|e| Error::io("open", path, e))?;
    let parse_err = |line: u64, message: String| Error::Parse {
        path: path.to_path_buf(),
        line,
        message,
    };
    let mut lines = BufReader::new(file).lines();
    let header = match lines.next() {
        Some(line) => line.map_err(|e| Error::io("read", path, e))?,
        None => return Err(parse_err(0, "empty file: no header line".into())),
    };
    let names = fields(&header).map_err(|m| parse_err(1, m))?;
    let mut columns: Vec<Option<Vec<f64>>> = vec![Some(Vec::new()); names.len()];
    for (i, line) in lines.enumerate() {
        let line_no = i as u64 + 2;
        let line = line.map_err(|e| Error::io("read", path, e))?;
        if line.trim().is_empty() {
            continue;
        }
        let row = fields(&line).map_err(|m| parse_err(line_no, m))?;
        if row.len() != names.len() {
            let message = format!("{} fields, but the header has {}", row.len(), names.len());
            return Err(parse_err(line_no, message));
        }
        for (column, field) in columns.iter_mut().zip(&row) {
            let value = if field.is_empty() {
                Some(f64::NAN)
            } else {
                parse_f64(field)
            };
            match (column.as_mut(), value) {
                (Some(values), Some(v)) => values.push(v),
                (Some(_), None) => *column = None,
                (None, _) => {}
            }
        }
    }
    let kept = names
        .into_iter()
        .zip(columns)
        .filter_map(|(name, values)| {
            let values = values.filter(|v| v.iter().any(|x| !x.is_nan()))?;
            Some(Column::new(name, values))
        })
        .collect();
    Table::new(kept).map_err(|e| parse_err(1, format!("bad header: {e}")))
}

/// The fields of one CSV line, unquoted.
fn fields(line: &str) -> std::result::Result<Vec<String>, String> {
    let line = line.trim_end_matches('\r');
    let mut out = Vec::new();
    let mut field = String::new();
    let mut chars = line.chars().peekable();
    let mut quoted = false;
    while let Some(c) = chars.next() {
        match (quoted, c) {
            (true, '"') if chars.peek() == Some(&'"') => {
                chars.next();
                field.push('"');
            }
            (true, '"') => quoted = false,
            (true, c) => field.push(c),
            (false, '"') if field.is_empty() => quoted = true,
            (false, ',') => out.push(std::mem::take(&mut field)),
            (false, c) => field.push(c),
        }
    }
    if quoted {
        return Err("a quoted field is not closed on its line".to_owned());
    }
    out.push(field);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quoted_fields_and_text_columns() {
        assert_eq!(
            fields(r#"1,"a, ""b""",,x"#).unwrap(),
            ["1", r#"a, "b""#, "", "x"]
        );
        assert!(fields(r#"1,"open"#).is_err());
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("sweep.csv");
        std::fs::write(
            &path,
            "member,l,energy_max_rel_error,status,error,note\n0,0.5,1e-9,completed,,\n1,1,,failed,\"step 3: no, it diverged\",\n",
        )
        .unwrap();
        let t = read_csv_numeric(&path).unwrap();
        assert_eq!(
            t.names().collect::<Vec<_>>(),
            ["member", "l", "energy_max_rel_error"]
        );
        assert!(t.values("energy_max_rel_error").unwrap()[1].is_nan());
        std::fs::write(&path, "a,b\n1\n").unwrap();
        assert!(
            read_csv_numeric(&path)
                .unwrap_err()
                .to_string()
                .contains("line 2")
        );
    }
}
