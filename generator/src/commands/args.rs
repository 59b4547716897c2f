//! `generator`'s arguments: the objects ([`Selection`], shared with `export-objects` and
//! `render`), how they become pairs ([`Sampling`]), the subcommands, and the config they
//! resolve to (built-in defaults, then `--config`, then the flags).

use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use clap::{Parser, Subcommand};
use pairs::dataset::Shard;
use pairs::{PairKind, SetMode};

use crate::commands::{objects, render};
use crate::config::GeneratorConfig;
use crate::shard::parse_shard;
use articulated::categories::Split;
use formats::Format;

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
pub struct Args {
    #[command(subcommand)]
    pub(crate) command: Option<Command>,
    #[command(flatten)]
    pub(crate) selection: Selection,
    #[command(flatten)]
    pub(crate) sampling: Sampling,
    /// Output folder [default: datasets/<kind>, or datasets/<kind>-<split> for train and
    /// validation; datasets/assets-<kind> with --assets; reports/gallery with --gallery].
    #[arg(short, long, value_name = "DIR")]
    pub(crate) out: Option<PathBuf>,
    /// Worker threads [default: all cores]; the output does not depend on it.
    #[arg(short = 'j', long)]
    pub(crate) threads: Option<usize>,
    /// Replace an existing dataset in the output folder (only once the new one is complete).
    #[arg(long)]
    pub(crate) force: bool,
    /// List the built-in categories with their splits and exit.
    #[arg(long)]
    pub(crate) list_categories: bool,
    /// Draw every category closed and opened into PNGs (reports/gallery) and exit.
    #[arg(long)]
    pub(crate) gallery: bool,
    /// Print the resolved config as TOML and exit.
    #[arg(long)]
    pub(crate) print_config: bool,
}

/// Which objects: the built-in categories and seed, or user assets (shared by generation
/// and `export-objects`).
#[derive(Debug, clap::Args)]
pub(crate) struct Selection {
    /// TOML file with any of the config fields (see datasets/sf2f.toml).
    #[arg(short, long, value_name = "FILE")]
    pub(crate) config: Option<PathBuf>,
    /// Number of objects; each gives --pairs-per-object pairs.
    #[arg(short = 'n', long)]
    pub(crate) objects: Option<u32>,
    /// Articulation states drawn per object.
    #[arg(long)]
    pub(crate) states_per_object: Option<u32>,
    /// Dataset seed: the same config and seed give byte-identical files.
    #[arg(short, long)]
    pub(crate) seed: Option<u64>,
    /// Category split: test (held-out benchmark categories), train or validation.
    #[arg(long)]
    pub(crate) split: Option<Split>,
    /// Comma-separated categories to draw objects from in turn (default: every category of
    /// the split; see --list-categories). A name listed twice is drawn twice as often.
    #[arg(long, value_delimiter = ',')]
    pub(crate) categories: Option<Vec<String>>,
    /// Make the dataset from user assets instead of the built-in categories: an asset file,
    /// or a folder searched recursively for .urdf, .gltf, .glb, and .obj files with a
    /// <name>.joints.json sidecar (docs/FORMAT.md, "User assets"). Each asset is one object
    /// (--objects, --split and --categories do not apply).
    #[arg(long, value_name = "PATH")]
    pub(crate) assets: Option<PathBuf>,
    /// Extra folder searched for URDF `package://` meshes (repeatable).
    #[arg(long, value_name = "DIR")]
    pub(crate) package_path: Vec<PathBuf>,
    /// Range given to continuous (unlimited) joints of assets, degrees: LO,HI.
    #[arg(long, value_name = "LO,HI", value_parser = parse_range, allow_hyphen_values = true)]
    pub(crate) continuous_range: Option<[f64; 2]>,
}

/// How objects become pairs (generation only).
#[derive(Debug, clap::Args)]
pub(crate) struct Sampling {
    /// Kind of pairs: SF2F (full to full), SF2P (full to a virtual scan) or SP2P (scan to
    /// scan, with depth, label and colour images under <out>/images); XF2F and XF2P are
    /// cross-instance: P and Q are two different objects of one category (full to full,
    /// full to a scan), parts matched by role, no flow (docs/DATASETS.md). `sets` writes
    /// sets of K views of one object instead (--views, --mode; docs/FORMAT.md, "Set
    /// datasets"). The scanner's settings are the [scan] table of --config
    /// (datasets/sf2p.toml lists them).
    #[arg(long, value_parser = parse_kind)]
    pub(crate) kind: Option<KindArg>,
    /// Views K per set, 2 to 16 [default: 4] (with --kind sets).
    #[arg(long, value_name = "K")]
    pub(crate) views: Option<u32>,
    /// What the views of a set are: full (every view a full shape), scan (every view a
    /// virtual scan, with images) or mixed (view 0 full, the others scans) [default: full]
    /// (with --kind sets).
    #[arg(long, value_parser = parse_mode)]
    pub(crate) mode: Option<SetMode>,
    /// Sets per object, each of K distinct states [default: 1] (with --kind sets).
    #[arg(long)]
    pub(crate) sets_per_object: Option<u32>,
    /// Pairs of distinct articulation states per object.
    #[arg(long)]
    pub(crate) pairs_per_object: Option<u32>,
    /// Points per cloud.
    #[arg(short, long)]
    pub(crate) points: Option<u32>,
    /// Fewest points every part must get in both clouds; pairs below it are redrawn.
    #[arg(long)]
    pub(crate) min_part_points: Option<u32>,
    /// Make only shard I of N (I from 0): a contiguous range of the objects, for one task
    /// of a cluster array job; `generator merge` joins the shards.
    #[arg(long, value_name = "I/N", value_parser = parse_shard_arg)]
    pub(crate) shard: Option<Shard>,
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
pub(crate) enum Command {
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
        physics: objects::PhysicsArgs,
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
pub(crate) enum KindArg {
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
    pub(crate) fn config(&self) -> Result<GeneratorConfig> {
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
    pub(crate) fn config(&self) -> Result<GeneratorConfig> {
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
