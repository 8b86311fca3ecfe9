//! Problem files as a library: mechanical systems described in TOML — Lagrangians, forces,
//! constraints and symmetries written as formulas — checked, run with the variational
//! integrators of the [`marsden`] crate, and summed up. The `marsden` command and the Python
//! package are thin front ends over the same entry points:
//!
//! ```no_run
//! use marsden_spec::{Controls, Overrides, Store};
//!
//! let spec = marsden_spec::load("examples/pendulum.toml".as_ref(), &Overrides::default())?;
//! let outcome = marsden_spec::execute(&spec, Store::Memory, &Controls::none())?;
//! let samples = outcome.samples.unwrap_or_default();
//! println!("{} samples, max |ΔE/E0| = {}", samples.len(), outcome.summary.energy.max_rel_error);
//! # Ok::<(), marsden_spec::Error>(())
//! ```
//!
//! Nothing here prints or exits; errors are values ([`Error`], its [`Diagnostic`] rendered with
//! the file's line and a caret).
//!
//! # Three crates behind one surface
//!
//! ```text
//! marsden-problem   TOML ──raw (serde, spans)──▶ RunSpec (its system a typed Lagrangian)
//! marsden-engine    Engine: prepare · run · initial_tangent · order_study, generic over L
//! marsden-engine-catalog   the engine compiled for the catalog's systems
//! marsden-spec      factory: RunSpec ──engine_for──▶ Box<dyn Engine> (the expression systems
//!                   compiled here); execute, sweeps, summary.json, plots, report texts
//! ```
//!
//! The language ([`problem`], [`model`], [`catalog`], [`error`], [`source`]) is re-exported
//! from `marsden-problem`. The rest of the crate is private: the front ends (the command, the
//! Python package), the crate's tests and benches use the list of names below, grouped by what
//! they are for. Types every front end passes around are named at the root; functions that
//! read best with their concern in front (`sweep::execute`, `resume::find`) are in small
//! namespaces holding only what is used from outside.
//!
//! | stage | names | what |
//! |---|---|---|
//! | file → spec | [`problem`] | every check → [`RunSpec`] (and [`SweepSpec`]); [`load`], [`from_toml_str`] |
//! | the seam | [`engine_for`], [`prepare`] | the [`marsden_engine::Engine`] of a file's system; the checked initial [`Start`] |
//! | run | [`execute`](fn@execute), [`Prepared`] | with [`Controls`] → [`Outcome`]: files, [`Samples`] in memory, [`Summary`] |
//! | sweeps | [`sweep`] | members in parallel, one row each, `--shard` ([`sweep::Shard`]) |
//! | long runs | [`resume`], [`checkpoint`] | a run or a sweep continued from its checkpoint |
//! | stepping | [`segment`] | a run continued from a state `(t, q, p)` (Python's `Simulation`) |
//! | derivatives | [`sensitivity`] | `[sensitivity]`: the tangent run's Jacobians |
//! | files | [`output`], [`plots`] | the names of the files; the plots drawn again (`marsden plot`) |
//! | order study | [`order`] | methods × step sizes, errors against a reference, fitted orders |
//! | texts | [`report`] | what `run`, `check` and `systems` print |
//!
//! The problem-file schema and the outputs (`trajectory.csv` columns, `summary.json` fields)
//! are a contract: extend, don't rename.

mod factory;
mod order_study;
mod run;
mod texts;

// The language: problem files, their systems and diagnostics (`marsden-problem`).
pub use marsden_problem::{
    Diagnostic, Error, ErrorKind, Overrides, RunSpec, SweepSpec, catalog, error, from_toml_str,
    load, model, problem, source,
};

// Running: the engine of a file, its checked start, a whole run and what it gives.
pub use factory::{engine_for, prepare};
pub use run::event_outputs::EventSamples;
pub use run::sampled_times::SampledStates;
pub use run::start::Start;
pub use run::{
    CHECK_EVERY, Controls, Outcome, Prepared, Progress, RunStatus, Samples, Store, Summary, execute,
};

/// Sweeps: every member of a `[sweep]`, in parallel, one row each (`--shard`: a part of them).
pub mod sweep {
    pub use crate::run::shard::Shard;
    pub use crate::run::sweep::{
        NOT_RUN, SweepOptions, SweepOutcome, execute, member_outcome, member_outcomes, run_members,
    };
}

/// Resume and checkpoints: a run (or a sweep) continued from the checkpoint in its directory.
pub mod resume {
    pub use crate::run::resume::{Found, find, resume_from, resume_sweep};
    pub use crate::run::sweep_checkpoint::SweepCheckpoint;
}

/// Resume and checkpoints: the checkpoint files, read without resuming (`marsden resume`
/// reports the tangent run's step).
pub mod checkpoint {
    pub use marsden_engine::checkpoint::{file, tangent};
}

/// Running: a run continued from a state `(t, q, p)` for some steps or to a time.
pub mod segment {
    pub use crate::run::segment::{StretchEnd, StretchStart, continued, steppable};
}

/// Running: `[sensitivity]`, the tangent run's Jacobians and their description.
pub mod sensitivity {
    pub use crate::run::sensitivity::{compute_streamed, compute_with, describe};
}

/// Outputs: the names of a run's files and the lock on its directory.
pub mod output {
    pub use crate::run::output::{SUMMARY_JSON, TRAJECTORY_CSV, lock, lock_named};
}

/// Plots: the PNG plots of a finished run drawn again from its files (`marsden plot`).
pub mod plots {
    pub use crate::run::plots::redraw;
}

/// Reports: the texts the command prints, so that every front end shows the same words.
pub mod report {
    /// The resolved problem (`marsden check`).
    pub mod check {
        pub use crate::texts::check::render;
    }
    /// The summary of a run (`marsden run`).
    pub mod run {
        pub use crate::texts::run::render;
    }
    /// The catalog (`marsden systems`).
    pub mod systems {
        pub use crate::texts::systems::{describe, render};
    }
    /// The summary table of a sweep.
    pub mod sweep_table {
        pub use crate::run::sweep_table::render;
    }
}

/// Order studies: methods × step sizes, errors against a reference, fitted orders
/// (`marsden order`).
pub mod order {
    pub use crate::order_study::{Request, measure, plan, table};
}
