//! The cost of one checkpoint of `marsden run` (`[output] checkpoint_every`): encoding the
//! run's carried state and writing it atomically (a temporary file, `fsync`, a rename), as a
//! run does every `checkpoint_every` steps. The checkpoints are those of real runs: the
//! pendulum (one coordinate), and the Hénon–Heiles section with its 2000-odd event records
//! (a checkpoint carries every record located so far, so it grows with them).
//!
//! `cargo bench -p marsden-spec --bench checkpoint`; the bytes per checkpoint are divan's
//! throughput column.

use std::path::Path;

use divan::counter::BytesCount;
use divan::{Bencher, black_box};
use marsden_engine::checkpoint::{CHECKPOINT_FILE, RunCheckpoint, file};
use marsden_spec::{Controls, Overrides, Store};

fn main() {
    divan::main();
}

/// Runs `example` (from `examples/`, `steps` steps) with checkpoints into a temporary
/// directory and returns its last checkpoint.
fn checkpoint_of(example: &str, steps: u64, every: u64) -> RunCheckpoint {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
    let overrides = Overrides {
        steps: Some(steps),
        out: Some(dir.path().to_path_buf()),
        checkpoint_every: Some(every),
        ..Overrides::default()
    };
    let spec =
        marsden_spec::load(&root.join(example), &overrides).unwrap_or_else(|e| panic!("{e}"));
    let mut spec = spec;
    spec.output.plots = false;
    marsden_spec::execute(&spec, Store::Files, &Controls::none()).unwrap_or_else(|e| panic!("{e}"));
    RunCheckpoint::load(&dir.path().join(CHECKPOINT_FILE)).unwrap_or_else(|e| panic!("{e}"))
}

fn bench_save(b: Bencher, checkpoint: &RunCheckpoint) {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
    let path = dir.path().join(CHECKPOINT_FILE);
    let bytes = file::encode(checkpoint).map_or(0, |b| b.len());
    b.counter(BytesCount::new(bytes))
        .bench(|| file::save(black_box(&path), black_box(checkpoint)));
}

/// The pendulum (midpoint, 20 000 steps, checkpointed every 5 000).
#[divan::bench(sample_count = 30)]
fn pendulum(b: Bencher) {
    bench_save(b, &checkpoint_of("pendulum.toml", 20_000, 5_000));
}

/// The Hénon–Heiles section (trapezoid, the example's 260 000 steps and 2011 crossings,
/// checkpointed every 100 000: the last checkpoint carries the records up to step 200 000).
#[divan::bench(sample_count = 30)]
fn henon_heiles_section(b: Bencher) {
    bench_save(
        b,
        &checkpoint_of("henon_heiles_section.toml", 260_000, 100_000),
    );
}
