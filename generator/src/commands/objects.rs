//! The `export-objects`, `export` and `merge` commands, and the progress bars and report
//! every command shares.

use std::path::PathBuf;

use crate::asset_dataset::{load_assets, relative};
use crate::objects::{built_in_objects, state_draw};
use crate::shard::merge_shards;
use anyhow::{bail, Context, Result};
use assets::{Source, SourcedObject};
use formats::{export_dataset, Format};
use indicatif::{ProgressBar, ProgressStyle};
use pairs::dataset::Manifest;
use simulators::collision::Budget;
use simulators::inertia::DEFAULT_DENSITY;
use simulators::physics::PhysicsOptions;
use simulators::{export_objects, ExportOptions, ExportedObject, ObjectFormat};

use crate::config::GeneratorConfig;

use crate::commands::args::Selection;

/// The simulator settings of `export-objects`.
#[derive(Debug, clap::Args)]
pub(crate) struct PhysicsArgs {
    /// Descriptions to write, comma-separated: urdf (PyBullet, SAPIEN, Isaac's importer),
    /// mjcf (MuJoCo), usd (UsdPhysics .usda: Isaac Sim).
    #[arg(long, value_delimiter = ',', default_value = "urdf,mjcf,usd", value_parser = parse_object_format)]
    format: Vec<ObjectFormat>,
    /// Density of every link, kilograms per cubic object unit (kg/m³: the built-in
    /// categories are modelled at real-world sizes in metres); masses and inertias come
    /// from the meshes' volumes.
    #[arg(long, default_value_t = DEFAULT_DENSITY)]
    density: f64,
    /// Convex collision hulls per link at most (the cheapest to merge are merged).
    #[arg(long, default_value_t = Budget::default().max_hulls)]
    max_hulls: usize,
    /// Vertices per collision hull at most.
    #[arg(long, default_value_t = Budget::default().max_vertices)]
    max_hull_vertices: usize,
}

impl PhysicsArgs {
    fn options(&self) -> Result<ExportOptions> {
        if !(self.density.is_finite() && self.density > 0.0) {
            bail!("--density must be a positive number, not {}", self.density);
        }
        if self.max_hulls == 0 {
            bail!("--max-hulls must be at least 1");
        }
        if self.max_hull_vertices < 4 {
            bail!("--max-hull-vertices must be at least 4 (a tetrahedron)");
        }
        let mut formats = self.format.clone();
        formats.dedup();
        Ok(ExportOptions {
            formats,
            physics: PhysicsOptions {
                density: self.density,
                budget: Budget { max_hulls: self.max_hulls, max_vertices: self.max_hull_vertices },
            },
        })
    }
}

fn parse_object_format(s: &str) -> Result<ObjectFormat, String> {
    s.parse()
}

/// `generator export-objects`.
pub(crate) fn export_objects_command(
    selection: &Selection,
    out: &std::path::Path,
    force: bool,
    physics: &PhysicsArgs,
) -> Result<()> {
    let options = physics.options()?;
    let config = selection.config()?;
    config.validate().context("checking the config")?;
    let started = std::time::Instant::now();
    let objects = selected_objects(selection, &config, "exported")?;
    let bar = progress_bar(objects.len() as u64, "objects");
    bar.set_message(format!("exporting {}", out.display()));
    let states = state_draw(&config);
    let written = export_objects(&states, &objects, out, force, &options, |n| bar.set_position(n))
        .with_context(|| format!("exporting objects to {}", out.display()))?;
    bar.finish_and_clear();
    let formats: Vec<&str> = options.formats.iter().map(|f| f.as_str()).collect();
    println!(
        "wrote {} objects ({}) to {} in {:.2} s",
        written.len(),
        formats.join(", "),
        out.display(),
        started.elapsed().as_secs_f64()
    );
    report_collision(&written, &options);
    Ok(())
}

/// The collision and mass summary of an export, and every fallback taken.
fn report_collision(written: &[ExportedObject], options: &ExportOptions) {
    let hulls: usize = written.iter().map(|o| o.collision.hulls).sum();
    let links: usize = written.iter().map(|o| o.links).sum();
    let worst = written
        .iter()
        .max_by(|a, b| a.collision.max_hausdorff.total_cmp(&b.collision.max_hausdorff));
    let ratios: Vec<f64> = written.iter().map(|o| o.collision.volume_ratio).collect();
    let (lo, hi) = ratios
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &r| (lo.min(r), hi.max(r)));
    let budget = options.physics.budget;
    println!(
        "collision: {hulls} convex hulls for {links} links (at most {} per link, {} vertices per \
         hull); hull volume / visual volume {lo:.3}-{hi:.3} per object",
        budget.max_hulls, budget.max_vertices
    );
    if let Some(w) = worst {
        println!(
            "  largest Hausdorff distance between a link and its hulls: {:.4} ({})",
            w.collision.max_hausdorff, w.folder
        );
    }
    let hull_massed: usize = written.iter().map(|o| o.collision.links_massed_by_hulls).sum();
    println!(
        "mass: density {} kg per cubic unit; {} links massed from their closed meshes, {hull_massed} \
         from their hulls (open meshes)",
        options.physics.density,
        links - hull_massed
    );
    for o in written {
        for note in &o.notes {
            eprintln!("  note: {}/{note}", o.folder);
        }
    }
}

