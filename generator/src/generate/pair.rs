//! One labelled pair of an object: its two states posed, observed (sampled, or scanned from
//! a viewpoint that shows every part), checked for the parts' point counts, and labelled
//! with the ground truth.

use pairs::math::{Isometry3, Real};
use pairs::parts::part_sizes;
use pairs::scan::{PairImages, ScanImages};
use pairs::{Cloud, Pair, PairInput, Pose, Provenance, Scan, Scans};

use crate::config::GeneratorConfig;
use crate::label::{cross_ground_truth, ground_truth, merge_links, parts_by_values, Parts, Side};
use crate::protocol::global_pose;
use articulated::kinematics::link_poses;
use articulated::objects::ArticulatedObject;
use articulated::sampling::{SurfacePoint, SurfaceSampler};
use articulated::seed::{rng_for, Rng, Stream};
use scanner::visibility::is_visible;
use scanner::{images, scan_side, Requirements, ScannedSide, SURFACE_TOLERANCE};

use super::{GenerateError, GeneratedPair, Variant};
use articulated::GENERATOR_VERSION;

/// One object of a dataset and what every pair of it needs.
pub(super) struct Scene<'a> {
    pub(super) config: &'a GeneratorConfig,
    pub(super) object: &'a ArticulatedObject,
    pub(super) sampler: &'a SurfaceSampler,
    pub(super) index: u32,
    pub(super) variant: Variant,
    /// The second object Q observes in a cross-instance pair; `None` when Q observes
    /// `object` too.
    pub(super) partner: Option<Partner<'a>>,
}

/// The second instance of a cross-instance pair: another object of the same category with
/// the same links and joints by name, built from its own seed.
#[derive(Clone, Copy)]
pub(super) struct Partner<'a> {
    pub(super) object: &'a ArticulatedObject,
    pub(super) sampler: &'a SurfaceSampler,
    /// The seed that built it (object `index` of the dataset's config with this seed).
    pub(super) seed: u64,
}

/// One articulation state: its index among the object's states and its joint values.
pub(super) struct State<'a> {
    pub(super) index: usize,
    pub(super) values: &'a [Real],
}

/// One observed side of a pair: its points as surface samples, and its scan if scanned.
pub(super) struct Observation {
    pub(super) samples: Vec<SurfacePoint>,
    pub(super) scan: Option<ScannedSide>,
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
pub(super) fn make_pair(
    scene: &Scene,
    (pair_index, candidate): (usize, u32),
    state_p: State,
    state_q: State,
    rng: &mut Rng,
) -> Result<Option<GeneratedPair>, GenerateError> {
    let Scene { config, object, sampler, index: object_index, variant, partner } = *scene;
    // Q's object: the same one, or the second instance of a cross-instance pair.
    let (object_q, sampler_q) = partner.map_or((object, sampler), |o| (o.object, o.sampler));
    let (values_p, values_q) = (state_p.values, state_q.values);
    let n = config.points as usize;
    let pose = |object: &ArticulatedObject, values: &[Real], rng: &mut Rng| {
        let global =
            global_pose(config.pose_rotation_deg as Real, config.pose_translation as Real, rng);
        let links = link_poses(object, values).into_iter().map(|l| global * l).collect::<Vec<_>>();
        (global, links)
    };
    let (global_p, poses_p) = pose(object, values_p, rng);
    let (global_q, poses_q) = pose(object_q, values_q, rng);
    let motions: Vec<Isometry3> =
        poses_q.iter().zip(&poses_p).map(|(q, p)| q * p.inverse()).collect();
    let (scan_p, scan_q) = (variant.kind.scanned_p(), variant.kind.scanned_q());
    let id = pair_id(variant, object_index, pair_index);
    let link_parts = |size: Real| match partner {
        Some(_) => parts_by_values(object, values_p, values_q),
        None => merge_links(&motions, size),
    };
    let (obs_p, obs_q, parts) = if scan_q {
        // Parts come first: the scanner checks that every part is seen.
        let parts = link_parts(object_size(object, &poses_p)?);
        let mut scan_rng =
            rng_for(config.seed, u64::from(object_index), Stream::Scan(candidate, variant.index));
        let Some(p) = (if scan_p {
            observe_side(config, (object, sampler), &poses_p, Some(&parts), &mut scan_rng)?
        } else {
            observe_side(config, (object, sampler), &poses_p, None, rng)?
        }) else {
            return Ok(None);
        };
        let Some(q) =
            observe_side(config, (object_q, sampler_q), &poses_q, Some(&parts), &mut scan_rng)?
        else {
            return Ok(None);
        };
        (p, q, Some(parts))
    } else {
        let samples_p = sampler.sample(object, n, rng);
        let samples_q = sampler_q.sample(object_q, n, rng);
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
    let parts = parts.unwrap_or_else(|| link_parts(cloud_p.normalisation.scale));
    let p = Side { samples: &obs_p.samples, poses: &poses_p, values: values_p, cloud: &cloud_p };
    let q = Side { samples: &obs_q.samples, poses: &poses_q, values: values_q, cloud: &cloud_q };
    let truth = match partner {
        Some(_) => cross_ground_truth((object, object_q), &p, &q, &parts),
        None => ground_truth(object, &p, &q, &parts, &presence(&obs_p, &obs_q, &poses_q)),
    };
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
        seed_q: partner.map(|o| o.seed),
        generator_version: GENERATOR_VERSION.into(),
        joints_p: object.configuration(values_p),
        joints_q: object_q.configuration(values_q),
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
pub(super) fn pair_id(variant: Variant, object: u32, pair: usize) -> String {
    let kind = variant.kind.as_str().to_lowercase();
    match variant.index {
        0 => format!("{kind}-{object:05}-{pair}"),
        v => format!("{kind}-{object:05}-{pair}-v{v}"),
    }
}

/// The diagonal of the posed object's bounding box (no ray-casting mesh needed).
pub(super) fn object_size(
    object: &ArticulatedObject,
    poses: &[Isometry3],
) -> Result<Real, GenerateError> {
    let posed = object
        .links
        .iter()
        .zip(poses)
        .flat_map(|(l, pose)| l.mesh.vertices.iter().map(move |v| pose * v));
    Ok(pairs::math::bounds(posed).map_or(0.0, |(min, max)| (max - min).norm()))
}

/// One side's points of `object`: N surface samples, or a scan when `parts` is given.
pub(super) fn observe_side(
    config: &GeneratorConfig,
    (object, sampler): (&ArticulatedObject, &SurfaceSampler),
    poses: &[Isometry3],
    parts: Option<&Parts>,
    rng: &mut Rng,
) -> Result<Option<Observation>, GenerateError> {
    let n = config.points as usize;
    let Some(parts) = parts else {
        return Ok(Some(Observation { samples: sampler.sample(object, n, rng), scan: None }));
    };
    let needs = Requirements {
        part_of_link: &parts.of_link,
        parts: parts.count(),
        points: n,
        min_part_points: config.min_part_points as usize,
    };
    let scanner = config.scanner();
    let scan = scan_side(object, sampler, poses, &scanner, &needs, rng)?;
    Ok(scan.map(|s| Observation { samples: s.samples.clone(), scan: Some(s) }))
}

/// Per point of P: whether its moved point is present in Q. Always for a full Q; for a
/// scanned Q, when it is a surface point (not a flying pixel) that Q's camera sees on Q's
/// posed mesh and whose pixel the scanner did not lose. The tolerance along the ray covers
/// P's own depth noise (three standard deviations).
pub(super) fn presence(p: &Observation, q: &Observation, poses_q: &[Isometry3]) -> Vec<bool> {
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
