//! The `marsden` command: a thin front end over [`marsden_spec`] (problem files, runs, sweeps,
//! order studies, texts) — it parses the command line, prints, draws the progress bar and
//! chooses the exit status.
//!
//! | stage | module | what |
//! |---|---|---|
//! | command line | [`cli`] | clap: `run`, `check`, `order`, `systems`, `plot`; what each prints |
//! | progress | [`progress`] | the indicatif bar on stderr, fed by the run's progress callback |
//! | exit | [`error`] | [`error::Status`] (0 completed, 1 failed, 2 bad input) |
//!
//! The problem-file schema and the outputs (`trajectory.csv` columns, `summary.json` fields,
//! exit statuses) are a contract: extend, don't rename.

pub mod cli;
pub mod error;
pub mod progress;
