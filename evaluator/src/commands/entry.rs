//! The `evaluator` binary's arguments and what each asks for: the whole evaluation
//! ([`crate::commands::pipeline`]), `--list`, and the `score` and `predict` subcommands
//! ([`crate::commands::files`]). `src/main.rs` parses [`Args`] and calls [`run`]; like a
//! binary's, these return [`anyhow::Result`] with context naming the file and the flag.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result};
use clap::Parser;

use crate::commands::bars::Bars;
use crate::commands::files::{
    add_remembered_rows, score_predictions, write_predictions, CommandOptions, PredictRequest,
};
use crate::commands::pipeline::{evaluate, Options};
use crate::datasets::{
    dataset_specs, default_datasets, parse_user_dataset, remember_datasets, validation_datasets,
    DatasetSpec,
};
use crate::rows::standard::{standard_registry, DEFAULT_WEIGHTS};

#[derive(Parser, Debug)]
#[command(
    name = "evaluator",
    version,
    about = "Score every part-induction method on every dataset into reports/",
    after_help = "Examples:
  evaluator --all                                   everything (generates missing datasets)
  evaluator --methods gt,net --limit 50             two rows on the first 50 pairs
  evaluator --methods seqransac@net-flow --force    recompute one row
  evaluator --dataset lamps=datasets/lamps --methods net,seqransac@net-flow   a user's dataset
  evaluator --methods net-iter --limit 50           Table 4 (iterations.csv) on 50 pairs
  evaluator --list                                  the registered rows and datasets
  evaluator score --dataset sf2f --predictions mine.mcap --name mine   a method run elsewhere
  evaluator score --dataset renders/paris --predictions joints.json   joints on a render
  evaluator predict --method net --dataset sf2f --out net.mcap          a row's predictions",
    long_about = None,
    args_conflicts_with_subcommands = true
)]
/// The evaluator's arguments.
pub struct Args {
    #[command(subcommand)]
    command: Option<Command>,
    /// Every registered method on every default dataset.
    #[arg(long)]
    all: bool,
    /// Only these rows (comma-separated names, see --list).
    #[arg(long, value_delimiter = ',')]
    methods: Vec<String>,
    /// Only these datasets (comma-separated names, see --list).
    #[arg(long, value_delimiter = ',')]
    datasets: Vec<String>,
    /// Also score the dataset folder PATH (any folder the generator wrote, from --assets
    /// too) under the name NAME; repeatable. Without --all or --datasets only these are run.
    /// Its rows stay in the boards on later runs (remembered in <reports>/user_datasets.json).
    #[arg(long = "dataset", value_name = "NAME=PATH", value_parser = parse_user_dataset)]
    user_datasets: Vec<DatasetSpec>,
    /// Only the first N pairs of each dataset (reports go to <reports>/limit-N/).
    #[arg(long, value_name = "N")]
    limit: Option<usize>,
    /// Recompute runs even when reports/runs holds a matching one.
    #[arg(long)]
    force: bool,
    /// Folder of the datasets (each in <root>/<name>).
    #[arg(long, default_value = "datasets")]
    datasets_root: PathBuf,
    /// Folder of the reports.
    #[arg(long, default_value = "reports")]
    reports: PathBuf,
    /// The network's weights folder (config.toml and model.bpk).
    #[arg(long, default_value = DEFAULT_WEIGHTS)]
    weights: PathBuf,
    /// Pairs per dataset in the segmentation gallery.
    #[arg(long, default_value_t = 3)]
    gallery_pairs: usize,
    /// List the registered rows and datasets, then exit.
    #[arg(long)]
    list: bool,
}

