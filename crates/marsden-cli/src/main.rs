//! The `marsden` binary; everything lives in the library ([`marsden_cli::cli`]).

use std::process::ExitCode;

fn main() -> ExitCode {
    marsden_cli::cli::main_with(std::env::args_os())
}
