//! The command line: `marsden run | resume | check | optimize | order | systems | plot`, parsed with clap's derive API.
//!
//! Exit statuses (a contract): 0 completed, 1 the simulation failed (partial trajectory and
//! summary still written, status "failed"), 2 bad problem file or usage (nothing run).

mod check;
mod optimize;
mod order;
mod plot;
mod resume;
mod run;
mod systems;

use std::ffi::OsString;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};

use marsden_spec::Overrides;
use marsden_spec::sweep::Shard;

use crate::error::{CliError, Status};

/// Discrete mechanics and variational integrators from TOML problem files.
#[derive(Debug, Parser)]
#[command(name = "marsden", version, about, long_about = None)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Run a problem file: trajectory, summary.json and plots in the output directory.
    Run(RunArgs),
    /// Continue a run from the last checkpoint in its output directory (`checkpoint_every`):
    /// the files it leaves are those of the uninterrupted run.
    Resume(ResumeArgs),
    /// Validate a problem file and print the resolved problem (nothing is run or written).
    Check(FileArgs),
    /// Solve the file's [optimal_control] problem (DMOC): trajectory, controls, summary, plots.
    Optimize(OptimizeArgs),
    /// Empirical order of convergence: run methods at several step sizes, fit the log–log slope.
    Order(OrderArgs),
    /// List the catalog systems (`builtin = "..."`) with coordinates, parameters, defaults.
    Systems {
        /// Show only this system.
        name: Option<String>,
    },
    /// Draw the plots of a finished run again (from trajectory.csv, or the .npy files).
    Plot {
        /// The run's output directory.
        dir: PathBuf,
    },
}

/// A problem file and the overrides of its values.
#[derive(Debug, Args)]
pub struct FileArgs {
    /// The problem file (TOML).
    pub file: PathBuf,
    /// Number of steps (replaces `steps` and `t_end` of the integrator table).
    #[arg(long)]
    pub steps: Option<u64>,
    /// Time step (replaces `h`; with `t_end`, the number of steps follows).
    #[arg(long, allow_negative_numbers = true)]
    pub h: Option<f64>,
    /// Output directory (replaces `dir` of the output table).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Save a checkpoint every N steps (replaces `checkpoint_every` of the output table);
    /// `marsden resume DIR` continues the run from the last one.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    pub checkpoint_every: Option<u64>,
}

impl FileArgs {
    /// The overrides given.
    pub fn overrides(&self) -> Overrides {
        Overrides {
            steps: self.steps,
            h: self.h,
            out: self.out.clone(),
            checkpoint_every: self.checkpoint_every,
            every: None,
        }
    }
}

/// `marsden run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// The problem file and overrides.
    #[command(flatten)]
    pub file: FileArgs,
    /// Print nothing on stdout (errors still go to stderr).
    #[arg(short, long)]
    pub quiet: bool,
    /// Never show the progress bar.
    #[arg(long)]
    pub no_progress: bool,
    /// With `[sweep]`: run only the members `k` with `k % n == i` (for array jobs; rows keep
    /// their global member index; files `sweep.shard-i-of-n.csv`).
    #[arg(long, value_name = "I/N")]
    pub shard: Option<Shard>,
    /// With `[sweep]`: number of worker threads (default: one per core).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..))]
    pub threads: Option<u16>,
}

/// `marsden resume`.
#[derive(Debug, Args)]
pub struct ResumeArgs {
    /// The run's output directory (holding `checkpoint.bin`, or a sweep's
    /// `sweep-checkpoint.bin`).
    pub dir: PathBuf,
    /// Print nothing on stdout (errors still go to stderr).
    #[arg(short, long)]
    pub quiet: bool,
    /// Never show the progress bar.
    #[arg(long)]
    pub no_progress: bool,
    /// A sweep: the shard to resume, when several shards ran into `DIR`.
    #[arg(long, value_name = "I/N")]
    pub shard: Option<Shard>,
    /// A sweep: number of worker threads (default: one per core).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..))]
    pub threads: Option<u16>,
}

/// `marsden optimize`.
#[derive(Debug, Args)]
pub struct OptimizeArgs {
    /// The problem file (TOML) with [optimal_control].
    pub file: PathBuf,
    /// Number of steps N (replaces `steps` of [optimal_control]).
    #[arg(long)]
    pub steps: Option<u64>,
    /// Output directory (replaces `dir` of the output table).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Print nothing on stdout (errors still go to stderr).
    #[arg(short, long)]
    pub quiet: bool,
}

/// `marsden order`.
#[derive(Debug, Args)]
pub struct OrderArgs {
    /// The problem file (TOML).
    pub file: PathBuf,
    /// Methods to compare, comma-separated (default: the file's method).
    #[arg(long, value_name = "M1,M2,...")]
    pub methods: Option<String>,
    /// Step sizes, comma-separated; each must divide T − t0 (default: the file's h × 1, 1/2,
    /// 1/4, 1/8).
    #[arg(long, value_name = "H1,H2,...", allow_hyphen_values = true)]
    pub h: Option<String>,
    /// Final time T (default: the file's t_end = t0 + h·steps).
    #[arg(long, allow_negative_numbers = true)]
    pub t_end: Option<f64>,
    /// Also write the errors as CSV to this file.
    #[arg(long)]
    pub csv: Option<PathBuf>,
}

/// Parses `args` (the first is the program name) and runs the command; the process's exit
/// code follows [`Status`].
pub fn main_with<I, T>(args: I) -> ExitCode
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    let cli = match Cli::try_parse_from(args) {
        Ok(cli) => cli,
        Err(e) => {
            let _ = e.print();
            return ExitCode::from(u8::try_from(e.exit_code()).unwrap_or(Status::BadInput.code()));
        }
    };
    match dispatch(cli.command) {
        Ok(status) => status.into(),
        Err(e) => {
            eprintln!("{e}");
            e.status.into()
        }
    }
}

fn dispatch(command: Command) -> Result<Status, CliError> {
    match command {
        Command::Run(args) => run::run(&args),
        Command::Resume(args) => resume::resume(&args),
        Command::Check(args) => check::check(&args),
        Command::Optimize(args) => optimize::optimize(&args),
        Command::Order(args) => order::order(&args),
        Command::Systems { name } => systems::systems(name.as_deref()),
        Command::Plot { dir } => plot::plot(&dir),
    }
}
