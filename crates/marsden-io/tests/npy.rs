//! `.npy`: read back with npyz (shape, dtype `<f8`, bit-identical values), 1-D and 2-D,
//! streaming per column group, and valid files at every stage of a run.

// Test helpers outside `#[test]` functions fail loudly too.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::Path;

use marsden_io::{
    Column, Error, Group, Layout, NpyDirWriter, NpyShape, NpyWriter, RowSink, Table, read_npy,
    read_npy_dir, read_npy_dir_thinned, write_npy_dir,
};
use proptest::prelude::*;

/// Reads a file with npyz directly (not through this crate): (dtype, shape, C-order?, values).
fn npyz_read(path: &Path) -> (String, Vec<u64>, bool, Vec<f64>) {
    let bytes = std::fs::read(path).unwrap();
    let npy = npyz::NpyFile::new(bytes.as_slice()).unwrap();
    let dtype = match npy.dtype() {
        npyz::DType::Plain(t) => t.to_string(),
        other => panic!("unexpected dtype {other:?}"),
    };
    let shape = npy.shape().to_vec();
    let c_order = npy.order() == npyz::Order::C;
    (dtype, shape, c_order, npy.into_vec::<f64>().unwrap())
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn two_d_round_trip_is_bit_identical(
        (cols, data) in (1usize..5, 0usize..50).prop_flat_map(|(c, r)| {
            (Just(c), proptest::collection::vec(any::<u64>().prop_map(f64::from_bits), c * r))
        })
    ) {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("q.npy");
        let mut w = NpyWriter::create(&path, NpyShape::Matrix { columns: cols }).unwrap();
        for row in data.chunks_exact(cols) {
            w.write_row(row).unwrap();
        }
        w.finish().unwrap();
        let (dtype, shape, c_order, values) = npyz_read(&path);
        prop_assert_eq!(dtype, "<f8");
        prop_assert_eq!(shape, vec![(data.len() / cols) as u64, cols as u64]);
        prop_assert!(c_order);
        // Binary format: even NaN payloads survive.
        prop_assert_eq!(bits(&values), bits(&data));
    }
}

#[test]
fn one_d_round_trip() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.npy");
    let data = [
        0.0,
        -0.0,
        5e-324,
        f64::MAX,
        f64::NAN,
        f64::NEG_INFINITY,
        0.1,
    ];
    let mut w = NpyWriter::create(&path, NpyShape::Vector).unwrap();
    for x in data {
        w.write_row(&[x]).unwrap();
    }
    w.finish().unwrap();
    let (dtype, shape, _, values) = npyz_read(&path);
    assert_eq!(dtype, "<f8");
    assert_eq!(shape, [data.len() as u64]);
    assert_eq!(bits(&values), bits(&data));
    // And through this crate's reader.
    let a = read_npy(&path).unwrap();
    assert_eq!((a.dtype.as_str(), a.shape.as_slice()), ("<f8", &[7u64][..]));
    assert_eq!(bits(&a.data), bits(&data));
}

#[test]
fn empty_arrays_are_valid() {
    let dir = tempfile::tempdir().unwrap();
    let p1 = dir.path().join("e1.npy");
    let p2 = dir.path().join("e2.npy");
    NpyWriter::create(&p1, NpyShape::Vector)
        .unwrap()
        .finish()
        .unwrap();
    NpyWriter::create(&p2, NpyShape::Matrix { columns: 3 })
        .unwrap()
        .finish()
        .unwrap();
    assert_eq!(npyz_read(&p1).1, [0]);
    assert_eq!(npyz_read(&p2).1, [0, 3]);
}

fn layout() -> Layout {
    Layout::new(vec![
        Group::scalar("t"),
        Group::vector("q", ["q_x", "q_y"]),
        Group::vector("p", ["p_x", "p_y"]),
        Group::scalar("energy"),
        Group::vector("J", ["J_rot"]),
        Group::scalar("constraint_residual"),
    ])
    .unwrap()
}

fn row(i: u32) -> [f64; 8] {
    let t = f64::from(i) * 0.01;
    [
        t,
        t.cos(),
        t.sin(),
        -t.sin(),
        t.cos(),
        0.5,
        1.0 + 1e-16 * t,
        1e-15 * t,
    ]
}

