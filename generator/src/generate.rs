//! Generation of pairs and datasets: object -> states -> posed samples -> labelled pairs ->
//! dataset files, in parallel, deterministic per pair whatever the thread count.

use std::path::Path;

use pairs::dataset::{DatasetOrigin, DatasetWriter, Manifest, Shard};
use pairs::math::{Isometry3, Real};
use pairs::scan::PairImages;
use pairs::{DatasetError, Pair, PairError, PairKind};
use rand::Rng as _;
use rayon::prelude::*;

use crate::config::{ConfigError, GeneratorConfig};
use crate::label::{same_structure, Parts};
use crate::protocol::{candidate_pairs, draw_state};
use crate::shard::shard_objects;
use articulated::categories::split_table;
use articulated::objects::{ArticulatedObject, ObjectError};
use articulated::sampling::SurfaceSampler;
use articulated::seed::{rng_for, Rng, Stream};
use scanner::scene::SceneError;

mod pair;
mod set;

use pair::{make_pair, Partner, Scene, State};
pub use set::{object_sets, set_id, sets_of_object, GeneratedSet, SET_ATTEMPTS};

use articulated::GENERATOR_VERSION;

/// Objects generated in parallel before their pairs are written: bounds memory.
const BATCH_OBJECTS: usize = 32;

/// Second instances tried per object of a cross-instance set before the object is left
/// out: each is built from its own seed and kept when it has the same links and joints by
/// name and gives the pairs wanted.
pub const PARTNER_ATTEMPTS: u32 = 16;

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
    /// No second instance of the object's category could be matched to it part for part
    /// (cross-instance kinds).
    #[error("object {object} ({category}): none of {PARTNER_ATTEMPTS} other instances of its category has the same links and joints and gives the pairs wanted")]
    NoPartner {
        /// Object index.
        object: u32,
        /// Its category.
        category: String,
    },
    /// An object could not give a set: no draw of K distinct states had every set part
    /// seen in every view.
    #[error("object {object} ({category}): none of {SET_ATTEMPTS} draws of {views} distinct states gives a set whose every part has at least {min} points in every view; lower `sets.views` or `min_part_points`, or raise `points`")]
    TooFewSets {
        /// Object index.
        object: u32,
        /// Its category.
        category: String,
        /// Views per set.
        views: u32,
        /// The config's `min_part_points`.
        min: u32,
    },
    /// The pair of two views would merge links that the set keeps apart (a generator bug).
    #[error("object {object}: the pair of views {i} and {j} groups links across set parts")]
    SetParts {
        /// Object index.
        object: u32,
        /// View taken as P.
        i: usize,
        /// View taken as Q.
        j: usize,
    },
    /// A generated pair broke an invariant (a generator bug).
    #[error("generated an invalid pair: {0}")]
    Pair(#[from] PairError),
    /// A generated set broke an invariant (a generator bug).
    #[error("generated an invalid set: {0}")]
    Set(#[from] pairs::SetError),
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

/// The pairs of object `index` in one [`Variant`]. A cross-instance object without a
/// second instance to match is an error ([`GenerateError::NoPartner`]); datasets leave such
/// objects out instead ([`dataset_object_pairs`]).
pub fn object_pairs_with(
    config: &GeneratorConfig,
    index: u32,
    variant: Variant,
) -> Result<Vec<GeneratedPair>, GenerateError> {
    let object = build_object(config, index)?;
    if !variant.kind.cross_instance() {
        return pairs_of_object(config, &object, index, variant);
    }
    cross_pairs_of_object(config, &object, index, variant)?.ok_or_else(|| {
        GenerateError::NoPartner { object: index, category: object.category.clone() }
    })
}

/// The pairs object `index` contributes to a dataset: `None` when it is a cross-instance
/// object left out (no second instance of its category matched it part for part).
pub fn dataset_object_pairs(
    config: &GeneratorConfig,
    index: u32,
) -> Result<Option<Vec<GeneratedPair>>, GenerateError> {
    match object_pairs(config, index) {
        Err(GenerateError::NoPartner { .. }) => Ok(None),
        other => other.map(Some),
    }
}

/// The pairs of an already built `object` as object `index` of a dataset (user assets
/// come here with their object built by `assets`).
pub fn pairs_of_object(
    config: &GeneratorConfig,
    object: &ArticulatedObject,
    index: u32,
    variant: Variant,
) -> Result<Vec<GeneratedPair>, GenerateError> {
    pairs_with(config, object, None, index, variant)
}

/// The cross-instance pairs of `object` as object `index`: P observes it, Q the first of
/// [`PARTNER_ATTEMPTS`] second instances (object `index` of the config under a seed drawn
/// from [`Stream::Partner`]) that has the same links and joints by name and gives the
/// pairs wanted; `None` when none does.
pub fn cross_pairs_of_object(
    config: &GeneratorConfig,
    object: &ArticulatedObject,
    index: u32,
    variant: Variant,
) -> Result<Option<Vec<GeneratedPair>>, GenerateError> {
    for attempt in 0..PARTNER_ATTEMPTS {
        let seed = rng_for(config.seed, u64::from(index), Stream::Partner(attempt)).random();
        let other = build_object(&GeneratorConfig { seed, ..config.clone() }, index)?;
        if !same_structure(object, &other) {
            continue;
        }
        let sampler = SurfaceSampler::new(&other);
        let partner = Partner { object: &other, sampler: &sampler, seed };
        match pairs_with(config, object, Some(partner), index, variant) {
            Err(GenerateError::TooFewPairs { .. }) => continue,
            other => return other.map(Some),
        }
    }
    Ok(None)
}

/// The pairs of `object`, with Q observing `partner` in a cross-instance set. Q's states
/// are the partner's own (drawn from its seed's [`Stream::States`]), so that
/// `articulation_q` indexes them as `articulation_p` indexes P's.
fn pairs_with(
    config: &GeneratorConfig,
    object: &ArticulatedObject,
    partner: Option<Partner>,
    index: u32,
    variant: Variant,
) -> Result<Vec<GeneratedPair>, GenerateError> {
    let sampler = SurfaceSampler::new(object);
    let mut rng = rng_for(config.seed, u64::from(index), Stream::States);
    let states = draw_states(config, object, &mut rng);
    let partner_states = partner.map(|o| {
        draw_states(config, o.object, &mut rng_for(o.seed, u64::from(index), Stream::States))
    });
    let states_q = partner_states.as_deref().unwrap_or(&states);
    let wanted = config.pairs_per_object as usize;
    let mut pairs = Vec::with_capacity(wanted);
    let scene = Scene { config, object, sampler: &sampler, index, variant, partner };
    for (candidate, (i, j)) in candidate_pairs(&states, &mut rng).into_iter().enumerate() {
        if pairs.len() == wanted {
            break;
        }
        let candidate = candidate as u32;
        let mut rng = rng_for(config.seed, u64::from(index), Stream::Pair(candidate));
        let (p, q) =
            (State { index: i, values: &states[i] }, State { index: j, values: &states_q[j] });
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
