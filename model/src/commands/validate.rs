//! `model validate`: score a weights folder on the validation pairs, or two folders on the
//! same pairs with the paired-bootstrap interval of each score's difference.

use std::path::PathBuf;

use anyhow::{Context, Result};

use crate::commands::shared::{load_weights, pairs_bar};
use crate::network::PartInductionNet;
use crate::train::validation::{
    compare, score_pairs_aligned, validation_pairs, PairScores, Scores, VALIDATION_SEED,
};

/// Score weights on the validation set of their config (EPE, Rand index, IoU, support IoU).
#[derive(clap::Args, Debug)]
pub struct ValidateArgs {
    /// Weights folder: config.toml and model.bpk (e.g. model/weights/cpu), a checkpoint
    /// folder of `model train`, or its best/.
    #[arg(long)]
    pub weights: PathBuf,
    /// Validation pairs to score [default: the config's `validation_pairs`]; a larger set
    /// holds every pair of a smaller one.
    #[arg(long)]
    pub pairs: Option<u32>,
    /// A second weights folder (the shipped weights, say): score it on the same pairs (those
    /// of `--weights`' config) and print each score's difference (`--weights` minus this
    /// one) with a 95% paired-bootstrap interval over the pairs.
    #[arg(long)]
    pub against: Option<PathBuf>,
    /// Bootstrap resamples for `--against`.
    #[arg(long, default_value_t = 2000)]
    pub resamples: usize,
    /// Global alignments of P before the `--weights` pass (the authors' release: 2), for
    /// weights trained without relative pose (`relative_pose = false`).
    #[arg(long, default_value_t = 0)]
    pub global_alignments: usize,
    /// Global alignments before the `--against` pass.
    #[arg(long, default_value_t = 0, requires = "against")]
    pub against_global_alignments: usize,
}

/// Runs `model validate`.
pub fn run(args: ValidateArgs) -> Result<()> {
    let first = load_weights(&args.weights, "--weights")?;
    let config = &first.config;
    let count = args.pairs.unwrap_or(config.validation_pairs);
    if count == 0 {
        anyhow::bail!("--pairs must be at least 1");
    }
    let other = args.against.as_deref().map(|d| load_weights(d, "--against")).transpose()?;
    let pairs = validation_pairs(config.points, count, config.scanned_per_pair > 0)
        .context("generating the validation pairs")?;
    let bar = pairs_bar(pairs.len() as u64 * (1 + u64::from(other.is_some())));
    let scored = |net: &PartInductionNet, alignments| -> Result<Vec<PairScores>> {
        let mut all = Vec::with_capacity(pairs.len());
        for chunk in pairs.chunks(8) {
            all.extend(score_pairs_aligned(net, chunk, alignments)?);
            bar.inc(chunk.len() as u64);
        }
        Ok(all)
    };
    let a = scored(&first.net, args.global_alignments)
        .with_context(|| format!("scoring {}", args.weights.display()))?;
    let b = match (&other, &args.against) {
        (Some(w), Some(path)) => Some(
            scored(&w.net, args.against_global_alignments)
                .with_context(|| format!("scoring {}", path.display()))?,
        ),
        _ => None,
    };
    bar.finish_and_clear();
    let line = |name: &std::path::Path, s: Scores| {
        println!(
            "{}: {} validation pairs: EPE {:.4}, RI {:.4}, IoU {:.4}, support IoU on the true flow {:.4}",
            name.display(),
            pairs.len(),
            s.epe,
            s.rand_index,
            s.iou,
            s.support_iou
        )
    };
    line(&args.weights, Scores::of(&a));
    if let (Some(b), Some(path)) = (b, &args.against) {
        line(path, Scores::of(&b));
        let c = compare(&a, &b, args.resamples, VALIDATION_SEED).context("comparing")?;
        println!(
            "difference (first minus second), 95% paired-bootstrap interval over {} resamples:",
            args.resamples
        );
        for (name, d) in
            [("EPE", c.epe), ("RI", c.rand_index), ("IoU", c.iou), ("support IoU", c.support_iou)]
        {
            println!("  {name:<12} {:+.4}  [{:+.4}, {:+.4}]", d.value, d.low, d.high);
        }
    }
    Ok(())
}
