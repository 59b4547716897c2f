//! `model procedures`: the iterative procedure's variants ([`crate::procedures`]) scored
//! side by side on the same pairs, printed and written as CSV.

use std::path::PathBuf;

use anyhow::{Context, Result};

use crate::commands::shared::{load_weights, read_dataset, spinner, write_table};
use crate::procedures::{self, release_variants, score_procedure, Variant};
use crate::train::validation::{validation_pairs, Difference};

/// Score the iterative procedure's variants side by side on the same pairs: the paper's
/// (the `net-iter` row), the authors' release's two global alignments, per-segment
/// sub-problems and full-Q matching each alone, and all three; each with its
/// paired-bootstrap 95% interval against the paper's, on all pairs and per kind. Prints the
/// table and writes it as CSV.
#[derive(clap::Args, Debug)]
pub struct ProceduresArgs {
    /// Weights folder (config.toml and model.bpk).
    #[arg(long, default_value = "model/weights/cpu")]
    pub weights: PathBuf,
    /// A dataset folder (datasets/<name>) to score on, repeatable [default: the validation
    /// pairs of the weights' config, a quarter of them SF2P and a quarter SP2P when the
    /// config trains on scans].
    #[arg(long)]
    pub dataset: Vec<PathBuf>,
    /// Validation pairs, or the first N of each dataset [default: 240; every pair of a
    /// dataset].
    #[arg(long)]
    pub pairs: Option<u32>,
    /// Only these variants (comma-separated: paper, +align, +sub, +full, release); the first
    /// is the one the others are compared with.
    #[arg(long, value_delimiter = ',')]
    pub variants: Vec<String>,
    /// Bootstrap resamples.
    #[arg(long, default_value_t = 2000)]
    pub resamples: usize,
    /// Where to write the table as CSV (replaced whole).
    #[arg(long, default_value = "procedures.csv")]
    pub out: PathBuf,
}

/// Runs `model procedures`.
pub fn run(args: ProceduresArgs) -> Result<()> {
    let all = release_variants();
    let variants: Vec<Variant> = if args.variants.is_empty() {
        all
    } else {
        args.variants
            .iter()
            .map(|n| {
                all.iter().find(|v| v.name == n).cloned().with_context(|| {
                    let known: Vec<&str> = all.iter().map(|v| v.name).collect();
                    format!("--variants: no variant {n:?} (known: {})", known.join(", "))
                })
            })
            .collect::<Result<_>>()?
    };
    let weights = load_weights(&args.weights, "--weights")?;
    let config = &weights.config;
    let pairs = if args.dataset.is_empty() {
        validation_pairs(config.points, args.pairs.unwrap_or(240), config.scanned_per_pair > 0)
            .context("generating the validation pairs")?
    } else {
        let mut pairs = Vec::new();
        for dir in &args.dataset {
            pairs.extend(read_dataset(dir, args.pairs)?);
        }
        pairs
    };
    let mut scored = Vec::new();
    for variant in &variants {
        let spinner = spinner(format!("{} on {} pairs", variant.name, pairs.len()));
        let s = score_procedure(&weights.net, &pairs, variant)
            .with_context(|| format!("running the {} procedure", variant.name))?;
        spinner.finish_and_clear();
        tracing::info!("{}: {:.1} s", variant.name, s.seconds);
        scored.push(s);
    }
    let lines = procedures::table(&pairs, &scored, args.resamples, 20_181_201)
        .context("comparing the variants")?;
    println!("{} pairs, weights {}", pairs.len(), args.weights.display());
    println!(
        "{:<8} {:<5} {:>5} {:>7} {:>7} {:>7} {:>6}  {:<26} {:<26}",
        "variant", "group", "pairs", "EPE", "RI", "IoU", "passes", "ΔEPE [95%]", "ΔIoU [95%]"
    );
    let d = |x: Option<Difference>| {
        x.map_or(String::new(), |d| format!("{:+.4} [{:+.4},{:+.4}]", d.value, d.low, d.high))
    };
    for l in &lines {
        println!(
            "{:<8} {:<5} {:>5} {:>7.4} {:>7.4} {:>7.4} {:>6.2}  {:<26} {:<26}",
            l.variant,
            l.group,
            l.pairs,
            l.scores.epe,
            l.scores.rand_index,
            l.scores.iou,
            l.passes,
            d(l.against_first.map(|c| c.epe)),
            d(l.against_first.map(|c| c.iou)),
        );
    }
    let seconds: Vec<String> =
        scored.iter().map(|s| format!("{} {:.1} s", s.name, s.seconds)).collect();
    println!("time: {}", seconds.join(", "));
    write_table(&args.out, &procedures::to_csv(&lines))?;
    println!("written to {}", args.out.display());
    Ok(())
}
