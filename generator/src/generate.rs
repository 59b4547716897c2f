//! Generation of pairs and datasets: object -> states -> posed samples -> labelled pairs ->
//! dataset files, in parallel, deterministic per pair whatever the thread count.

use std::path::Path;

use pairs::dataset::{DatasetOrigin, DatasetWriter, Manifest, Shard};
use pairs::math::{Isometry3, Point3, Real};
use pairs::parts::part_sizes;
use pairs::scan::{PairImages, ScanImages};
use pairs::{
    Cloud, DatasetError, Pair, PairError, PairInput, PairKind, Pose, Provenance, Scan, Scans,
};
use rayon::prelude::*;

use crate::categories::split_table;
use crate::config::{ConfigError, GeneratorConfig};
use crate::kinematics::link_poses;
use crate::label::{ground_truth, merge_links, Parts, Side};
use crate::objects::{ArticulatedObject, ObjectError};
use crate::protocol::{candidate_pairs, draw_state, global_pose};
use crate::sampling::{SurfacePoint, SurfaceSampler};
use crate::scan::scene::SceneError;
use crate::scan::visibility::is_visible;
use crate::scan::{images, scan_side, Requirements, ScannedSide, SURFACE_TOLERANCE};
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

/// One object of a dataset and what every pair of it needs.
struct Scene<'a> {
    config: &'a GeneratorConfig,
    object: &'a ArticulatedObject,
    sampler: &'a SurfaceSampler,
    index: u32,
    variant: Variant,
}

/// One articulation state: its index among the object's states and its joint values.
struct State<'a> {
    index: usize,
    values: &'a [Real],
}

/// One observed side of a pair: its points as surface samples, and its scan if scanned.
struct Observation {
    samples: Vec<SurfacePoint>,
    scan: Option<ScannedSide>,
}

impl Observation {
    /// Per point: whether it is a flying pixel (never for a full shape).
    fn outlier(&self, i: usize) -> bool {
        self.scan.as_ref().is_some_and(|s| s.outlier[i])
    }

    /// Per point: the standard deviation of its depth noise (0 for a full shape).
    fn sigma(&self, i: usize) -> Real {
        self.scan.as_ref().map_or(0.0, |s| s.sigma[i])
    }
}

/// One pair between two states, or `None` if a part gets fewer than `min_part_points`
/// (or no viewpoint shows every part).
fn make_pair(
    scene: &Scene,
    (pair_index, candidate): (usize, u32),
    state_p: State,
    state_q: State,
    rng: &mut Rng,
) -> Result<Option<GeneratedPair>, GenerateError> {
    let Scene { config, object, sampler, index: object_index, variant } = *scene;
    let (values_p, values_q) = (state_p.values, state_q.values);
    let n = config.points as usize;
    let pose = |values: &[Real], rng: &mut Rng| {
        let global =
            global_pose(config.pose_rotation_deg as Real, config.pose_translation as Real, rng);
        let links = link_poses(object, values).into_iter().map(|l| global * l).collect::<Vec<_>>();
        (global, links)
    };
    let (global_p, poses_p) = pose(values_p, rng);
    let (global_q, poses_q) = pose(values_q, rng);
    let motions: Vec<Isometry3> =
        poses_q.iter().zip(&poses_p).map(|(q, p)| q * p.inverse()).collect();
    let (scan_p, scan_q) = match variant.kind {
        PairKind::Sf2f => (false, false),
        PairKind::Sf2p => (false, true),
        PairKind::Sp2p => (true, true),
    };
    let id = pair_id(variant, object_index, pair_index);
    let (obs_p, obs_q, parts) = if scan_q {
        // Parts come first: the scanner checks that every part is seen.
        let size = (object_size(object, &poses_p))?;
        let parts = merge_links(&motions, size);
        let mut scan_rng =
            rng_for(config.seed, u64::from(object_index), Stream::Scan(candidate, variant.index));
        let observe = |poses: &[Isometry3], scanned: bool, rng: &mut Rng| {
            observe_side(scene, poses, scanned.then_some(&parts), rng)
        };
        let Some(p) = observe(&poses_p, scan_p, if scan_p { &mut scan_rng } else { rng })? else {
            return Ok(None);
        };
        let Some(q) = observe(&poses_q, true, &mut scan_rng)? else {
            return Ok(None);
        };
        (p, q, Some(parts))
    } else {
        let samples_p = sampler.sample(object, n, rng);
        let samples_q = sampler.sample(object, n, rng);
        (
            Observation { samples: samples_p, scan: None },
            Observation { samples: samples_q, scan: None },
            None,
        )
    };
    let cloud = |obs: &Observation, poses: &[Isometry3]| {
        let points: Vec<_> = obs.samples.iter().map(|s| s.posed(poses)).collect();
        Cloud::normalise(&points)
    };
    let (Some(cloud_p), Some(cloud_q)) = (cloud(&obs_p, &poses_p), cloud(&obs_q, &poses_q)) else {
        return Ok(None);
    };
    let parts = parts.unwrap_or_else(|| merge_links(&motions, cloud_p.normalisation.scale));
    let present = presence(&obs_p, &obs_q, &poses_q);
    let p = Side { samples: &obs_p.samples, poses: &poses_p, values: values_p, cloud: &cloud_p };
    let q = Side { samples: &obs_q.samples, poses: &poses_q, values: values_q, cloud: &cloud_q };
    let truth = ground_truth(object, &p, &q, &parts, &present);
    let min = config.min_part_points as usize;
    let too_small = |ids: &[u8]| part_sizes(ids, parts.count()).into_iter().any(|s| s < min);
    if parts.count() < 2 || too_small(&truth.part_p) || too_small(&truth.part_q) {
        return Ok(None);
    }
    let input = PairInput { id: id.clone(), kind: variant.kind, p: cloud_p, q: cloud_q };
    let provenance = Provenance {
        category: object.category.clone(),
        object_id: object_index,
        articulation_p: state_p.index as u32,
        articulation_q: state_q.index as u32,
        seed: config.seed,
        generator_version: GENERATOR_VERSION.into(),
        joints_p: configuration(object, values_p),
        joints_q: configuration(object, values_q),
        pose_p: Some(Pose::of(&global_p)),
        pose_q: Some(Pose::of(&global_q)),
    };
    let record = |obs: &Observation, side: &str| {
        obs.scan.as_ref().map(|s| {
            let images = ScanImages::for_pair(&id, side);
            Scan::new(s.camera.intrinsics, &s.camera.pose, s.depth_scale, images)
        })
    };
    let scans = Scans { p: record(&obs_p, "p"), q: record(&obs_q, "q") };
    let pair = Pair::new(input, truth, provenance)?.with_scans(scans)?;
    let images = if variant.images {
        let encode = |obs: &Observation| {
            obs.scan
                .as_ref()
                .map(|s| images::encode(&s.render, &s.depth, &parts.of_link))
                .transpose()
        };
        PairImages { p: encode(&obs_p)?, q: encode(&obs_q)? }
    } else {
        PairImages::default()
    };
    Ok(Some(GeneratedPair { pair, poses_p, poses_q, parts, images }))
}

