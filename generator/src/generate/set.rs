//! Sets of K observations of one object in K distinct articulation states (the
//! MultiBodySync setting): each view posed and observed on its own (a full shape or a scan
//! that shows every set part), labelled with set parts consistent across all K, and with
//! what every pair of views needs to give the pair generator's ground truth
//! ([`pairs::Set::pair`]).

use pairs::math::{Isometry3, Real};
use pairs::parts::part_sizes;
use pairs::scan::ScanImages;
use pairs::set::{SetJoint, SetProvenance, SetTruth, ViewProvenance};
use pairs::{Cloud, Pose, Scan, Set, SetInput, Similarity, View, ViewKind};
use rand::seq::SliceRandom;

use crate::config::{GeneratorConfig, SetsConfig};
use crate::label::{merge_links, merge_links_over, Parts};
use crate::protocol::global_pose;
use articulated::kinematics::link_poses;
use articulated::objects::ArticulatedObject;
use articulated::sampling::SurfaceSampler;
use articulated::seed::{rng_for, Stream};
use scanner::images;

use super::object::set_states;
use super::pair::{object_size, observe_side, presence, Observation};
use super::{build_object, GenerateError};
use articulated::GENERATOR_VERSION;

/// Draws of K states tried per set before the object is declared unable to give it.
pub const SET_ATTEMPTS: u32 = 32;

/// A generated set with the scene it was made from, for checks against the pair generator.
#[derive(Debug, Clone)]
pub struct GeneratedSet {
    /// The set.
    pub set: Set,
    /// Per view: the link poses (rest frame to the view's object frame, global pose
    /// included).
    pub poses: Vec<Vec<Isometry3>>,
    /// Per view: the link of every point.
    pub links: Vec<Vec<usize>>,
    /// Which links form which set part.
    pub parts: Parts,
    /// Per view: the PNG images of a scanned view (`None` for a full view, or when images
    /// were not asked for).
    pub images: Vec<Option<ScanImages<Vec<u8>>>>,
}

/// The sets of object `index` of a set dataset (`config.sets` must be present).
pub fn object_sets(
    config: &GeneratorConfig,
    index: u32,
    with_images: bool,
) -> Result<Vec<GeneratedSet>, GenerateError> {
    sets_of_object(config, &build_object(config, index)?, index, with_images)
}

/// The sets of an already built `object` as object `index` of a set dataset (user assets
/// come here with their object built by `assets`).
pub fn sets_of_object(
    config: &GeneratorConfig,
    object: &ArticulatedObject,
    index: u32,
    with_images: bool,
) -> Result<Vec<GeneratedSet>, GenerateError> {
    let sets = config.sets.clone().unwrap_or_default();
    let sampler = SurfaceSampler::new(object);
    let states = set_states(config, object, index, sets.views as usize);
    let k = sets.views as usize;
    let mut made = Vec::with_capacity(sets.per_object as usize);
    for s in 0..sets.per_object {
        let mut rng = rng_for(config.seed, u64::from(index), Stream::Set(s));
        let mut found = None;
        for attempt in 0..SET_ATTEMPTS {
            let mut order: Vec<usize> = (0..states.len()).collect();
            order.shuffle(&mut rng);
            let mut chosen: Vec<usize> = Vec::with_capacity(k);
            for i in order {
                if chosen.iter().all(|&c| states[c] != states[i]) {
                    chosen.push(i);
                }
            }
            if chosen.len() < k {
                break;
            }
            chosen.truncate(k);
            let scene = SetScene { config, sets: &sets, object, sampler: &sampler, index };
            let candidate = s * SET_ATTEMPTS + attempt;
            if let Some(set) = make_set(&scene, (s, candidate), &chosen, &states, with_images)? {
                found = Some(set);
                break;
            }
        }
        match found {
            Some(set) => made.push(set),
            None => {
                return Err(GenerateError::TooFewSets {
                    object: index,
                    category: object.category.clone(),
                    views: sets.views,
                    min: config.min_part_points,
                })
            }
        }
    }
    Ok(made)
}

/// One object of a set dataset and what every set of it needs.
struct SetScene<'a> {
    config: &'a GeneratorConfig,
    sets: &'a SetsConfig,
    object: &'a ArticulatedObject,
    sampler: &'a SurfaceSampler,
    index: u32,
}

/// The id of a set: mode, views, object, index within the object.
pub fn set_id(sets: &SetsConfig, object: u32, set: u32) -> String {
    format!("{}-k{}-{object:05}-{set}", sets.mode.as_str(), sets.views)
}

