//! What `generator` does with its [`Args`]: a dataset (built-in categories or user
//! assets), a shard merge, an export, renders, the gallery, the category list.

use std::path::PathBuf;

use anyhow::{bail, Context, Result};

use crate::asset_dataset::{generate_asset_dataset, load_assets, relative};
use crate::commands::args::{Args, Command};
use crate::commands::objects::{
    export_command, export_objects_command, merge, progress_bar, report,
};
use crate::config::GeneratorConfig;
use crate::gallery::write_gallery;
use crate::generate::generate_dataset;
use articulated::categories::{Split, CATEGORIES};

/// Runs what `args` ask for.
pub fn run(args: Args) -> Result<()> {
    match &args.command {
        Some(Command::Merge { shards, out, force }) => return merge(shards, out, *force),
        Some(Command::ExportObjects { selection, out, force, threads, physics }) => {
            set_threads(*threads)?;
            return export_objects_command(selection, out, *force, physics);
        }
        Some(Command::Render { args, threads }) => {
            set_threads(*threads)?;
            return crate::commands::render::render_command(args);
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
    let objects = crate::shard::shard_objects(config.objects, args.sampling.shard)?;
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
