//! CSV: bit-identical round trips, exact headers, streaming that can stop at any row.

// Test helpers outside `#[test]` functions fail loudly too.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::io::Write;
use std::path::Path;

use marsden_io::{Column, CsvWriter, Error, RowSink, Table, read_csv, read_csv_from, write_csv};
use proptest::prelude::*;

/// Bitwise equality, except that any NaN matches any NaN (CSV writes every NaN as `NaN`).
fn same(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

fn assert_tables_match(a: &Table, b: &Table) {
    assert_eq!(a.names().collect::<Vec<_>>(), b.names().collect::<Vec<_>>());
    assert_eq!(a.n_rows(), b.n_rows());
    for (ca, cb) in a.columns().iter().zip(b.columns()) {
        for (i, (&x, &y)) in ca.values.iter().zip(&cb.values).enumerate() {
            assert!(
                same(x, y),
                "{}[{i}]: wrote {x:e} ({:#x}), read {y:e} ({:#x})",
                ca.name,
                x.to_bits(),
                y.to_bits()
            );
        }
    }
}

/// Any f64 at all: every bit pattern (subnormals, ±0, ±inf, NaNs) is equally likely.
fn any_bits() -> impl Strategy<Value = f64> {
    any::<u64>().prop_map(f64::from_bits)
}

/// Values spread over every class and magnitude, weighted towards the interesting ones.
fn any_value() -> impl Strategy<Value = f64> {
    prop_oneof![
        any_bits(),
        proptest::num::f64::ANY,
        (-1e3..1e3f64),
        Just(0.0),
        Just(-0.0),
        Just(f64::MIN_POSITIVE),
        Just(f64::from_bits(1)),
        Just(f64::MAX),
        Just(f64::MIN),
    ]
}

fn tables() -> impl Strategy<Value = Table> {
    (1usize..6, 0usize..40).prop_flat_map(|(cols, rows)| {
        proptest::collection::vec(proptest::collection::vec(any_value(), rows), cols).prop_map(
            |columns| {
                let named = columns
                    .into_iter()
                    .enumerate()
                    .map(|(i, v)| Column::new(format!("c_{i}"), v))
                    .collect();
                Table::new(named).unwrap()
            },
        )
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn file_round_trip_is_bit_identical(table in tables()) {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("trajectory.csv");
        write_csv(&path, &table).unwrap();
        assert_tables_match(&table, &read_csv(&path).unwrap());
    }

    #[test]
    fn streamed_round_trip_is_bit_identical(values in proptest::collection::vec(any_bits(), 0..300)) {
        let mut w = CsvWriter::from_writer(Vec::new(), "mem.csv", &["t", "x", "y"]).unwrap();
        for row in values.chunks_exact(3) {
            w.write_row(row).unwrap();
        }
        let bytes = w.into_inner().unwrap();
        let back = read_csv_from(bytes.as_slice(), "mem.csv").unwrap();
        let flat: Vec<f64> = (0..back.n_rows()).flat_map(|i| back.row(i).unwrap()).collect();
        prop_assert_eq!(flat.len(), values.len() / 3 * 3);
        for (a, b) in values.iter().zip(&flat) {
            prop_assert!(same(*a, *b), "{:e} came back as {:e}", a, b);
        }
    }
}

#[test]
fn header_is_exactly_as_given() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("trajectory.csv");
    let header = [
        "t",
        "q_theta",
        "q_phi",
        "p_theta",
        "p_phi",
        "energy",
        "J_rotation about z",
        "constraint_residual",
    ];
    let w = CsvWriter::create(&path, &header).unwrap();
    drop(w);
    let text = std::fs::read_to_string(&path).unwrap();
    assert_eq!(text, format!("{}\n", header.join(",")));
    let t = read_csv(&path).unwrap();
    assert_eq!(t.names().collect::<Vec<_>>(), header);
    assert_eq!(t.n_rows(), 0);
}

#[test]
fn numbers_are_written_shortest_and_readably() {
    let mut w = CsvWriter::from_writer(Vec::new(), "mem", &["a", "b", "c", "d", "e", "f"]).unwrap();
    w.write_row(&[
        0.1,
        -0.0,
        1e-300,
        6.02214076e23,
        f64::NAN,
        f64::NEG_INFINITY,
    ])
    .unwrap();
    let text = String::from_utf8(w.into_inner().unwrap()).unwrap();
    assert_eq!(text, "a,b,c,d,e,f\n0.1,-0,1e-300,6.02214076e23,NaN,-inf\n");
}

#[test]
fn finishing_early_keeps_a_valid_file_with_the_rows_so_far() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("trajectory.csv");
    let mut w = CsvWriter::create(&path, &["t", "q_x", "energy"]).unwrap();
    for i in 0..537 {
        let t = f64::from(i) * 0.01;
        w.write_row(&[t, t.sin(), 0.5]).unwrap();
    }
    // The run fails here: the CLI finishes the writer and reports the error.
    w.finish().unwrap();
    w.finish().unwrap(); // idempotent
    assert_eq!(w.rows_written(), 537);
    let e = w.write_row(&[1.0, 2.0, 3.0]).unwrap_err();
    assert!(matches!(e, Error::Finished { .. }), "{e}");
    let table = read_csv(&path).unwrap();
    assert_eq!(table.n_rows(), 537);
    assert_eq!(table.values("q_x").unwrap()[536], (5.36f64).sin());
}

#[test]
fn dropping_an_unfinished_writer_keeps_its_rows() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("trajectory.csv");
    {
        let mut w = CsvWriter::create(&path, &["t"]).unwrap();
        for i in 0..10 {
            w.write_row(&[f64::from(i)]).unwrap();
        }
        // e.g. an early `?` return in the CLI
    }
    assert_eq!(read_csv(&path).unwrap().n_rows(), 10);
}

