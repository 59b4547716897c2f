//! `generator`: writes a dataset of articulated shape pairs with complete ground truth.

use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use clap::{Parser, Subcommand};
use generator::asset_dataset::{generate_asset_dataset, load_assets, relative};
use generator::categories::{Split, CATEGORIES};
use generator::config::GeneratorConfig;
use generator::export::formats::Format;
use generator::gallery::write_gallery;
use generator::generate::generate_dataset;
use generator::shard::parse_shard;
use pairs::dataset::Shard;
use pairs::{PairKind, SetMode};

mod commands;
mod render;

use commands::{export_command, export_objects_command, merge, progress_bar, report};

/// Generate a dataset of articulated shape pairs (P, Q) with ground-truth parts, motions,
/// flow, correspondences and joints, following the test protocol of Yi et al. 2018.
///
/// With no arguments it writes the paper-size SF2F set (175 objects, 875 pairs, N = 512,
/// seed 0, held-out test categories) to datasets/sf2f; `--kind sf2p` and `--kind sp2p`
/// write the scanned sets to datasets/sf2p and datasets/sp2p, `--kind xf2f` and `--kind xf2p`
/// the cross-instance sets (two objects of one category). Flags override the values of
/// --config, which override the built-in defaults (datasets/sf2f.toml, sf2p.toml and
/// sp2p.toml list them).
#[derive(Debug, Parser)]
#[command(version, about, long_about, args_conflicts_with_subcommands = true, after_help = EXAMPLES)]
struct Args {
    #[command(subcommand)]
    command: Option<Command>,
    #[command(flatten)]
    selection: Selection,
    #[command(flatten)]
    sampling: Sampling,
    /// Output folder [default: datasets/<kind>, or datasets/<kind>-<split> for train and
    /// validation; datasets/assets-<kind> with --assets; reports/gallery with --gallery].
    #[arg(short, long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Worker threads [default: all cores]; the output does not depend on it.
    #[arg(short = 'j', long)]
    threads: Option<usize>,
    /// Replace an existing dataset in the output folder (only once the new one is complete).
    #[arg(long)]
    force: bool,
    /// List the built-in categories with their splits and exit.
    #[arg(long)]
    list_categories: bool,
    /// Draw every category closed and opened into PNGs (reports/gallery) and exit.
    #[arg(long)]
    gallery: bool,
    /// Print the resolved config as TOML and exit.
    #[arg(long)]
    print_config: bool,
}

/// Which objects: the built-in categories and seed, or user assets (shared by generation
/// and `export-objects`).
#[derive(Debug, clap::Args)]
struct Selection {
    /// TOML file with any of the config fields (see datasets/sf2f.toml).
    #[arg(short, long, value_name = "FILE")]
    config: Option<PathBuf>,
    /// Number of objects; each gives --pairs-per-object pairs.
    #[arg(short = 'n', long)]
    objects: Option<u32>,
    /// Articulation states drawn per object.
    #[arg(long)]
    states_per_object: Option<u32>,
    /// Dataset seed: the same config and seed give byte-identical files.
    #[arg(short, long)]
    seed: Option<u64>,
    /// Category split: test (held-out benchmark categories), train or validation.
    #[arg(long)]
    split: Option<Split>,
    /// Comma-separated categories to draw objects from in turn (default: every category of
    /// the split; see --list-categories). A name listed twice is drawn twice as often.
    #[arg(long, value_delimiter = ',')]
    categories: Option<Vec<String>>,
    /// Make the dataset from user assets instead of the built-in categories: an asset file,
    /// or a folder searched recursively for .urdf, .gltf, .glb, and .obj files with a
    /// <name>.joints.json sidecar (docs/FORMAT.md, "User assets"). Each asset is one object
    /// (--objects, --split and --categories do not apply).
    #[arg(long, value_name = "PATH")]
    assets: Option<PathBuf>,
    /// Extra folder searched for URDF `package://` meshes (repeatable).
    #[arg(long, value_name = "DIR")]
    package_path: Vec<PathBuf>,
    /// Range given to continuous (unlimited) joints of assets, degrees: LO,HI.
    #[arg(long, value_name = "LO,HI", value_parser = parse_range, allow_hyphen_values = true)]
    continuous_range: Option<[f64; 2]>,
}

