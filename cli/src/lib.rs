//! What the workspace's binaries (`generator`, `model`, `evaluator`) share at their edges, so
//! each `main` only parses its arguments and calls its library:
//!
//! - [`run`]: logging set up, the command run, and an error printed as one line on stderr
//!   (`error: ` and the chain of contexts and causes) with exit status 1.
//! - Logging goes to stderr at `info` unless `RUST_LOG` says otherwise (`RUST_LOG=warn`,
//!   `RUST_LOG=model=debug`, ...), so warnings, a texture an asset names that cannot be
//!   read say, are shown by default.
//! - The allocator: jemalloc keeps freed large blocks for reuse instead of returning them to
//!   the kernel (glibc's malloc unmaps every block over 32 MB, and the network's pair tensors
//!   are 16-67 MB: half of a training step went to page faults). A library's
//!   `#[global_allocator]` applies to every binary that links it.

use std::io::IsTerminal;
use std::process::ExitCode;

#[cfg(not(target_env = "msvc"))]
#[global_allocator]
static ALLOCATOR: tikv_jemallocator::Jemalloc = tikv_jemallocator::Jemalloc;

/// Sets up logging, runs `command` and turns its outcome into the process's exit status,
/// printing an error as `error: <context>: <cause>: ...` on stderr.
pub fn run(command: impl FnOnce() -> anyhow::Result<()>) -> ExitCode {
    init_logging();
    match command() {
        Ok(()) => ExitCode::SUCCESS,
        Err(err) => {
            eprintln!("error: {}", message(&err));
            ExitCode::FAILURE
        }
    }
}

/// Logging to stderr, at `info` unless `RUST_LOG` sets the filter, coloured only on a
/// terminal. Calling it twice is
/// harmless (the second call keeps the first subscriber).
pub fn init_logging() {
    let filter = tracing_subscriber::EnvFilter::try_from_default_env()
        .unwrap_or_else(|_| tracing_subscriber::EnvFilter::new("info"));
    let _ = tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_target(false)
        .with_ansi(std::io::stderr().is_terminal())
        .with_writer(std::io::stderr)
        .try_init();
}

/// An error's chain of contexts and causes on one line, joined by `: `, leaving out a cause
/// whose text its parent's message already holds (the libraries' errors quote their sources).
pub fn message(err: &anyhow::Error) -> String {
    let mut parts: Vec<String> = Vec::new();
    for cause in err.chain() {
        let text = cause.to_string();
        if !parts.last().is_some_and(|last| last.contains(&text)) {
            parts.push(text);
        }
    }
    parts.join(": ")
}

#[cfg(test)]
mod tests {
    use super::message;
    use anyhow::Context;

    #[test]
    fn the_chain_is_one_line_without_repeats() {
        let io = std::io::Error::new(std::io::ErrorKind::NotFound, "no such file");
        // A library error that quotes its source, as the workspace's thiserror types do.
        let quoting = anyhow::Error::new(io).context("weights/model.bpk: no such file");
        let err = Err::<(), _>(quoting).context("loading the weights folder weights").unwrap_err();
        assert_eq!(
            message(&err),
            "loading the weights folder weights: weights/model.bpk: no such file"
        );
        let plain = Err::<(), _>(anyhow::anyhow!("bad value")).context("--pairs").unwrap_err();
        assert_eq!(message(&plain), "--pairs: bad value");
    }
}
