//! Resuming a streamed file at a mark ([`RowSink::mark`]): the rows written after the mark (a
//! run killed after its checkpoint) are cut off, and going on from the mark gives the bytes of
//! a file written in one go.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use marsden_io::{CsvWriter, Group, Layout, NpyDirWriter, RowSink};

fn rows() -> Vec<Vec<f64>> {
    (0..7)
        .map(|i| {
            let x = f64::from(i);
            vec![0.1 * x, x.sin(), x.cos(), -x / 3.0]
        })
        .collect()
}

/// Writes rows 0..3, marks, writes 3..5 (to be cut off), then reopens at the mark and writes
/// 3..7: the file must equal the one written straight through.
fn interrupted_then_resumed(
    make: impl Fn() -> Box<dyn RowSink>,
    reopen: impl Fn(&marsden_io::SinkMark) -> Box<dyn RowSink>,
) {
    let rows = rows();
    let mut first = make();
    for r in &rows[..3] {
        first.write_row(r).unwrap();
    }
    let mark = first.mark().unwrap();
    assert_eq!(mark.rows, 3);
    for r in &rows[3..5] {
        first.write_row(r).unwrap();
    }
    first.flush().unwrap();
    drop(first);
    let mut second = reopen(&mark);
    assert_eq!(second.rows_written(), 3);
    for r in &rows[3..] {
        second.write_row(r).unwrap();
    }
    second.finish().unwrap();
}

#[test]
fn csv_resumed_at_a_mark_equals_one_pass() {
    let dir = tempfile::tempdir().unwrap();
    let header = ["t", "q_x", "p_x", "energy"];
    let (once, twice) = (dir.path().join("once.csv"), dir.path().join("twice.csv"));
    let mut w = CsvWriter::create(&once, &header).unwrap();
    for r in rows() {
        w.write_row(&r).unwrap();
    }
    w.finish().unwrap();
    interrupted_then_resumed(
        || Box::new(CsvWriter::create(&twice, &header).unwrap()),
        |mark| Box::new(CsvWriter::reopen(&twice, &header, mark).unwrap()),
    );
    assert_eq!(
        std::fs::read(&once).unwrap(),
        std::fs::read(&twice).unwrap()
    );
}

#[test]
fn csv_refuses_a_file_shorter_than_its_mark_or_another_header() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.csv");
    let mut w = CsvWriter::create(&path, &["t", "x"]).unwrap();
    w.write_row(&[0.0, 1.0]).unwrap();
    let mut mark = w.mark().unwrap();
    drop(w);
    let other = CsvWriter::reopen(&path, &["t", "y"], &mark).unwrap_err();
    assert!(other.to_string().contains("header"), "{other}");
    mark.bytes[0] += 100;
    let short = CsvWriter::reopen(&path, &["t", "x"], &mark).unwrap_err();
    assert!(short.to_string().contains("checkpoint"), "{short}");
}

#[test]
fn npy_resumed_at_a_mark_equals_one_pass() {
    let layout = Layout::new(vec![
        Group::scalar("t"),
        Group::vector("q", ["x", "y"]),
        Group::scalar("energy"),
    ])
    .unwrap();
    let root = tempfile::tempdir().unwrap();
    let (once, twice) = (root.path().join("once"), root.path().join("twice"));
    let mut w = NpyDirWriter::create(&once, &layout).unwrap();
    for r in rows() {
        w.write_row(&r).unwrap();
    }
    w.finish().unwrap();
    interrupted_then_resumed(
        || Box::new(NpyDirWriter::create(&twice, &layout).unwrap()),
        |mark| Box::new(NpyDirWriter::reopen(&twice, &layout, mark).unwrap()),
    );
    for name in ["t.npy", "q.npy", "energy.npy"] {
        let a = std::fs::read(once.join(name)).unwrap();
        assert_eq!(a, std::fs::read(twice.join(name)).unwrap(), "{name}");
    }
}