#[test]
fn streaming_memory_is_bounded_rows_reach_the_file_before_finish() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("trajectory.csv");
    let mut w = CsvWriter::create(&path, &["t", "q", "p"]).unwrap();
    for i in 0..200_000 {
        let t = f64::from(i) * 1e-3;
        w.write_row(&[t, t.cos(), -t.sin()]).unwrap();
    }
    let on_disk = std::fs::metadata(&path).unwrap().len();
    assert!(
        on_disk > 1_000_000,
        "only {on_disk} bytes reached the file before finish"
    );
    // What is on disk before finish is whole rows: it parses.
    let partial = read_csv(&path).unwrap();
    assert!(partial.n_rows() > 10_000 && partial.n_rows() <= 200_000);
    w.finish().unwrap();
    assert_eq!(read_csv(&path).unwrap().n_rows(), 200_000);
}

/// A writer that fails once `limit` bytes have been accepted.
struct FailAfter {
    written: Vec<u8>,
    limit: usize,
}

impl Write for FailAfter {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        if self.written.len() + buf.len() > self.limit {
            return Err(std::io::Error::other("disk full"));
        }
        self.written.extend_from_slice(buf);
        Ok(buf.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

#[test]
fn io_failures_are_typed_errors_naming_the_path() {
    let sink = FailAfter {
        written: Vec::new(),
        limit: 100_000,
    };
    let mut w = CsvWriter::from_writer(sink, "/runs/pendulum/trajectory.csv", &["t", "q"]).unwrap();
    let err = (0..100_000)
        .map(|i| w.write_row(&[f64::from(i), 0.25]))
        .find_map(Result::err)
        .expect("the sink fills up");
    assert!(matches!(err, Error::Io { .. }));
    let msg = err.to_string();
    assert!(
        msg.contains("/runs/pendulum/trajectory.csv") && msg.contains("disk full"),
        "{msg}"
    );

    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("no/such/dir/trajectory.csv");
    let err = CsvWriter::create(&missing, &["t"]).unwrap_err();
    assert!(
        err.to_string().contains("no/such/dir/trajectory.csv"),
        "{err}"
    );
    let err = read_csv(&missing).unwrap_err();
    assert!(
        matches!(err, Error::Io { .. }) && err.to_string().contains("no/such/dir"),
        "{err}"
    );
}

/// A disk that takes bytes up to `limit`, then refuses (a short write, then an error, as a
/// file-size limit or a full disk do).
struct ShortThenFull {
    written: Vec<u8>,
    limit: usize,
}

impl Write for ShortThenFull {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let room = self.limit - self.written.len();
        if room == 0 {
            return Err(std::io::Error::other("file too large"));
        }
        let k = room.min(buf.len());
        self.written.extend_from_slice(&buf[..k]);
        Ok(k)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// After a write that fails part-way, `rows_written` counts the whole rows the writer took
/// (not the rows accepted into the buffer), for limits inside the header, at a row boundary
/// and inside a row.
#[test]
fn rows_written_after_a_failed_write_are_the_whole_rows_on_disk() {
    for limit in [3, 9, 70_000, 100_003, 150_000] {
        let sink = ShortThenFull {
            written: Vec::new(),
            limit,
        };
        let Ok(mut w) = CsvWriter::from_writer(sink, "trajectory.csv", &["t", "q"]) else {
            assert!(limit < 4, "the header `t,q` fits in {limit} bytes");
            continue;
        };
        let err = (0..1_000_000)
            .map(|i| w.write_row(&[f64::from(i), 0.125]))
            .find_map(Result::err)
            .expect("the sink fills up");
        assert!(err.to_string().contains("trajectory.csv"), "{err}");
        let rows = w.rows_written();
        assert!(rows < 1_000_000);
        // Nothing more is written after the failure, and the count stays.
        assert!(w.flush().is_ok());
        assert_eq!(w.rows_written(), rows);
        let bytes = w.into_inner().unwrap().written;
        let whole = bytes.iter().filter(|&&b| b == b'\n').count() as u64;
        assert_eq!(rows, whole - 1, "limit {limit}");
        let text = String::from_utf8(bytes).unwrap();
        if let Some(last) = rows.checked_sub(1) {
            let line = text.lines().nth(rows as usize).unwrap();
            assert_eq!(line, format!("{last},0.125"));
        }
    }
}

#[test]
fn rows_and_headers_are_checked() {
    let mut w = CsvWriter::from_writer(Vec::new(), "mem.csv", &["t", "q"]).unwrap();
    let err = w.write_row(&[1.0]).unwrap_err();
    assert!(
        matches!(
            err,
            Error::RowLength {
                expected: 2,
                found: 1,
                row: 0,
                ..
            }
        ),
        "{err}"
    );
    assert!(CsvWriter::from_writer(Vec::new(), "m", &["t", "t"]).is_err());
    assert!(CsvWriter::from_writer(Vec::new(), "m", &["a,b"]).is_err());
    assert!(CsvWriter::from_writer(Vec::new(), "m", &[] as &[&str]).is_err());
    // A rejected header creates no file.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.csv");
    assert!(CsvWriter::create(&path, &["x\ny"]).is_err());
    assert!(!Path::new(&path).exists());
}

#[test]
fn works_as_a_row_sink() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("trajectory.csv");
    let mut sink: Box<dyn RowSink> = Box::new(CsvWriter::create(&path, &["t", "q"]).unwrap());
    sink.write_row(&[0.0, 1.0]).unwrap();
    sink.flush().unwrap();
    assert_eq!(read_csv(&path).unwrap().n_rows(), 1);
    sink.write_row(&[0.1, 0.9]).unwrap();
    sink.finish().unwrap();
    assert_eq!(sink.rows_written(), 2);
    assert_eq!(read_csv(&path).unwrap().values("q"), Some(&[1.0, 0.9][..]));
}

/// numpy (if installed) reads our CSV to the same bits. Skipped when python3/numpy is absent.
#[test]
fn numpy_reads_the_csv_identically_if_available() {
    let ok = std::process::Command::new("python3")
        .args(["-c", "import numpy"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !ok {
        eprintln!("skipped: python3 with numpy not available");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("trajectory.csv");
    let values = [
        0.1,
        -0.0,
        1e-300,
        5e-324,
        1.7976931348623157e308,
        1.0 / 3.0,
        f64::INFINITY,
        f64::NAN,
    ];
    let table = Table::new(vec![Column::new("v", values.to_vec())]).unwrap();
    write_csv(&path, &table).unwrap();
    let script = "import sys, numpy as np\n\
        a = np.genfromtxt(sys.argv[1], delimiter=',', skip_header=1)\n\
        print(' '.join(hex(x) for x in a.view(np.uint64)))";
    let out = std::process::Command::new("python3")
        .args(["-c", script, path.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let bits: Vec<u64> = String::from_utf8(out.stdout)
        .unwrap()
        .split_whitespace()
        .map(|h| u64::from_str_radix(h.trim_start_matches("0x"), 16).unwrap())
        .collect();
    assert_eq!(bits.len(), values.len());
    for (v, b) in values.iter().zip(bits) {
        assert!(
            same(*v, f64::from_bits(b)),
            "{v:e} read by numpy as {:e}",
            f64::from_bits(b)
        );
    }
}
