//! `model diagnose`: the network's error decomposed by oracle substitution
//! ([`crate::diagnose`]), printed and written as CSV.

use std::path::PathBuf;

use anyhow::{Context, Result};

use crate::commands::shared::{load_weights, pairs_bar, read_dataset, write_table};
use crate::diagnose::{diagnose, DiagnoseParams};
use crate::train::validation::validation_pairs;

/// Decompose the network's error by oracle substitution, without training: the flow
/// module against the matching alone and the true flow at subset sizes; on the true flow,
/// the support module against a residual threshold rule (on the network's hypotheses, a
/// rigid and a similarity fit per true part) and the true same-part matrix, each through
/// the RPEN; the subset ceiling; the pairs' motion scales. Prints the table and writes it
/// as CSV.
#[derive(clap::Args, Debug)]
pub struct DiagnoseArgs {
    /// Weights folder: config.toml and model.bpk (e.g. model/weights/cpu), a checkpoint
    /// folder of `model train`, or its best/.
    #[arg(long)]
    pub weights: PathBuf,
    /// A dataset folder (datasets/<name>) to diagnose instead of the validation pairs.
    #[arg(long)]
    pub dataset: Option<PathBuf>,
    /// Pairs to diagnose: the first N validation pairs, or of the dataset [default: the
    /// config's `validation_pairs`; every pair of a dataset].
    #[arg(long)]
    pub pairs: Option<u32>,
    /// Where to write the table as CSV (replaced whole).
    #[arg(long, default_value = "diagnose.csv")]
    pub out: PathBuf,
}

/// Runs `model diagnose`.
pub fn run(args: DiagnoseArgs) -> Result<()> {
    let weights = load_weights(&args.weights, "--weights")?;
    let config = &weights.config;
    let pairs = match &args.dataset {
        None => {
            let count = args.pairs.unwrap_or(config.validation_pairs);
            validation_pairs(config.points, count, config.scanned_per_pair > 0)
                .context("generating the validation pairs")?
        }
        Some(dir) => read_dataset(dir, args.pairs)?,
    };
    let bar = pairs_bar(pairs.len() as u64);
    let diagnosis = diagnose(&weights.net, &pairs, &DiagnoseParams::default(), |done| {
        bar.set_position(done as u64)
    })
    .context("diagnosing")?;
    bar.finish_and_clear();
    println!("{} pairs, weights {}", diagnosis.pairs, args.weights.display());
    println!("{:<72} {:>11} {:>7} {:>7}", "row", "support IoU", "IoU", "EPE");
    let cell = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.4}"));
    for r in &diagnosis.rows {
        println!(
            "{:<72} {:>11} {:>7} {:>7}",
            r.name,
            cell(r.support_iou),
            cell(r.iou),
            cell(r.epe)
        );
    }
    let s = diagnosis.scale;
    println!(
        "per-pair motion scale |s - 1|: median {:.4}, 90th percentile {:.4}, max {:.4}",
        s.median, s.p90, s.max
    );
    write_table(&args.out, &diagnosis.to_csv())?;
    println!("wrote {}", args.out.display());
    Ok(())
}