/// The K views of one candidate set, posed and observed, before labelling.
struct ObservedSet {
    /// Index of the set among the object's sets.
    set_index: u32,
    /// Each view's state index.
    chosen: Vec<usize>,
    /// Each view's global pose.
    globals: Vec<Isometry3>,
    /// Each view's link poses.
    poses: Vec<Vec<Isometry3>>,
    /// `motions_from_0[k][link]`: each link's motion from view 0's pose to view k's.
    motions_from_0: Vec<Vec<Isometry3>>,
    /// The set parts.
    parts: Parts,
    /// Each view's samples (and scan).
    observations: Vec<Observation>,
    /// Each view's cloud.
    clouds: Vec<Cloud>,
    /// Each view's set part per point.
    labels: Vec<Vec<u8>>,
}

/// One set of the given states, or `None` if a view misses a set part (too few points, no
/// viewpoint shows every part) or the states leave fewer than two set parts.
fn make_set(
    scene: &SetScene,
    (set_index, candidate): (u32, u32),
    chosen: &[usize],
    states: &[Vec<Real>],
    with_images: bool,
) -> Result<Option<GeneratedSet>, GenerateError> {
    match observe_set(scene, (set_index, candidate), chosen, states)? {
        Some(observed) => label_set(scene, observed, states, with_images).map(Some),
        None => Ok(None),
    }
}

/// Poses and observes the views of a candidate set; `None` as [`make_set`] says.
fn observe_set(
    scene: &SetScene,
    (set_index, candidate): (u32, u32),
    chosen: &[usize],
    states: &[Vec<Real>],
) -> Result<Option<ObservedSet>, GenerateError> {
    let SetScene { config, sets, object, sampler, index } = *scene;
    let k = chosen.len();
    let mode = sets.mode;
    let mut rngs: Vec<_> = (0..k)
        .map(|v| rng_for(config.seed, u64::from(index), Stream::View(candidate, v as u32)))
        .collect();
    let mut globals = Vec::with_capacity(k);
    let mut poses: Vec<Vec<Isometry3>> = Vec::with_capacity(k);
    for (v, rng) in rngs.iter_mut().enumerate() {
        let global =
            global_pose(config.pose_rotation_deg as Real, config.pose_translation as Real, rng);
        let links = link_poses(object, &states[chosen[v]]);
        poses.push(links.into_iter().map(|l| global * l).collect());
        globals.push(global);
    }
    let motions_from_0: Vec<Vec<Isometry3>> = poses
        .iter()
        .map(|p| p.iter().zip(&poses[0]).map(|(q, p0)| q * p0.inverse()).collect())
        .collect();
    let parts = merge_links_over(&motions_from_0[1..], object_size(object, &poses[0])?);
    if parts.count() < 2 {
        return Ok(None);
    }
    let mut observations: Vec<Observation> = Vec::with_capacity(k);
    for (v, rng) in rngs.iter_mut().enumerate() {
        let scanned = mode.view(v) == ViewKind::Scan;
        let needs = scanned.then_some(&parts);
        let Some(obs) = observe_side(config, (object, sampler), &poses[v], needs, rng)? else {
            return Ok(None);
        };
        observations.push(obs);
    }
    let mut clouds: Vec<Cloud> = Vec::with_capacity(k);
    for (obs, p) in observations.iter().zip(&poses) {
        let points: Vec<_> = obs.samples.iter().map(|s| s.posed(p)).collect();
        let Some(cloud) = Cloud::normalise(&points) else { return Ok(None) };
        clouds.push(cloud);
    }
    let labels: Vec<Vec<u8>> = observations
        .iter()
        .map(|o| o.samples.iter().map(|s| parts.of_link[s.link]).collect())
        .collect();
    let min = config.min_part_points as usize;
    if labels.iter().any(|l| part_sizes(l, parts.count()).into_iter().any(|n| n < min)) {
        return Ok(None);
    }
    Ok(Some(ObservedSet {
        set_index,
        chosen: chosen.to_vec(),
        globals,
        poses,
        motions_from_0,
        parts,
        observations,
        clouds,
        labels,
    }))
}