#[test]
fn one_file_per_group_with_the_right_rank() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run");
    let mut w = NpyDirWriter::create(&out, &layout()).unwrap();
    for i in 0..1000 {
        w.write_row(&row(i)).unwrap();
    }
    w.finish().unwrap();
    let expect = [
        ("t", vec![1000]),
        ("q", vec![1000, 2]),
        ("p", vec![1000, 2]),
        ("energy", vec![1000]),
        ("J", vec![1000, 1]),
        ("constraint_residual", vec![1000]),
    ];
    for (name, shape) in expect {
        let (dtype, s, _, values) = npyz_read(&out.join(format!("{name}.npy")));
        assert_eq!((dtype.as_str(), &s), ("<f8", &shape), "{name}.npy");
        assert_eq!(values.len() as u64, shape.iter().product::<u64>());
    }
    // q.npy row 7 is (q_x, q_y) of step 7, in C order.
    let (_, _, _, q) = npyz_read(&out.join("q.npy"));
    assert_eq!(&q[14..16], &row(7)[1..3]);

    // The directory reads back into the same table the CSV would hold.
    let table = read_npy_dir(&out, &layout()).unwrap();
    assert_eq!(table.names().collect::<Vec<_>>(), layout().column_names());
    for i in [0, 1, 999] {
        assert_eq!(table.row(i as usize).unwrap(), row(i).to_vec());
    }
}

#[test]
fn one_shot_table_write_matches_streaming() {
    let dir = tempfile::tempdir().unwrap();
    let names = layout()
        .column_names()
        .iter()
        .map(|s| s.to_string())
        .collect::<Vec<_>>();
    let columns = names
        .iter()
        .enumerate()
        .map(|(j, n)| Column::new(n.clone(), (0..300).map(|i| row(i)[j]).collect()))
        .collect();
    let table = Table::new(columns).unwrap();
    write_npy_dir(dir.path(), &layout(), &table).unwrap();
    assert_eq!(read_npy_dir(dir.path(), &layout()).unwrap(), table);
}

#[test]
fn a_run_that_stops_early_leaves_loadable_files() {
    let dir = tempfile::tempdir().unwrap();
    let mut w = NpyDirWriter::create(dir.path(), &layout()).unwrap();
    // Enough rows for several 64 KiB spills of q.npy, without finishing.
    for i in 0..20_000 {
        w.write_row(&row(i)).unwrap();
    }
    let (_, shape, _, values) = npyz_read(&dir.path().join("q.npy"));
    assert!(shape[0] > 0 && shape[0] < 20_000, "{shape:?}");
    assert_eq!(values.len() as u64, shape[0] * 2);
    // flush makes every file exact.
    RowSink::flush(&mut w).unwrap();
    assert_eq!(npyz_read(&dir.path().join("t.npy")).1, [20_000]);
    // finish early, then writes are refused.
    w.write_row(&row(20_000)).unwrap();
    w.finish().unwrap();
    assert_eq!(npyz_read(&dir.path().join("J.npy")).1, [20_001, 1]);
    assert!(matches!(w.write_row(&row(0)), Err(Error::Finished { .. })));
    // Dropping an unfinished writer finishes it too.
    let mut single = NpyWriter::create(dir.path().join("d.npy"), NpyShape::Vector).unwrap();
    single.write_row(&[1.0]).unwrap();
    drop(single);
    assert_eq!(npyz_read(&dir.path().join("d.npy")).3, [1.0]);
}