/// How objects become pairs (generation only).
#[derive(Debug, clap::Args)]
struct Sampling {
    /// Kind of pairs: SF2F (full to full), SF2P (full to a virtual scan) or SP2P (scan to
    /// scan, with depth, label and colour images under <out>/images); XF2F and XF2P are
    /// cross-instance: P and Q are two different objects of one category (full to full,
    /// full to a scan), parts matched by role, no flow (docs/DATASETS.md). `sets` writes
    /// sets of K views of one object instead (--views, --mode; docs/FORMAT.md, "Set
    /// datasets"). The scanner's settings are the [scan] table of --config
    /// (datasets/sf2p.toml lists them).
    #[arg(long, value_parser = parse_kind)]
    kind: Option<KindArg>,
    /// Views K per set, 2 to 16 [default: 4] (with --kind sets).
    #[arg(long, value_name = "K")]
    views: Option<u32>,
    /// What the views of a set are: full (every view a full shape), scan (every view a
    /// virtual scan, with images) or mixed (view 0 full, the others scans) [default: full]
    /// (with --kind sets).
    #[arg(long, value_parser = parse_mode)]
    mode: Option<SetMode>,
    /// Sets per object, each of K distinct states [default: 1] (with --kind sets).
    #[arg(long)]
    sets_per_object: Option<u32>,
    /// Pairs of distinct articulation states per object.
    #[arg(long)]
    pairs_per_object: Option<u32>,
    /// Points per cloud.
    #[arg(short, long)]
    points: Option<u32>,
    /// Fewest points every part must get in both clouds; pairs below it are redrawn.
    #[arg(long)]
    min_part_points: Option<u32>,
    /// Make only shard I of N (I from 0): a contiguous range of the objects, for one task
    /// of a cluster array job; `generator merge` joins the shards.
    #[arg(long, value_name = "I/N", value_parser = parse_shard_arg)]
    shard: Option<Shard>,
}