/// The evaluator's subcommands.
#[derive(clap::Subcommand, Debug)]
pub enum Command {
    /// Score a prediction file (docs/FORMAT.md, "Prediction files") written by any program,
    /// e.g. the Python package's PredictionWriter, and add it to every board as an external
    /// row. Checks the file against the dataset first; a refused file changes no report.
    /// On a render folder (`generator render`), the file is a joints-only prediction
    /// (`joints.json`, docs/FORMAT.md "Joints-only predictions"), scored in every
    /// convention into joints_renders.csv.
    Score {
        /// The dataset the file was made for: a name (see `evaluator --list`) or a dataset
        /// folder.
        #[arg(long)]
        dataset: String,
        /// The prediction file.
        #[arg(long)]
        predictions: PathBuf,
        /// The row's name on the boards (default: the method named in the file's header).
        #[arg(long)]
        name: Option<String>,
        /// The folders and weights.
        #[command(flatten)]
        common: Common,
    },
    /// Write any row's predictions on a dataset as a prediction file (the format `score`
    /// reads), to compare or share them.
    Predict {
        /// The row (see `evaluator --list`).
        #[arg(long)]
        method: String,
        /// The dataset: a name or a dataset folder.
        #[arg(long)]
        dataset: String,
        /// The prediction file to write.
        #[arg(long)]
        out: PathBuf,
        /// Only the first N pairs of the dataset.
        #[arg(long, value_name = "N")]
        limit: Option<usize>,
        /// The folders and weights.
        #[command(flatten)]
        common: Common,
    },
}

/// The folders and weights shared by the subcommands.
#[derive(clap::Args, Debug)]
pub struct Common {
    /// Folder of the datasets (each in <root>/<name>).
    #[arg(long, default_value = "datasets")]
    datasets_root: PathBuf,
    /// Folder of the reports.
    #[arg(long, default_value = "reports")]
    reports: PathBuf,
    /// The network's weights folder (config.toml and model.bpk).
    #[arg(long, default_value = DEFAULT_WEIGHTS)]
    weights: PathBuf,
    /// Pairs per dataset in the segmentation gallery (as given to the runs already in the
    /// reports, whose rows otherwise leave the boards).
    #[arg(long, default_value_t = 3)]
    gallery_pairs: usize,
}

fn registry(weights: &Path) -> Result<crate::rows::registry::Registry> {
    standard_registry(weights)
        .with_context(|| format!("building the method registry (weights {})", weights.display()))
}

fn run_command(command: Command) -> Result<()> {
    let bars = Bars::default();
    let started = Instant::now();
    match command {
        Command::Score { dataset, predictions, name, common }
            if pairs::renders::is_render(Path::new(&dataset)) =>
        {
            use crate::boards::render_joints::{score_render, table, upsert, RENDER_JOINTS_FILE};
            let dir = Path::new(&dataset);
            let rows = score_render(dir, &predictions, name.as_deref()).with_context(|| {
                format!("scoring {} on the render {dataset}", predictions.display())
            })?;
            upsert(&common.reports, &rows).with_context(|| {
                format!("writing {}", common.reports.join(RENDER_JOINTS_FILE).display())
            })?;
            for line in table(&rows) {
                println!("{line}");
            }
            eprintln!(
                "scored {} as {} in {:.1} s; wrote {}",
                predictions.display(),
                rows[0].method,
                started.elapsed().as_secs_f64(),
                common.reports.join(RENDER_JOINTS_FILE).display()
            );
        }
        Command::Score { dataset, predictions, name, common } => {
            let registry = registry(&common.weights)?;
            let specs = dataset_specs(&common.reports, &common.datasets_root, &[])?;
            let setup = CommandOptions {
                datasets_root: common.datasets_root,
                reports: common.reports,
                gallery_pairs: common.gallery_pairs,
            };
            let (row, summary) = score_predictions(
                &registry,
                &specs,
                &dataset,
                &predictions,
                name.as_deref(),
                &setup,
                &bars,
            )
            .with_context(|| format!("scoring {} on {dataset}", predictions.display()))?;
            for line in crate::boards::leaderboard::row_lines(&summary.reports, &row) {
                println!("{line}");
            }
            eprintln!(
                "scored {} as {row} in {:.1} s; wrote {}/LEADERBOARD.md",
                predictions.display(),
                started.elapsed().as_secs_f64(),
                summary.reports.display()
            );
        }
        Command::Predict { method, dataset, out, limit, common } => {
            let mut registry = registry(&common.weights)?;
            add_remembered_rows(&mut registry, &common.reports).with_context(|| {
                format!("reading the external rows in {}", common.reports.display())
            })?;
            let specs = dataset_specs(&common.reports, &common.datasets_root, &[])?;
            let setup = CommandOptions {
                datasets_root: common.datasets_root,
                reports: common.reports,
                gallery_pairs: common.gallery_pairs,
            };
            let request = PredictRequest { dataset, row: method, out, limit };
            let (pairs, failed) = write_predictions(&registry, &specs, &request, &setup, &bars)
                .with_context(|| {
                    format!("writing {}'s predictions on {}", request.row, request.dataset)
                })?;
            eprintln!(
                "wrote {} ({pairs} pairs, {failed} failed) in {:.1} s",
                request.out.display(),
                started.elapsed().as_secs_f64()
            );
        }
    }
    Ok(())
}

