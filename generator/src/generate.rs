//! Generation of pairs and datasets: object -> states -> posed samples -> labelled pairs ->
//! dataset files, in parallel, deterministic per pair whatever the thread count.

use std::path::Path;

use pairs::dataset::{DatasetOrigin, DatasetWriter, Manifest, Shard};
use pairs::math::{Isometry3, Real};
use pairs::parts::part_sizes;
use pairs::{Cloud, DatasetError, Pair, PairError, PairInput, Provenance};
use rayon::prelude::*;

use crate::categories::split_table;
use crate::config::{ConfigError, GeneratorConfig};
use crate::kinematics::link_poses;
use crate::label::{ground_truth, merge_links, Parts, Side};
use crate::objects::{ArticulatedObject, ObjectError};
use crate::protocol::{candidate_pairs, draw_state, global_pose};
use crate::sampling::SurfaceSampler;
use crate::seed::{rng_for, Rng, Stream};
use crate::shard::shard_objects;

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

/// All pairs of object `index`, per the paper's protocol.
pub fn object_pairs(
    config: &GeneratorConfig,
    index: u32,
) -> Result<Vec<GeneratedPair>, GenerateError> {
    let object = build_object(config, index)?;
    let sampler = SurfaceSampler::new(&object);
    let mut rng = rng_for(config.seed, u64::from(index), Stream::States);
    let states: Vec<Vec<Real>> = (0..config.states_per_object)
        .map(|_| draw_state(&object, config.rest_probability, &mut rng))
        .collect();
    let wanted = config.pairs_per_object as usize;
    let mut pairs = Vec::with_capacity(wanted);
    let scene = Scene { config, object: &object, sampler: &sampler, index };
    for (candidate, (i, j)) in candidate_pairs(&states, &mut rng).into_iter().enumerate() {
        if pairs.len() == wanted {
            break;
        }
        let mut rng = rng_for(config.seed, u64::from(index), Stream::Pair(candidate as u32));
        let (p, q) =
            (State { index: i, values: &states[i] }, State { index: j, values: &states[j] });
        if let Some(pair) = make_pair(&scene, pairs.len(), p, q, &mut rng)? {
            pairs.push(pair);
        }
    }
    if pairs.len() < wanted {
        return Err(GenerateError::TooFewPairs {
            object: index,
            category: object.category,
            found: pairs.len(),
            wanted,
            min: config.min_part_points,
        });
    }
    Ok(pairs)
}

/// One object of a dataset and what every pair of it needs.
struct Scene<'a> {
    config: &'a GeneratorConfig,
    object: &'a ArticulatedObject,
    sampler: &'a SurfaceSampler,
    index: u32,
}

/// One articulation state: its index among the object's states and its joint values.
struct State<'a> {
    index: usize,
    values: &'a [Real],
}

/// One pair between two states, or `None` if a part gets fewer than `min_part_points`.
fn make_pair(
    scene: &Scene,
    pair_index: usize,
    state_p: State,
    state_q: State,
    rng: &mut Rng,
) -> Result<Option<GeneratedPair>, GenerateError> {
    let Scene { config, object, sampler, index: object_index } = *scene;
    let (values_p, values_q) = (state_p.values, state_q.values);
    let n = config.points as usize;
    let pose = |values: &[Real], rng: &mut Rng| {
        let global =
            global_pose(config.pose_rotation_deg as Real, config.pose_translation as Real, rng);
        link_poses(object, values).into_iter().map(|l| global * l).collect::<Vec<_>>()
    };
    let poses_p = pose(values_p, rng);
    let poses_q = pose(values_q, rng);
    let samples_p = sampler.sample(object, n, rng);
    let samples_q = sampler.sample(object, n, rng);
    let cloud = |samples: &[crate::sampling::SurfacePoint], poses: &[Isometry3]| {
        let points: Vec<_> = samples.iter().map(|s| s.posed(poses)).collect();
        Cloud::normalise(&points)
    };
    let (Some(cloud_p), Some(cloud_q)) = (cloud(&samples_p, &poses_p), cloud(&samples_q, &poses_q))
    else {
        return Ok(None);
    };
    let motions: Vec<Isometry3> =
        poses_q.iter().zip(&poses_p).map(|(q, p)| q * p.inverse()).collect();
    let parts = merge_links(&motions, cloud_p.normalisation.scale);
    let p = Side { samples: &samples_p, poses: &poses_p, values: values_p, cloud: &cloud_p };
    let q = Side { samples: &samples_q, poses: &poses_q, values: values_q, cloud: &cloud_q };
    let truth = ground_truth(object, &p, &q, &parts);
    let min = config.min_part_points as usize;
    let too_small = |ids: &[u8]| part_sizes(ids, parts.count()).into_iter().any(|s| s < min);
    if parts.count() < 2 || too_small(&truth.part_p) || too_small(&truth.part_q) {
        return Ok(None);
    }
    let input = PairInput {
        id: format!("{}-{object_index:05}-{pair_index}", config.kind.as_str().to_lowercase()),
        kind: config.kind,
        p: cloud_p,
        q: cloud_q,
    };
    let provenance = Provenance {
        category: object.category.clone(),
        object_id: object_index,
        articulation_p: state_p.index as u32,
        articulation_q: state_q.index as u32,
        seed: config.seed,
        generator_version: GENERATOR_VERSION.into(),
    };
    let pair = Pair::new(input, truth, provenance)?;
    Ok(Some(GeneratedPair { pair, poses_p, poses_q, parts }))
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
            writer.write(&pair.pair)?;
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
        config: serde_json::to_value(config).expect("a config always serialises"),
        splits: split_table(),
        shard,
    }
}
