//! `generator`: writes a dataset of articulated shape pairs with complete ground truth.

use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use clap::Parser;
use generator::categories::CATEGORIES;
use generator::config::GeneratorConfig;
use generator::generate::generate_dataset;
use indicatif::{ProgressBar, ProgressStyle};
use pairs::PairKind;

/// Generate a dataset of articulated shape pairs (P, Q) with ground-truth parts, motions,
/// flow, correspondences and joints, following the test protocol of Yi et al. 2018.
///
/// With no arguments it writes the paper-size SF2F set (175 objects, 875 pairs, N = 512,
/// seed 0) to datasets/sf2f. Flags override the values of --config, which override the
/// built-in defaults (datasets/sf2f.toml lists them).
#[derive(Debug, Parser)]
#[command(version, about, long_about)]
struct Args {
    /// TOML file with any of the config fields (see datasets/sf2f.toml).
    #[arg(short, long, value_name = "FILE")]
    config: Option<PathBuf>,
    /// Kind of pairs: SF2F (full to full). SF2P and SP2P need the virtual scanner.
    #[arg(long, value_parser = parse_kind)]
    kind: Option<PairKind>,
    /// Number of objects; each gives --pairs-per-object pairs.
    #[arg(short = 'n', long)]
    objects: Option<u32>,
    /// Pairs of distinct articulation states per object.
    #[arg(long)]
    pairs_per_object: Option<u32>,
    /// Articulation states drawn per object.
    #[arg(long)]
    states_per_object: Option<u32>,
    /// Points per cloud.
    #[arg(short, long)]
    points: Option<u32>,
    /// Dataset seed: the same config and seed give byte-identical files.
    #[arg(short, long)]
    seed: Option<u64>,
    /// Comma-separated categories to draw objects from in turn (default: all; see
    /// --list-categories).
    #[arg(long, value_delimiter = ',')]
    categories: Option<Vec<String>>,
    /// Output folder [default: datasets/<kind>, e.g. datasets/sf2f].
    #[arg(short, long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Worker threads [default: all cores]; the output does not depend on it.
    #[arg(short = 'j', long)]
    threads: Option<usize>,
    /// Replace an existing dataset in the output folder (only once the new one is complete).
    #[arg(long)]
    force: bool,
    /// List the built-in categories and exit.
    #[arg(long)]
    list_categories: bool,
    /// Print the resolved config as TOML and exit.
    #[arg(long)]
    print_config: bool,
}

fn parse_kind(s: &str) -> Result<PairKind, String> {
    match s.to_ascii_uppercase().as_str() {
        "SF2F" => Ok(PairKind::Sf2f),
        "SF2P" => Ok(PairKind::Sf2p),
        "SP2P" => Ok(PairKind::Sp2p),
        _ => Err(format!("unknown kind {s:?} (SF2F, SF2P or SP2P)")),
    }
}

impl Args {
    /// The config: built-in defaults, then the file, then the flags.
    fn config(&self) -> Result<GeneratorConfig> {
        let mut config = match &self.config {
            Some(path) => {
                let text = std::fs::read_to_string(path)
                    .with_context(|| format!("reading {}", path.display()))?;
                toml::from_str(&text)
                    .with_context(|| format!("parsing config {}", path.display()))?
            }
            None => GeneratorConfig::default(),
        };
        macro_rules! set {
            ($($field:ident),*) => { $(if let Some(v) = &self.$field { config.$field = v.clone(); })* };
        }
        set!(kind, objects, pairs_per_object, states_per_object, points, seed, categories);
        Ok(config)
    }
}

fn main() {
    tracing_subscriber::fmt()
        .with_env_filter(tracing_subscriber::EnvFilter::from_default_env())
        .with_writer(std::io::stderr)
        .init();
    if let Err(err) = run(Args::parse()) {
        eprintln!("error: {err:#}");
        std::process::exit(1);
    }
}

fn run(args: Args) -> Result<()> {
    if args.list_categories {
        for c in CATEGORIES {
            println!("{:<12} {}", c.name, c.description);
        }
        return Ok(());
    }
    let config = args.config()?;
    if args.print_config {
        print!("{}", toml::to_string(&config).context("formatting the config")?);
        return Ok(());
    }
    config.validate().context("checking the config")?;
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("datasets").join(config.kind.as_str().to_lowercase()));
    if !args.force && out.join(pairs::dataset::MANIFEST_FILE).exists() {
        bail!("{} already holds a dataset; pass --force to replace it", out.display());
    }
    if let Some(threads) = args.threads {
        if threads == 0 {
            bail!("--threads must be at least 1");
        }
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build_global()
            .context("starting the thread pool")?;
    }
    let bar = ProgressBar::new(config.total_pairs()).with_style(
        ProgressStyle::with_template(
            "{msg} [{elapsed_precise}] {wide_bar} {pos}/{len} pairs ({eta})",
        )
        .expect("the template is valid"),
    );
    bar.set_message(format!("generating {}", out.display()));
    let started = std::time::Instant::now();
    let manifest = generate_dataset(&config, &out, args.force, None, |n| bar.set_position(n))
        .with_context(|| format!("generating the dataset in {}", out.display()))?;
    bar.finish_and_clear();
    let bytes: u64 = manifest.files.values().map(|f| f.bytes).sum();
    println!(
        "wrote {} pairs of {} objects to {} ({:.1} MiB) in {:.2} s",
        manifest.counts.pairs,
        manifest.counts.objects,
        out.display(),
        bytes as f64 / (1 << 20) as f64,
        started.elapsed().as_secs_f64()
    );
    Ok(())
}
