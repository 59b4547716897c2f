//! `model average`: the parameter-wise mean of several weights folders ("model soup").

use std::path::PathBuf;

use anyhow::{Context, Result};
use burn::prelude::*;

use crate::train::average::average_weights;
use crate::weights;

/// Average several weights folders of one network parameter by parameter (a "model soup":
/// checkpoints fine-tuned from the same weights), into a new weights folder.
#[derive(clap::Args, Debug)]
pub struct AverageArgs {
    /// The weights folders (config.toml and model.bpk, or checkpoint folders), averaged in
    /// this order; all of the first one's network sizes.
    #[arg(long, num_args = 1.., required = true)]
    pub weights: Vec<PathBuf>,
    /// The weights folder to write (the first folder's config and the mean parameters; each
    /// file replaced whole or not at all).
    #[arg(long)]
    pub out: PathBuf,
}

/// Runs `model average`.
pub fn run(args: AverageArgs) -> Result<()> {
    let (net, config) =
        average_weights(&args.weights, &Device::flex()).context("averaging the weights")?;
    weights::save(&args.out, &net, &config)
        .with_context(|| format!("writing the weights folder {}", args.out.display()))?;
    println!("wrote the mean of {} weights folders to {}", args.weights.len(), args.out.display());
    Ok(())
}
