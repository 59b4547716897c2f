//! `evaluator`: every method on every dataset, scored into the leaderboards under `reports/`.
//! The arguments and their handling live in the library's [`evaluator::commands::entry`].

use clap::Parser;
use evaluator::commands::entry::{run, Args};

fn main() -> std::process::ExitCode {
    cli::run(|| run(Args::parse()))
}