/// A run killed part-way (its writer never finished) leaves files that end at different rows:
/// the strict reader refuses them, the plots' reader draws the rows they all hold and says how
/// many were left out.
#[test]
fn a_killed_run_is_drawn_from_the_rows_every_file_holds() {
    let dir = tempfile::tempdir().unwrap();
    let mut w = NpyDirWriter::create(dir.path(), &layout()).unwrap();
    for i in 0..13_000 {
        w.write_row(&row(i)).unwrap();
    }
    std::mem::forget(w); // killed: no finish, no drop
    let t_rows = npyz_read(&dir.path().join("t.npy")).1[0];
    let q_rows = npyz_read(&dir.path().join("q.npy")).1[0];
    assert!(t_rows < q_rows, "t {t_rows}, q {q_rows}");
    assert!(matches!(
        read_npy_dir(dir.path(), &layout()),
        Err(Error::Npy { .. })
    ));
    let sketch = read_npy_dir_thinned(dir.path(), &layout(), &["energy"], 1000).unwrap();
    assert_eq!(sketch.rows_read, t_rows);
    let last = sketch.table.n_rows() - 1;
    assert_eq!(
        sketch.table.row(last).unwrap(),
        row(t_rows as u32 - 1).to_vec()
    );
    let note = sketch.note().unwrap();
    assert!(
        note.contains(&format!("{} left out", q_rows - t_rows)),
        "{note}"
    );
}

#[test]
fn errors_are_typed_and_name_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let mut w = NpyDirWriter::create(dir.path(), &layout()).unwrap();
    let e = w.write_row(&[1.0, 2.0]).unwrap_err();
    assert!(
        matches!(
            e,
            Error::RowLength {
                expected: 8,
                found: 2,
                ..
            }
        ),
        "{e}"
    );
    w.finish().unwrap();
    // Shape that does not fit the layout.
    let other = Layout::new(vec![Group::vector("q", ["a", "b", "c"])]).unwrap();
    let e = read_npy_dir(dir.path(), &other).unwrap_err();
    assert!(
        matches!(e, Error::Npy { .. }) && e.to_string().contains("q.npy"),
        "{e}"
    );
    // A table lacking one of the layout's columns.
    let partial = Table::new(vec![Column::new("t", vec![0.0])]).unwrap();
    let e = write_npy_dir(dir.path(), &layout(), &partial).unwrap_err();
    assert!(
        matches!(&e, Error::MissingColumn { name } if name == "q_x"),
        "{e}"
    );
    // Missing file.
    let e = read_npy(dir.path().join("nope.npy")).unwrap_err();
    assert!(
        matches!(e, Error::Io { .. }) && e.to_string().contains("nope.npy"),
        "{e}"
    );
    // Not an npy file.
    std::fs::write(dir.path().join("junk.npy"), b"hello").unwrap();
    let e = read_npy(dir.path().join("junk.npy")).unwrap_err();
    assert!(matches!(e, Error::Npy { .. }), "{e}");
    // Unwritable location.
    let blocker = dir.path().join("file");
    std::fs::write(&blocker, b"").unwrap();
    let e = NpyDirWriter::create(blocker.join("sub"), &layout()).unwrap_err();
    assert!(
        matches!(e, Error::Io { .. }) && e.to_string().contains("file/sub"),
        "{e}"
    );
}

/// numpy (if installed) loads the files with the expected shapes and bits. Skipped otherwise.
#[test]
fn numpy_loads_the_files_if_available() {
    let ok = std::process::Command::new("python3")
        .args(["-c", "import numpy"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !ok {
        eprintln!("skipped: python3 with numpy not available");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let mut w = NpyDirWriter::create(dir.path(), &layout()).unwrap();
    for i in 0..10_000 {
        w.write_row(&row(i)).unwrap();
    }
    w.finish().unwrap();
    let script = "import sys, numpy as np\n\
        d = sys.argv[1]\n\
        for n in ['t', 'q', 'p', 'energy', 'J', 'constraint_residual']:\n\
        \x20   a = np.load(d + '/' + n + '.npy')\n\
        \x20   print(n, a.dtype.str, a.shape, a.flags['C_CONTIGUOUS'])\n\
        print(np.load(d + '/q.npy')[7].tolist() == [np.cos(0.07), np.sin(0.07)])";
    let out = std::process::Command::new("python3")
        .args(["-c", script, dir.path().to_str().unwrap()])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    assert_eq!(
        text,
        "t <f8 (10000,) True\nq <f8 (10000, 2) True\np <f8 (10000, 2) True\n\
         energy <f8 (10000,) True\nJ <f8 (10000, 1) True\nconstraint_residual <f8 (10000,) True\nTrue\n"
    );
}
