//! The `marsden` binary; everything lives in the library ([`marsden_cli::cli`]).

use std::process::ExitCode;

fn main() -> ExitCode {
    catch_file_size_limit();
    marsden_cli::cli::main_with(std::env::args_os())
}

/// Under a file-size limit (`ulimit -f`) the kernel sends SIGXFSZ to a process whose write
/// exceeds it, which by default ends the process with no message and no summary. Caught, the
/// write fails with EFBIG instead, and the run reports it as a failed write (its summary says
/// so), as it does for a full disk.
fn catch_file_size_limit() {
    #[cfg(unix)]
    {
        use std::sync::Arc;
        use std::sync::atomic::AtomicBool;
        let reached = Arc::new(AtomicBool::new(false));
        // Without the handler the default action stays: the process ends as before.
        let _ = signal_hook::flag::register(signal_hook::consts::SIGXFSZ, reached);
    }
}