/// The id of a pair: kind, object, index within the object, and the variant past 0.
fn pair_id(variant: Variant, object: u32, pair: usize) -> String {
    let kind = variant.kind.as_str().to_lowercase();
    match variant.index {
        0 => format!("{kind}-{object:05}-{pair}"),
        v => format!("{kind}-{object:05}-{pair}-v{v}"),
    }
}

/// The diagonal of the posed object's bounding box (no ray-casting mesh needed).
fn object_size(object: &ArticulatedObject, poses: &[Isometry3]) -> Result<Real, GenerateError> {
    let (min, max) = object
        .links
        .iter()
        .zip(poses)
        .flat_map(|(l, pose)| l.mesh.vertices.iter().map(move |v| pose * v))
        .fold((Point3::from([Real::MAX; 3]), Point3::from([Real::MIN; 3])), |(lo, hi), v| {
            (lo.inf(&v), hi.sup(&v))
        });
    Ok((max - min).norm())
}

/// One side's points: N surface samples, or a scan when `parts` is given.
fn observe_side(
    scene: &Scene,
    poses: &[Isometry3],
    parts: Option<&Parts>,
    rng: &mut Rng,
) -> Result<Option<Observation>, GenerateError> {
    let n = scene.config.points as usize;
    let Some(parts) = parts else {
        return Ok(Some(Observation {
            samples: scene.sampler.sample(scene.object, n, rng),
            scan: None,
        }));
    };
    let needs = Requirements {
        part_of_link: &parts.of_link,
        parts: parts.count(),
        points: n,
        min_part_points: scene.config.min_part_points as usize,
    };
    let scanner = scene.config.scanner();
    let scan = scan_side(scene.object, scene.sampler, poses, &scanner, &needs, rng)?;
    Ok(scan.map(|s| Observation { samples: s.samples.clone(), scan: Some(s) }))
}

/// Per point of P: whether its moved point is present in Q. Always for a full Q; for a
/// scanned Q, when it is a surface point (not a flying pixel) that Q's camera sees on Q's
/// posed mesh and whose pixel the scanner did not lose. The tolerance along the ray covers
/// P's own depth noise (three standard deviations).
fn presence(p: &Observation, q: &Observation, poses_q: &[Isometry3]) -> Vec<bool> {
    let Some(scan) = &q.scan else {
        return vec![true; p.samples.len()];
    };
    let surface = SURFACE_TOLERANCE * scan.scene.diagonal();
    p.samples
        .iter()
        .enumerate()
        .map(|(i, s)| {
            !p.outlier(i)
                && is_visible(
                    &scan.scene,
                    &scan.camera,
                    &s.posed(poses_q),
                    surface + 3.0 * p.sigma(i),
                    Some(&scan.lost),
                )
        })
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