/// The set record of observed views.
fn label_set(
    scene: &SetScene,
    observed: ObservedSet,
    states: &[Vec<Real>],
    with_images: bool,
) -> Result<GeneratedSet, GenerateError> {
    let SetScene { config, sets, object, index, .. } = *scene;
    let ObservedSet {
        set_index,
        chosen,
        globals,
        poses,
        motions_from_0,
        parts,
        observations,
        clouds,
        labels,
    } = observed;
    let (k, mode) = (chosen.len(), sets.mode);
    let norm0 = clouds[0].normalisation;
    // View 0's motions are the identity exactly (its link motions to itself only round).
    let motions: Vec<Vec<Similarity>> = (0..k)
        .map(|v| {
            if v == 0 {
                return vec![Similarity::identity(); parts.count()];
            }
            parts
                .first_link
                .iter()
                .map(|&l| {
                    Similarity::between_normalised(
                        &motions_from_0[v][l],
                        &norm0,
                        &clouds[v].normalisation,
                    )
                })
                .collect()
        })
        .collect();
    let flows = motions
        .iter()
        .map(|m| {
            clouds[0]
                .points
                .iter()
                .zip(&labels[0])
                .map(|(x, &s)| m[usize::from(s)].apply(x) - x)
                .collect()
        })
        .collect();
    let mut presences = Vec::with_capacity(k);
    let mut pair_parts = Vec::with_capacity(k);
    for i in 0..k {
        let mut presence_row = Vec::with_capacity(k);
        let mut groups_row = Vec::with_capacity(k);
        for j in 0..k {
            if i == j {
                presence_row.push(vec![true; clouds[i].len()]);
                groups_row.push((0..parts.count() as u8).collect());
                continue;
            }
            presence_row.push(presence(&observations[i], &observations[j], &poses[j]));
            // The pair generator's parts for P = view i, Q = view j (`make_pair`): links
            // merged by their motion between the two states, translations compared with the
            // posed object's size when Q is scanned (parts come before the scan) and with
            // P's cloud's otherwise.
            let size = match mode.view(j) {
                ViewKind::Scan => object_size(object, &poses[i])?,
                ViewKind::Full => clouds[i].normalisation.scale,
            };
            let link_motions: Vec<Isometry3> =
                poses[j].iter().zip(&poses[i]).map(|(q, p)| q * p.inverse()).collect();
            let pair = merge_links(&link_motions, size);
            let groups: Vec<u8> = parts.first_link.iter().map(|&l| pair.of_link[l]).collect();
            let coarser = (0..object.links.len())
                .all(|l| pair.of_link[l] == groups[usize::from(parts.of_link[l])]);
            if !coarser {
                return Err(GenerateError::SetParts { object: index, i, j });
            }
            groups_row.push(groups);
        }
        presences.push(presence_row);
        pair_parts.push(groups_row);
    }
    let joints = object
        .joints
        .iter()
        .enumerate()
        .filter(|(_, j)| parts.of_link[j.child] != parts.of_link[j.parent])
        .map(|(index, joint)| SetJoint {
            name: joint.name.clone(),
            part: parts.of_link[joint.child],
            parent: parts.of_link[joint.parent],
            kind: joint.kind,
            axis: poses
                .iter()
                .map(|p| pairs::math::unit_or(&(p[joint.parent].rotation * joint.axis), joint.axis))
                .collect(),
            pivot: poses
                .iter()
                .zip(&clouds)
                .map(|(p, c)| c.normalisation.apply(&(p[joint.parent] * joint.pivot)))
                .collect(),
            value: chosen.iter().map(|&s| states[s][index]).collect(),
        })
        .collect();
    let id = set_id(sets, index, set_index);
    let scans: Vec<Option<Scan>> = observations
        .iter()
        .enumerate()
        .map(|(v, o)| {
            o.scan.as_ref().map(|s| {
                let images = ScanImages::for_pair(&id, &format!("v{v}"));
                Scan::new(s.camera.intrinsics, &s.camera.pose, s.depth_scale, images)
            })
        })
        .collect();
    let images = observations
        .iter()
        .map(|o| match (&o.scan, with_images) {
            (Some(s), true) => images::encode(&s.render, &s.depth, &parts.of_link).map(Some),
            _ => Ok(None),
        })
        .collect::<Result<Vec<_>, _>>()?;
    let provenance = SetProvenance {
        category: object.category.clone(),
        object_id: index,
        set_index,
        seed: config.seed,
        generator_version: GENERATOR_VERSION.into(),
        views: chosen
            .iter()
            .zip(&globals)
            .map(|(&s, g)| ViewProvenance {
                articulation: s as u32,
                joints: object.configuration(&states[s]),
                pose: Some(Pose::of(g)),
            })
            .collect(),
    };
    let views = clouds
        .into_iter()
        .enumerate()
        .map(|(v, cloud)| View { kind: mode.view(v), cloud })
        .collect();
    let truth = SetTruth { parts: labels, motions, flows, presence: presences, pair_parts, joints };
    let set = Set::new(SetInput { id, views }, truth, provenance, scans)?;
    let links = observations.iter().map(|o| o.samples.iter().map(|s| s.link).collect()).collect();
    Ok(GeneratedSet { set, poses, links, parts, images })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::label::{ground_truth, Side};
    use articulated::categories::Split;
    use pairs::SetMode;

    fn config(mode: SetMode, views: u32) -> GeneratorConfig {
        GeneratorConfig {
            objects: 6,
            points: 256,
            seed: 11,
            split: Split::Test,
            sets: Some(SetsConfig { views, mode, per_object: 1 }),
            ..Default::default()
        }
    }

    /// A set's states begin with the object's (the pairs' states), and run on until K of
    /// them are distinct, even when most are at rest.
    #[test]
    fn set_states_extend_the_objects_states() {
        let config = GeneratorConfig { rest_probability: 0.6, ..config(SetMode::Full, 6) };
        for index in 0..8 {
            let object = build_object(&config, index).expect("an object");
            let states = set_states(&config, &object, index, 6);
            let first = crate::generate::object_states(&config, &object, index);
            assert_eq!(states[..first.len()], first[..]);
            let distinct = states.iter().enumerate().filter(|(i, s)| !states[..*i].contains(s));
            assert!(distinct.count() >= 6, "object {index}: {} states", states.len());
        }
    }

    /// Every pair of views of a set has the ground truth the pair generator's labelling
    /// gives the same two observations: the same parts, correspondences and joints, and
    /// the same motions and flow up to the composition's rounding.
    #[test]
    fn every_pair_of_views_is_the_pair_generators_pair() {
        let mut merged = 0;
        for (mode, views) in [(SetMode::Full, 4), (SetMode::Mixed, 3), (SetMode::Scan, 3)] {
            let config = config(mode, views);
            let sets = config.sets.clone().expect("a set config");
            let mut checked = 0;
            for index in 0..config.objects {
                let object = build_object(&config, index).expect("an object");
                let sampler = SurfaceSampler::new(&object);
                let states = set_states(&config, &object, index, views as usize);
                let scene = SetScene {
                    config: &config,
                    sets: &sets,
                    object: &object,
                    sampler: &sampler,
                    index,
                };
                let chosen: Vec<usize> = {
                    let mut c: Vec<usize> = Vec::new();
                    for i in 0..states.len() {
                        if c.iter().all(|&j| states[j] != states[i]) {
                            c.push(i);
                        }
                    }
                    c.truncate(views as usize);
                    c
                };
                let Some(observed) =
                    observe_set(&scene, (0, 0), &chosen, &states).expect("observes")
                else {
                    continue;
                };
                let again = observe_set(&scene, (0, 0), &chosen, &states).expect("observes");
                let generated = label_set(&scene, again.expect("deterministic"), &states, false)
                    .expect("labels");
                let set = &generated.set;
                let o = &observed;
                for i in 0..chosen.len() {
                    for j in 0..chosen.len() {
                        if i == j
                            || (mode.view(i), mode.view(j)) == (ViewKind::Scan, ViewKind::Full)
                        {
                            continue;
                        }
                        let size = match mode.view(j) {
                            ViewKind::Scan => object_size(&object, &o.poses[i]).expect("size"),
                            ViewKind::Full => o.clouds[i].normalisation.scale,
                        };
                        let motions: Vec<Isometry3> = o.poses[j]
                            .iter()
                            .zip(&o.poses[i])
                            .map(|(q, p)| q * p.inverse())
                            .collect();
                        let parts = merge_links(&motions, size);
                        let side = |v: usize| Side {
                            samples: &o.observations[v].samples,
                            poses: &o.poses[v],
                            values: &states[chosen[v]],
                            cloud: &o.clouds[v],
                        };
                        let present = presence(&o.observations[i], &o.observations[j], &o.poses[j]);
                        let want = ground_truth(&object, &side(i), &side(j), &parts, &present);
                        let pair = set.pair(i, j).expect("a pair");
                        let got = pair.truth();
                        let at = format!("{mode:?} object {index} views ({i}, {j})");
                        assert_eq!(got.part_p, want.part_p, "{at}");
                        assert_eq!(got.part_q, want.part_q, "{at}");
                        assert_eq!(got.corr_mask, want.corr_mask, "{at}");
                        assert_eq!(got.corr_index, want.corr_index, "{at}");
                        assert_eq!(got.joints, want.joints, "{at}");
                        assert_eq!(got.motions.len(), want.motions.len(), "{at}");
                        for (a, b) in got.motions.iter().zip(&want.motions) {
                            assert!((a.rotation - b.rotation).norm() < 1e-5, "{at}");
                            assert!((a.translation - b.translation).norm() < 1e-5, "{at}");
                            assert!((a.scale - b.scale).abs() < 1e-5, "{at}");
                        }
                        let (fa, fb) =
                            (got.flow.as_ref().expect("flow"), want.flow.as_ref().expect("flow"));
                        let worst =
                            fa.iter().zip(fb).map(|(a, b)| (a - b).norm()).fold(0.0, f32::max);
                        assert!(worst < 1e-5, "{at}: flow differs by {worst}");
                        assert_eq!(pair.input().kind.scanned_q(), mode.view(j) == ViewKind::Scan);
                        checked += 1;
                        merged += usize::from(want.motions.len() < set.truth().num_parts());
                    }
                }
            }
            assert!(checked >= 12, "{mode:?}: only {checked} pairs checked");
        }
        // Some pairs merge set parts (a joint unchanged between two of the states).
        assert!(merged > 0, "no pair of views merged set parts");
    }
}