/// Runs what `args` ask for.
pub fn run(args: Args) -> Result<()> {
    if let Some(command) = args.command {
        return run_command(command);
    }
    let mut registry = registry(&args.weights)?;
    let limited = match args.limit {
        Some(n) => args.reports.join(format!("limit-{n}")),
        None => args.reports.clone(),
    };
    add_remembered_rows(&mut registry, &limited)
        .with_context(|| format!("reading the external rows in {}", limited.display()))?;
    let specs = dataset_specs(&limited, &args.datasets_root, &args.user_datasets)?;
    if args.list {
        println!("rows:");
        for entry in registry.entries() {
            println!("  {:28} flow source {}", entry.name, entry.flow_source());
        }
        println!("datasets:");
        for spec in &specs {
            println!("  {:28} {}", spec.name, spec.dir(&args.datasets_root).display());
        }
        let render = crate::running::renders::RENDER_DATASET;
        println!(
            "  {render:28} {} (render benchmark: joints only)",
            args.datasets_root.join(render).display()
        );
        return Ok(());
    }
    if !args.all
        && args.methods.is_empty()
        && args.datasets.is_empty()
        && args.user_datasets.is_empty()
    {
        anyhow::bail!(
            "nothing to do: pass --all, or narrow with --methods/--datasets/--dataset (see --help)"
        );
    }
    // --datasets names them; else the defaults (unless only --dataset was given) and the
    // datasets given with --dataset.
    let mut datasets = args.datasets.clone();
    if datasets.is_empty() {
        if args.all || args.user_datasets.is_empty() {
            datasets.extend(default_datasets().into_iter().map(|s| s.name));
            datasets.push(crate::running::renders::RENDER_DATASET.into());
        }
        datasets.extend(args.user_datasets.iter().map(|s| s.name.clone()));
    }
    let options = Options {
        datasets,
        methods: args.methods,
        limit: args.limit,
        datasets_root: args.datasets_root,
        reports: args.reports,
        force: args.force,
        gallery_pairs: args.gallery_pairs,
        validation: validation_datasets(),
    };
    let started = Instant::now();
    let bars = Bars::default();
    let summary = evaluate(&registry, &specs, &options, &bars)?;
    remember_datasets(&summary.reports, &args.user_datasets).with_context(|| {
        format!("remembering the user datasets in {}", summary.reports.display())
    })?;
    eprintln!(
        "{} runs ({} fresh, {} cached), {} failed pairs, {} failed sets, {:.1} s; wrote {}/LEADERBOARD.md",
        summary.fresh + summary.cached,
        summary.fresh,
        summary.cached,
        summary.failed,
        summary.failed_sets,
        started.elapsed().as_secs_f64(),
        summary.reports.display()
    );
    for line in
        crate::boards::iterations::summary_lines(&summary.iterations, &summary.iteration_joints)
    {
        eprintln!("{line}");
    }
    Ok(())
}
