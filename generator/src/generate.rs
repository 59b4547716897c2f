//! Generation of pairs and datasets: object -> states -> posed samples -> labelled pairs ->
//! dataset files, in parallel, deterministic per pair whatever the thread count.

use std::path::Path;

use pairs::dataset::{DatasetOrigin, DatasetWriter, Manifest, Shard};
use pairs::math::{Isometry3, Real};
use pairs::scan::PairImages;
use pairs::{DatasetError, Pair, PairError, PairKind};
use rayon::prelude::*;

use crate::categories::split_table;
use crate::config::{ConfigError, GeneratorConfig};
use crate::label::Parts;
use crate::objects::{ArticulatedObject, ObjectError};
use crate::protocol::{candidate_pairs, draw_state};
use crate::sampling::SurfaceSampler;
use crate::scan::scene::SceneError;
use crate::seed::{rng_for, Rng, Stream};
use crate::shard::shard_objects;

mod pair;

use pair::{make_pair, Scene, State};

/// Version written into every pair's provenance and the manifest.
pub const GENERATOR_VERSION: &str = env!("CARGO_PKG_VERSION");

/// Objects generated in parallel before their pairs are written: bounds memory.
const BATCH_OBJECTS: usize = 32;

/// Why generation failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum GenerateError {
    /// The configuration is invalid.
    #[error("invalid config: {0}")]
    Config(#[from] ConfigError),
    /// A category built an object that breaks the model's rules.
    #[error("object {object}: {source}")]
    Object {
        /// Object index.
        object: u32,
        /// The broken rule.
        source: ObjectError,
    },
    /// An object could not give enough valid pairs (parts too small to be sampled).
    #[error("object {object} ({category}): only {found} of {wanted} pairs have every part with at least {min} points; raise `points` or lower `min_part_points`")]
    TooFewPairs {
        /// Object index.
        object: u32,
        /// Its category.
        category: String,
        /// Valid pairs found.
        found: usize,
        /// Pairs wanted.
        wanted: usize,
        /// The config's `min_part_points`.
        min: u32,
    },
    /// A generated pair broke an invariant (a generator bug).
    #[error("generated an invalid pair: {0}")]
    Pair(#[from] PairError),
    /// Writing the dataset failed.
    #[error(transparent)]
    Dataset(#[from] DatasetError),
    /// The posed object could not be ray cast.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// Encoding a scan's images failed.
    #[error("encoding a scan image: {0}")]
    Image(#[from] image::ImageError),
    /// A shard was asked for that does not exist, or shards do not fit together.
    #[error(transparent)]
    Shard(#[from] crate::shard::ShardError),
}

/// A generated pair with the scene it was made from, for checks against the meshes.
#[derive(Debug, Clone)]
pub struct GeneratedPair {
    /// The pair.
    pub pair: Pair,
    /// Link poses of P's shape (rest frame to P's object frame, global pose included).
    pub poses_p: Vec<Isometry3>,
    /// Link poses of Q's shape.
    pub poses_q: Vec<Isometry3>,
    /// Which links form which part.
    pub parts: Parts,
    /// PNG images of the scanned sides (empty for full shapes, or when not asked for).
    pub images: PairImages,
}

/// Builds object `index` of a dataset: its category comes in turn from the config.
pub fn build_object(
    config: &GeneratorConfig,
    index: u32,
) -> Result<ArticulatedObject, GenerateError> {
    let categories = config.categories()?;
    let category = categories[index as usize % categories.len()];
    let object = (category.build)(&mut rng_for(config.seed, u64::from(index), Stream::Object));
    object.validate().map_err(|source| GenerateError::Object { object: index, source })?;
    Ok(object)
}

/// All pairs of object `index`, per the paper's protocol, with the images of their scans.
pub fn object_pairs(
    config: &GeneratorConfig,
    index: u32,
) -> Result<Vec<GeneratedPair>, GenerateError> {
    object_pairs_with(config, index, Variant { index: 0, kind: config.kind, images: true })
}

/// Which rendition of an object's pairs to make: the training stream makes several scanned
/// variants of the same shapes, each from its own viewpoints, without images.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Variant {
    /// 0 for a dataset's own pairs; 1, 2, ... for extra scanned renditions.
    pub index: u32,
    /// Kind of the pairs.
    pub kind: PairKind,
    /// Whether to encode the scans' PNG images.
    pub images: bool,
}

/// The pairs of object `index` in one [`Variant`].
pub fn object_pairs_with(
    config: &GeneratorConfig,
    index: u32,
    variant: Variant,
) -> Result<Vec<GeneratedPair>, GenerateError> {
    let object = build_object(config, index)?;
    pairs_of_object(config, &object, index, variant)
}

/// The pairs of an already built `object` as object `index` of a dataset (user assets
/// come here with their object built by `crate::import`).
pub fn pairs_of_object(
    config: &GeneratorConfig,
    object: &ArticulatedObject,
    index: u32,
    variant: Variant,
) -> Result<Vec<GeneratedPair>, GenerateError> {
    let sampler = SurfaceSampler::new(object);
    let mut rng = rng_for(config.seed, u64::from(index), Stream::States);
    let states = draw_states(config, object, &mut rng);
    let wanted = config.pairs_per_object as usize;
    let mut pairs = Vec::with_capacity(wanted);
    let scene = Scene { config, object, sampler: &sampler, index, variant };
    for (candidate, (i, j)) in candidate_pairs(&states, &mut rng).into_iter().enumerate() {
        if pairs.len() == wanted {
            break;
        }
        let candidate = candidate as u32;
        let mut rng = rng_for(config.seed, u64::from(index), Stream::Pair(candidate));
        let (p, q) =
            (State { index: i, values: &states[i] }, State { index: j, values: &states[j] });
        if let Some(pair) = make_pair(&scene, (pairs.len(), candidate), p, q, &mut rng)? {
            pairs.push(pair);
        }
    }
    if pairs.len() < wanted {
        return Err(GenerateError::TooFewPairs {
            object: index,
            category: object.category.clone(),
            found: pairs.len(),
            wanted,
            min: config.min_part_points,
        });
    }
    Ok(pairs)
}

/// The articulation states of object `index` (one value per joint each): the states its
/// pairs are drawn between, which `provenance.articulation_p` and `_q` index.
pub fn object_states(
    config: &GeneratorConfig,
    object: &ArticulatedObject,
    index: u32,
) -> Vec<Vec<Real>> {
    draw_states(config, object, &mut rng_for(config.seed, u64::from(index), Stream::States))
}

/// The object's states, drawn from `rng` (the start of its [`Stream::States`]).
fn draw_states(
    config: &GeneratorConfig,
    object: &ArticulatedObject,
    rng: &mut Rng,
) -> Vec<Vec<Real>> {
    (0..config.states_per_object)
        .map(|_| draw_state(object, config.rest_probability, rng))
        .collect()
}

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
    let objects: Vec<u32> = shard_objects(config.objects, shard)?.collect();
    let mut writer = DatasetWriter::create(dir, overwrite)?;
    for batch in objects.chunks(BATCH_OBJECTS) {
        let generated: Vec<Vec<GeneratedPair>> =
            batch.par_iter().map(|&i| object_pairs(config, i)).collect::<Result<_, _>>()?;
        for pair in generated.iter().flatten() {
            writer.write_scanned(&pair.pair, &pair.images)?;
            progress(writer.len());
        }
    }
    Ok(writer.finish(dataset_origin(config, shard))?)
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
    }
}

/// Every joint's value in one state, by joint name.
pub fn configuration(
    object: &ArticulatedObject,
    values: &[Real],
) -> std::collections::BTreeMap<String, Real> {
    object.joints.iter().zip(values).map(|(j, &v)| (j.name.clone(), v)).collect()
}
