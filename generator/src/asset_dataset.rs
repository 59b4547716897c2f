//! Datasets from user assets (`generator --assets`): every asset found is one object, made
//! into pairs by the same protocol, normalisation and ground truth as a built-in category.
//! An asset that cannot be read, or cannot give its pairs, is recorded with its error in
//! the manifest and the others still give theirs.

use std::path::{Path, PathBuf};

use pairs::dataset::{AssetRecord, DatasetWriter, FileEntry, Manifest};
use rayon::prelude::*;

use crate::config::GeneratorConfig;
use crate::generate::{
    dataset_origin, pairs_of_object, sets_of_object, GenerateError, GeneratedPair, GeneratedSet,
    Variant,
};
use assets::{discover_assets, load_asset, ImportError, Imported};

/// Assets made into pairs at once before their pairs are written: bounds memory.
const BATCH_ASSETS: usize = 16;

/// One asset found under the folder given: where it is and what reading it gave.
#[derive(Debug)]
pub struct AssetSource {
    /// The asset's main file.
    pub path: PathBuf,
    /// The object, or why there is none.
    pub loaded: Result<Imported, ImportError>,
}

/// Finds every asset under `root` (or `root` itself, a file) and reads them in parallel,
/// in path order. Only a `root` that cannot be listed is an error; each asset's own
/// failure is kept in its [`AssetSource`].
pub fn load_assets(root: &Path, config: &GeneratorConfig) -> Result<Vec<AssetSource>, ImportError> {
    let options = config.importer();
    let paths = discover_assets(root)?;
    Ok(paths
        .into_par_iter()
        .map(|path| {
            let loaded = load_asset(&path, &options);
            AssetSource { path, loaded }
        })
        .collect())
}

/// A written asset dataset and the assets that gave no pairs.
#[derive(Debug, Clone)]
pub struct AssetDataset {
    /// The manifest written.
    pub manifest: Manifest,
    /// (asset path relative to the root, error) of every asset that gave no pairs.
    pub failures: Vec<(String, String)>,
}

/// Writes the pairs of `sources` (found under `root`) into `dir` as one dataset: asset `i`
/// is object `i`. Existing output is kept unless `overwrite`.
pub fn generate_asset_dataset(
    config: &GeneratorConfig,
    root: &Path,
    sources: &[AssetSource],
    dir: &Path,
    overwrite: bool,
    mut progress: impl FnMut(u64),
) -> Result<AssetDataset, GenerateError> {
    let config = GeneratorConfig { objects: (sources.len() as u32).max(1), ..config.clone() };
    config.validate()?;
    if config.kind.cross_instance() {
        return Err(GenerateError::Config(crate::config::ConfigError::Invalid {
            field: "kind",
            reason: format!(
                "{} pairs two instances of a procedural category; an asset is one object \
                 (use SF2F, SF2P or SP2P with --assets)",
                config.kind.as_str()
            ),
        }));
    }
    let mut writer = match config.sets {
        Some(_) => DatasetWriter::create_sets(dir, overwrite)?,
        None => DatasetWriter::create(dir, overwrite)?,
    };
    let mut records = Vec::with_capacity(sources.len());
    let mut failures = Vec::new();
    let indexed: Vec<(u32, &AssetSource)> = (0u32..).zip(sources).collect();
    for batch in indexed.chunks(BATCH_ASSETS) {
        let made: Vec<Result<Made, String>> =
            batch.par_iter().map(|&(index, source)| asset_items(&config, index, source)).collect();
        for (&(index, source), made) in batch.iter().zip(made) {
            let mut record = asset_record(root, index, source)?;
            match made {
                Ok(Made::Pairs(pairs)) => {
                    for pair in &pairs {
                        writer.write_scanned(&pair.pair, &pair.images)?;
                        progress(writer.len());
                    }
                }
                Ok(Made::Sets(sets)) => {
                    for set in &sets {
                        writer.write_set(&set.set, &set.images)?;
                        progress(writer.len());
                    }
                }
                Err(error) => {
                    failures.push((record.path.clone(), error.clone()));
                    record.error = Some(error);
                }
            }
            records.push(record);
        }
    }
    let mut origin = dataset_origin(&config, None);
    origin.assets = records;
    Ok(AssetDataset { manifest: writer.finish(origin)?, failures })
}

/// What one asset gave: its pairs, or its sets in a set dataset.
enum Made {
    Pairs(Vec<GeneratedPair>),
    Sets(Vec<GeneratedSet>),
}

/// The pairs (or sets) of one asset, or its error as text.
fn asset_items(config: &GeneratorConfig, index: u32, source: &AssetSource) -> Result<Made, String> {
    let imported = source.loaded.as_ref().map_err(ToString::to_string)?;
    if config.sets.is_some() {
        return sets_of_object(config, &imported.object, index, true)
            .map(Made::Sets)
            .map_err(|e| e.to_string());
    }
    let variant = Variant { index: 0, kind: config.kind, images: true };
    pairs_of_object(config, &imported.object, index, variant)
        .map(Made::Pairs)
        .map_err(|e| e.to_string())
}

/// The manifest record of an asset: its files' sizes and checksums (error not yet set).
fn asset_record(
    root: &Path,
    index: u32,
    source: &AssetSource,
) -> Result<AssetRecord, GenerateError> {
    // An asset that could not be read may not be readable for a checksum either; it is
    // recorded with an empty one rather than failing the whole dataset.
    let file = match (FileEntry::of(&source.path), &source.loaded) {
        (Ok(file), _) => file,
        (Err(_), Err(_)) => FileEntry { bytes: 0, sha256: String::new() },
        (Err(e), Ok(_)) => return Err(e.into()),
    };
    let mut files = std::collections::BTreeMap::new();
    if let Ok(imported) = &source.loaded {
        for f in &imported.files {
            files.insert(relative(root, f), FileEntry::of(f)?);
        }
    }
    Ok(AssetRecord {
        path: relative(root, &source.path),
        object_id: index,
        file,
        files,
        error: None,
    })
}

/// `path` relative to `root` (or to its folder when `root` is a file) with `/`
/// separators; the full path when it lies outside.
pub fn relative(root: &Path, path: &Path) -> String {
    let base = if root.is_file() { root.parent().unwrap_or(Path::new("")) } else { root };
    match path.strip_prefix(base) {
        Ok(inner) => inner
            .components()
            .map(|c| c.as_os_str().to_string_lossy())
            .collect::<Vec<_>>()
            .join("/"),
        Err(_) => path.display().to_string(),
    }
}