/// Shown after the options in `--help`.
const EXAMPLES: &str = "Examples:
  generator --kind sf2p                                   the paper-size SF2P set, datasets/sf2p
  generator --kind sp2p -n 20 --out /tmp/sp2p             20 objects of scan pairs with images
  generator --kind xf2p                                   two objects of a category, full to scan
  generator --kind sets --views 4                         sets of 4 full views, datasets/sets
  generator --kind sets --views 8 --mode scan -n 20       sets of 8 scans with images
  generator --split train -n 20000 --out datasets/train   a training set on disk
  generator --shard 3/8 --out shards/3                    shard 3 of 8 (cluster array job)
  generator merge shards/* --out datasets/sf2f            the shards as one dataset
  generator --assets models/ --kind sf2p -o /tmp/m        pairs of your URDF, OBJ and glTF assets
  generator --gallery                                     reports/gallery/*.png
  generator export-objects -n 26 --out objects/           objects as URDF (PartNet-Mobility layout)
  generator render --layout paris -n 5                    multi-view images for PARIS (see render --help)
  generator export --format yi-mat --dataset datasets/sf2f --out sf2f-mat";

/// Subcommands besides generating.
#[derive(Debug, Subcommand)]
enum Command {
    /// Merge the shard folders of one sharded run into a dataset byte-identical to the
    /// unsharded run (every shard is verified against its checksums first).
    Merge {
        /// The shard folders, in any order; each of 0..N exactly once.
        #[arg(required = true, value_name = "SHARD_DIR")]
        shards: Vec<PathBuf>,
        /// Folder of the merged dataset.
        #[arg(short, long, value_name = "DIR")]
        out: PathBuf,
        /// Replace an existing dataset in --out (only once the merged one is complete).
        #[arg(long)]
        force: bool,
    },
    /// Export objects as simulation-ready folders in the PartNet-Mobility layout, one per
    /// object, from the built-in categories or from --assets: mobility.urdf, mobility.xml
    /// (MJCF) and mobility.usda (USD), textured_objs/*.obj, convex collision hulls in
    /// collision/*.obj, masses from the geometry, mobility_v2.json, meta.json, states.json;
    /// `generator --assets <out>` with the same settings makes the same pairs
    /// (docs/SIMULATORS.md, docs/FORMAT.md "Exported objects").
    #[command(after_help = EXPORT_OBJECTS_EXAMPLES)]
    ExportObjects {
        #[command(flatten)]
        selection: Selection,
        /// Output folder; refused if not empty, unless --force.
        #[arg(short, long, value_name = "DIR")]
        out: PathBuf,
        /// Replace the output folder's contents (only once the export is complete).
        #[arg(long)]
        force: bool,
        /// Worker threads [default: all cores]; the output does not depend on it.
        #[arg(short = 'j', long)]
        threads: Option<usize>,
        #[command(flatten)]
        physics: commands::PhysicsArgs,
    },
    /// Render objects in two or more articulation states from V calibrated cameras for
    /// image-based methods: RGB (materials and light, never the part), depth, part-label
    /// and normal images, in our layout or PARIS's, DigitalTwinArt's or ArtGS's
    /// (docs/FORMAT.md, "Renders").
    #[command(after_help = render::RENDER_EXAMPLES)]
    Render {
        #[command(flatten)]
        args: render::RenderArgs,
        /// Worker threads [default: all cores]; the output does not depend on it.
        #[arg(short = 'j', long)]
        threads: Option<usize>,
    },
    /// Export a dataset in another method's layout: `yi-mat` (the .mat files of Yi et al.'s
    /// code) or `mbs-npz` (MultiBodySync's npz files and meta.json); docs/FORMAT.md,
    /// "Exports for other methods".
    Export {
        /// Layout: yi-mat or mbs-npz.
        #[arg(long, value_parser = parse_format)]
        format: Format,
        /// A dataset folder (with manifest.json and pairs.mcap).
        #[arg(long, value_name = "DIR")]
        dataset: PathBuf,
        /// Output folder; refused if not empty, unless --force.
        #[arg(short, long, value_name = "DIR")]
        out: PathBuf,
        /// Replace the output folder's contents (only once the export is complete).
        #[arg(long)]
        force: bool,
    },
}

/// Shown after the options of `export-objects --help`.
const EXPORT_OBJECTS_EXAMPLES: &str = "Examples:
  generator export-objects -n 26 --out objects/            one object of every test category
  generator export-objects --split train -n 200 --out o/   200 training objects
  generator export-objects --assets models/ --out o/       your assets in the same layout
  generator export-objects -n 26 --format mjcf --out o/    MJCF only (plus meshes and hulls)
  generator export-objects -n 26 --max-hulls 8 --density 700 --out o/
  generator --assets objects/ -n 26 --kind sf2p            pairs of the exported objects";

fn parse_format(s: &str) -> Result<Format, String> {
    s.parse()
}

fn parse_shard_arg(s: &str) -> Result<Shard, String> {
    parse_shard(s).map_err(|e| e.to_string())
}

fn parse_range(s: &str) -> Result<[f64; 2], String> {
    let bad = || format!("{s:?} is not a range: write LO,HI in degrees, e.g. -90,90");
    let (lo, hi) = s.split_once(',').ok_or_else(bad)?;
    Ok([lo.trim().parse().map_err(|_| bad())?, hi.trim().parse().map_err(|_| bad())?])
}

/// `--kind`: a pair kind, or `sets`.
#[derive(Debug, Clone, Copy, PartialEq)]
enum KindArg {
    Pair(PairKind),
    Sets,
}

fn parse_kind(s: &str) -> Result<KindArg, String> {
    if s.eq_ignore_ascii_case("sets") {
        return Ok(KindArg::Sets);
    }
    s.parse().map(KindArg::Pair).map_err(|e: String| format!("{e}, or sets"))
}

fn parse_mode(s: &str) -> Result<SetMode, String> {
    s.parse()
}

impl Selection {
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
        set!(objects, states_per_object, seed, split, categories);
        if !self.package_path.is_empty() || self.continuous_range.is_some() {
            let mut import = config.importer();
            import.package_paths.extend(self.package_path.iter().cloned());
            if let Some(range) = self.continuous_range {
                import.continuous_range_deg = range;
            }
            config.import = Some(import);
        }
        Ok(config)
    }
}

impl Args {
    /// The config of a dataset: the selection's, then the sampling flags.
    fn config(&self) -> Result<GeneratorConfig> {
        let mut config = self.selection.config()?;
        let sampling = &self.sampling;
        macro_rules! set {
            ($($field:ident),*) => { $(if let Some(v) = &sampling.$field { config.$field = v.clone(); })* };
        }
        set!(pairs_per_object, points, min_part_points);
        match sampling.kind {
            Some(KindArg::Pair(kind)) => {
                config.kind = kind;
                config.sets = None;
            }
            Some(KindArg::Sets) => config.sets = Some(config.sets.unwrap_or_default()),
            None => {}
        }
        let set_flags = [
            ("--views", sampling.views.is_some()),
            ("--mode", sampling.mode.is_some()),
            ("--sets-per-object", sampling.sets_per_object.is_some()),
        ];
        match &mut config.sets {
            Some(sets) => {
                sets.views = sampling.views.unwrap_or(sets.views);
                sets.mode = sampling.mode.unwrap_or(sets.mode);
                sets.per_object = sampling.sets_per_object.unwrap_or(sets.per_object);
            }
            None => {
                if let Some((flag, _)) = set_flags.iter().find(|(_, given)| *given) {
                    bail!("{flag} applies to set datasets: add --kind sets");
                }
            }
        }
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
    match &args.command {
        Some(Command::Merge { shards, out, force }) => return merge(shards, out, *force),
        Some(Command::ExportObjects { selection, out, force, threads, physics }) => {
            set_threads(*threads)?;
            return export_objects_command(selection, out, *force, physics);
        }
        Some(Command::Render { args, threads }) => {
            set_threads(*threads)?;
            return render::render_command(args);
        }
        Some(Command::Export { format, dataset, out, force }) => {
            return export_command(*format, dataset, out, *force);
        }
        None => {}
    }
    if args.list_categories {
        for c in CATEGORIES {
            let splits: Vec<&str> = c.splits.iter().map(|s| s.as_str()).collect();
            println!("{:<16} {:<16} {}", c.name, splits.join(","), c.description);
        }
        return Ok(());
    }
    set_threads(args.threads)?;
    if args.gallery {
        let dir = args.out.clone().unwrap_or_else(|| PathBuf::from("reports/gallery"));
        let bar = progress_bar(CATEGORIES.len() as u64, "categories");
        let written = write_gallery(&dir, args.selection.seed.unwrap_or(0), |c| {
            bar.set_message(c.name);
            bar.inc(1);
        })?;
        bar.finish_and_clear();
        println!("wrote {} files to {}", written.len(), dir.display());
        return Ok(());
    }
    let config = args.config()?;
    if args.print_config {
        print!("{}", toml::to_string(&config.resolved()).context("formatting the config")?);
        return Ok(());
    }
    config.validate().context("checking the config")?;
    if let Some(root) = &args.selection.assets {
        return assets(&args, &config, root);
    }
    let out = args.out.clone().unwrap_or_else(|| default_out(&config));
    if !args.force && out.join(pairs::dataset::MANIFEST_FILE).exists() {
        bail!("{} already holds a dataset; pass --force to replace it", out.display());
    }
    let objects = generator::shard::shard_objects(config.objects, args.sampling.shard)?;
    let unit = if config.sets.is_some() { "sets" } else { "pairs" };
    let bar = progress_bar(
        u64::from(objects.end - objects.start) * u64::from(config.items_per_object()),
        unit,
    );
    bar.set_message(format!("generating {}", out.display()));
    let started = std::time::Instant::now();
    let manifest =
        generate_dataset(&config, &out, args.force, args.sampling.shard, |n| bar.set_position(n))
            .with_context(|| format!("generating the dataset in {}", out.display()))?;
    bar.finish_and_clear();
    report(&manifest, &out, started);
    Ok(())
}

/// `generator --assets`: one object per asset found; failures listed at the end.
fn assets(args: &Args, config: &GeneratorConfig, root: &std::path::Path) -> Result<()> {
    if args.sampling.shard.is_some() {
        bail!("--shard does not apply to --assets");
    }
    let out = args.out.clone().unwrap_or_else(|| {
        let kind = match config.sets {
            Some(_) => "sets".to_string(),
            None => config.kind.as_str().to_lowercase(),
        };
        PathBuf::from("datasets").join(format!("assets-{kind}"))
    });
    if !args.force && out.join(pairs::dataset::MANIFEST_FILE).exists() {
        bail!("{} already holds a dataset; pass --force to replace it", out.display());
    }
    let started = std::time::Instant::now();
    let sources = load_assets(root, config)
        .with_context(|| format!("looking for assets in {}", root.display()))?;
    if sources.is_empty() {
        bail!(
            "no assets in {} (.urdf, .gltf, .glb, or .obj with a .joints.json sidecar)",
            root.display()
        );
    }
    let loaded = sources.iter().filter(|s| s.loaded.is_ok()).count();
    if loaded == 0 {
        for s in &sources {
            if let Err(e) = &s.loaded {
                eprintln!("  {}: {e}", relative(root, &s.path));
            }
        }
        bail!("none of the {} assets in {} could be read", sources.len(), root.display());
    }
    let unit = if config.sets.is_some() { "sets" } else { "pairs" };
    let bar = progress_bar(sources.len() as u64 * u64::from(config.items_per_object()), unit);
    bar.set_message(format!("generating {}", out.display()));
    let made =
        generate_asset_dataset(config, root, &sources, &out, args.force, |n| bar.set_position(n))
            .with_context(|| format!("generating the dataset in {}", out.display()))?;
    bar.finish_and_clear();
    report(&made.manifest, &out, started);
    if !made.failures.is_empty() {
        println!("{} of {} assets gave no pairs:", made.failures.len(), sources.len());
        for (path, error) in &made.failures {
            println!("  {path}: {error}");
        }
    }
    Ok(())
}

/// Sets the worker threads of the global pool (all cores when not given).
fn set_threads(threads: Option<usize>) -> Result<()> {
    if let Some(threads) = threads {
        if threads == 0 {
            bail!("--threads must be at least 1");
        }
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build_global()
            .context("starting the thread pool")?;
    }
    Ok(())
}

/// Where a dataset goes unless --out says otherwise.
fn default_out(config: &GeneratorConfig) -> PathBuf {
    let kind = match config.sets {
        Some(_) => "sets".to_string(),
        None => config.kind.as_str().to_lowercase(),
    };
    match config.split {
        Split::Test => PathBuf::from("datasets").join(kind),
        split => PathBuf::from("datasets").join(format!("{kind}-{split}")),
    }
}
