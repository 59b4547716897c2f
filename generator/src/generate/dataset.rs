//! Whole datasets (or one shard of one): every object's pairs or sets made in parallel
//! batches and written in object order, and the manifest's record of what made them.

use std::path::Path;

use pairs::dataset::{DatasetOrigin, DatasetWriter, Manifest, Shard};
use pairs::DatasetError;
use rayon::prelude::*;

use crate::config::GeneratorConfig;
use crate::generate::set::{object_sets, GeneratedSet};
use crate::generate::{dataset_object_pairs, GenerateError, GeneratedPair};
use crate::shard::shard_objects;
use articulated::categories::split_table;
use articulated::GENERATOR_VERSION;

/// Objects generated in parallel before their pairs are written: bounds memory.
const BATCH_OBJECTS: usize = 32;

/// Generates a dataset into `dir` (the whole dataset, or only `shard` of it), calling
/// `progress` with the number of pairs written after each one. Existing output is kept
/// unless `overwrite`, and replaced only once the new dataset is complete.
pub fn generate_dataset(
    config: &GeneratorConfig,
    dir: &Path,
    overwrite: bool,
    shard: Option<Shard>,
    mut progress: impl FnMut(u64),
) -> Result<Manifest, GenerateError> {
    config.validate()?;
    if config.sets.is_some() {
        return generate_set_dataset(config, dir, overwrite, shard, progress);
    }
    let mut writer = DatasetWriter::create(dir, overwrite)?;
    let left_out = write_objects(
        config,
        shard,
        &mut writer,
        |i| dataset_object_pairs(config, i),
        |writer, pair: &GeneratedPair| writer.write_scanned(&pair.pair, &pair.images),
        &mut progress,
    )?;
    Ok(writer.finish(DatasetOrigin { left_out, ..dataset_origin(config, shard) })?)
}

/// [`generate_dataset`] for a set dataset: every object's sets, in object order; an object
/// that cannot give its sets (a scanned view misses a small part in every draw) is left
/// out and counted in the manifest's `left_out`.
fn generate_set_dataset(
    config: &GeneratorConfig,
    dir: &Path,
    overwrite: bool,
    shard: Option<Shard>,
    mut progress: impl FnMut(u64),
) -> Result<Manifest, GenerateError> {
    let mut writer = DatasetWriter::create_sets(dir, overwrite)?;
    let left_out = write_objects(
        config,
        shard,
        &mut writer,
        |i| match object_sets(config, i, true) {
            Err(GenerateError::TooFewSets { .. }) => Ok(None),
            other => other.map(Some),
        },
        |writer, set: &GeneratedSet| writer.write_set(&set.set, &set.images),
        &mut progress,
    )?;
    Ok(writer.finish(DatasetOrigin { left_out, ..dataset_origin(config, shard) })?)
}

/// Makes the items (pairs or sets) of the dataset's objects (or one shard's) in parallel
/// batches and writes them in object order; `make` gives `None` for an object left out,
/// counted per category in the returned map.
fn write_objects<T: Send>(
    config: &GeneratorConfig,
    shard: Option<Shard>,
    writer: &mut DatasetWriter,
    make: impl Fn(u32) -> Result<Option<Vec<T>>, GenerateError> + Sync,
    write: impl Fn(&mut DatasetWriter, &T) -> Result<(), DatasetError>,
    progress: &mut impl FnMut(u64),
) -> Result<std::collections::BTreeMap<String, u32>, GenerateError> {
    let objects: Vec<u32> = shard_objects(config.objects, shard)?.collect();
    let categories = config.categories()?;
    let mut left_out = std::collections::BTreeMap::new();
    for batch in objects.chunks(BATCH_OBJECTS) {
        let generated: Vec<Option<Vec<T>>> =
            batch.par_iter().map(|&i| make(i)).collect::<Result<_, _>>()?;
        for (&i, items) in batch.iter().zip(&generated) {
            let Some(items) = items else {
                let category = categories[i as usize % categories.len()].name;
                *left_out.entry(category.to_owned()).or_insert(0) += 1;
                continue;
            };
            for item in items {
                write(writer, item)?;
                progress(writer.len());
            }
        }
    }
    Ok(left_out)
}

/// The manifest's record of what made a dataset (or one shard of it).
pub fn dataset_origin(config: &GeneratorConfig, shard: Option<Shard>) -> DatasetOrigin {
    DatasetOrigin {
        generator_version: GENERATOR_VERSION.into(),
        seed: config.seed,
        config: serde_json::to_value(config.resolved()).expect("a config always serialises"),
        splits: split_table(),
        shard,
        assets: Vec::new(),
        left_out: Default::default(),
    }
}
