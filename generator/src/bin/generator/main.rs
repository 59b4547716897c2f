//! `generator`: writes a dataset of articulated shape pairs with complete ground truth. The
//! arguments and their handling live in the library's [`generator::commands`].

use clap::Parser;
use generator::commands::{run, Args};

fn main() -> std::process::ExitCode {
    cli::run(|| run(Args::parse()))
}