/// The objects a selection names: the built-in objects of the config, or every asset
/// that loads (the others are listed on stderr as not `what`).
pub(crate) fn selected_objects(
    selection: &Selection,
    config: &GeneratorConfig,
    what: &str,
) -> Result<Vec<SourcedObject>> {
    let objects = match &selection.assets {
        Some(root) => {
            let sources = load_assets(root, config)
                .with_context(|| format!("looking for assets in {}", root.display()))?;
            let mut objects = Vec::with_capacity(sources.len());
            let mut failed = 0;
            for (i, source) in sources.into_iter().enumerate() {
                let path = relative(root, &source.path);
                match source.loaded {
                    Ok(imported) => objects.push(SourcedObject {
                        object_id: i as u32,
                        object: imported.object,
                        source: Source::Asset { path },
                        surfaces: imported.surfaces,
                    }),
                    Err(e) => {
                        failed += 1;
                        eprintln!("  {path}: {e}");
                    }
                }
            }
            if objects.is_empty() {
                bail!("no asset in {} could be read", root.display());
            }
            if failed > 0 {
                eprintln!("{failed} assets could not be read and are not {what}");
            }
            objects
        }
        None => built_in_objects(config).context("building the objects")?,
    };
    Ok(objects)
}

/// `generator export`.
pub(crate) fn export_command(
    format: Format,
    dataset: &std::path::Path,
    out: &std::path::Path,
    force: bool,
) -> Result<()> {
    let started = std::time::Instant::now();
    let bar = progress_bar(0, "pairs");
    bar.set_message(format!("exporting {} as {}", dataset.display(), format.as_str()));
    let summary = export_dataset(format, dataset, out, force, |n| bar.set_position(n))
        .with_context(|| format!("exporting {} to {}", dataset.display(), out.display()))?;
    bar.finish_and_clear();
    println!(
        "wrote {} pairs as {} ({} files, {:.1} MiB) to {} in {:.2} s",
        summary.pairs,
        format.as_str(),
        summary.files,
        summary.bytes as f64 / (1 << 20) as f64,
        out.display(),
        started.elapsed().as_secs_f64()
    );
    Ok(())
}

/// `generator merge`.
pub(crate) fn merge(shards: &[PathBuf], out: &std::path::Path, force: bool) -> Result<()> {
    if !force && out.join(pairs::dataset::MANIFEST_FILE).exists() {
        bail!("{} already holds a dataset; pass --force to replace it", out.display());
    }
    let bar = progress_bar(0, "pairs");
    bar.set_message(format!("merging into {}", out.display()));
    let started = std::time::Instant::now();
    let manifest = merge_shards(shards, out, force, |n| bar.set_position(n))
        .with_context(|| format!("merging {} shards into {}", shards.len(), out.display()))?;
    bar.finish_and_clear();
    report(&manifest, out, started);
    Ok(())
}

/// A progress bar counting `unit`.
pub(crate) fn progress_bar(len: u64, unit: &str) -> ProgressBar {
    let template =
        format!("{{msg}} [{{elapsed_precise}}] {{wide_bar}} {{pos}}/{{len}} {unit} ({{eta}})");
    ProgressBar::new(len)
        .with_style(ProgressStyle::with_template(&template).expect("the template is valid"))
}

/// Prints what was written.
pub(crate) fn report(manifest: &Manifest, out: &std::path::Path, started: std::time::Instant) {
    let bytes: u64 = manifest.files.values().map(|f| f.bytes).sum();
    let shard = manifest
        .origin
        .shard
        .map(|s| format!(" (shard {}/{})", s.index, s.count))
        .unwrap_or_default();
    let (count, unit) = match manifest.counts.sets {
        0 => (manifest.counts.pairs, "pairs"),
        sets => (sets, "sets"),
    };
    println!(
        "wrote {count} {unit} of {} objects{shard} to {} ({:.1} MiB) in {:.2} s",
        manifest.counts.objects,
        out.display(),
        bytes as f64 / (1 << 20) as f64,
        started.elapsed().as_secs_f64()
    );
}
