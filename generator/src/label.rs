//! Labelling: which links form one rigid part in a pair, and the pair's ground truth.

use pairs::ground_truth::nearest_of_part;
use pairs::math::{Isometry3, Point3, Real};
use pairs::{Cloud, GroundTruth, JointTruth, PartId, Similarity};

use articulated::objects::ArticulatedObject;
use articulated::sampling::SurfacePoint;

/// Rotation difference (radians) below which two link motions count as one.
const SAME_ROTATION: Real = 1e-5;
/// Translation difference, relative to the object's size, below which two link motions
/// count as one.
const SAME_TRANSLATION: Real = 1e-5;

/// Links grouped into the rigid parts of one pair.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Parts {
    /// Part of each link; the root's part is 0, the others are numbered by their first link.
    pub of_link: Vec<PartId>,
    /// First link of each part.
    pub first_link: Vec<usize>,
}

impl Parts {
    /// Number of parts.
    pub fn count(&self) -> usize {
        self.first_link.len()
    }
}

/// Groups links whose motion from P's state to Q's state is the same (their relative
/// transform did not change), given each link's motion and the object's size.
pub fn merge_links(link_motions: &[Isometry3], size: Real) -> Parts {
    merge_links_over(std::slice::from_ref(&link_motions), size)
}

/// Groups links whose motions are the same in every one of several state changes
/// (`motions[k][link]`: the set's views, each from view 0): a link joins the first group
/// whose first link moved as it did in all of them. One change is [`merge_links`].
pub fn merge_links_over<M: AsRef<[Isometry3]>>(motions: &[M], size: Real) -> Parts {
    let same = |a: &Isometry3, b: &Isometry3| {
        a.rotation.angle_to(&b.rotation) < SAME_ROTATION
            && (a.translation.vector - b.translation.vector).norm() < SAME_TRANSLATION * size
    };
    let links = motions.first().map_or(0, |m| m.as_ref().len());
    let mut first_link: Vec<usize> = Vec::new();
    let of_link = (0..links)
        .map(|link| {
            let together =
                |r: usize| motions.iter().all(|m| same(&m.as_ref()[link], &m.as_ref()[r]));
            let part = first_link.iter().position(|&r| together(r)).unwrap_or_else(|| {
                first_link.push(link);
                first_link.len() - 1
            });
            part as PartId
        })
        .collect();
    Parts { of_link, first_link }
}

/// One side of a pair before labelling: its samples, link poses, joint values and cloud.
#[derive(Debug, Clone)]
pub struct Side<'a> {
    /// Sampled surface points.
    pub samples: &'a [SurfacePoint],
    /// Pose of every link (rest frame to the observed object frame, global pose included).
    pub poses: &'a [Isometry3],
    /// Joint values of the state.
    pub values: &'a [Real],
    /// The normalised cloud of the samples.
    pub cloud: &'a Cloud,
}

/// Part ids of both clouds and the full ground truth of a pair (DESIGN.md definitions);
/// `present` says per point of P whether its moved point is present in Q (all true for a
/// full Q). A present point whose part has no point in Q is marked absent.
pub fn ground_truth(
    object: &ArticulatedObject,
    p: &Side,
    q: &Side,
    parts: &Parts,
    present: &[bool],
) -> GroundTruth {
    let link_motion = |link: usize| q.poses[link] * p.poses[link].inverse();
    let (norm_p, norm_q) = (&p.cloud.normalisation, &q.cloud.normalisation);
    let motions: Vec<Similarity> = parts
        .first_link
        .iter()
        .map(|&l| Similarity::between_normalised(&link_motion(l), norm_p, norm_q))
        .collect();
    let part_p: Vec<PartId> = p.samples.iter().map(|s| parts.of_link[s.link]).collect();
    let part_q: Vec<PartId> = q.samples.iter().map(|s| parts.of_link[s.link]).collect();
    let moved: Vec<Point3> = p
        .cloud
        .points
        .iter()
        .zip(&part_p)
        .map(|(x, &k)| motions[usize::from(k)].apply(x))
        .collect();
    let flow = moved.iter().zip(&p.cloud.points).map(|(m, x)| m - x).collect();
    let corr_index: Vec<i32> = moved
        .iter()
        .zip(&part_p)
        .zip(present)
        .map(
            |((m, &k), &present)| {
                if present {
                    nearest_of_part(m, k, &q.cloud.points, &part_q)
                } else {
                    -1
                }
            },
        )
        .collect();
    let corr_mask = corr_index.iter().map(|&i| i >= 0).collect();
    let joints = joint_truths((object, object), p, q, parts);
    GroundTruth { part_p, part_q, motions, flow: Some(flow), corr_mask, corr_index, joints }
}

/// Whether two objects of one category can be matched part for part: the same links and
/// joints by name, joint kind and place in the tree, joint axes pointing the same way in
/// the rest frame (a door hinged on the other side is not the same joint), and the same
/// mimic rules.
pub fn same_structure(a: &ArticulatedObject, b: &ArticulatedObject) -> bool {
    let links = |o: &ArticulatedObject| o.links.iter().map(|l| l.name.clone()).collect::<Vec<_>>();
    let joints = |o: &ArticulatedObject| {
        o.joints.iter().map(|j| (j.name.clone(), j.kind, j.parent, j.child)).collect::<Vec<_>>()
    };
    let mimics =
        |o: &ArticulatedObject| o.mimics.iter().map(|m| (m.joint, m.leader)).collect::<Vec<_>>();
    let aligned = a.joints.iter().zip(&b.joints).all(|(x, y)| x.axis.dot(&y.axis) > 0.5);
    a.category == b.category
        && links(a) == links(b)
        && aligned
        && joints(a) == joints(b)
        && mimics(a) == mimics(b)
}

/// The rigid parts of a cross-instance pair: a link joins its parent's part when its joint
/// has the same value in P's state (of one object) and Q's state (of the other), as a link
/// whose joint did not move joins its parent in a pair of one object. Links come after
/// their parents (the model's rule), so one pass in link order suffices.
pub fn parts_by_values(object: &ArticulatedObject, values_p: &[Real], values_q: &[Real]) -> Parts {
    let mut of_link: Vec<PartId> = vec![0; object.links.len()];
    let mut first_link = vec![0];
    for link in 1..object.links.len() {
        let joint = object.joints.iter().position(|j| j.child == link);
        of_link[link] = match joint {
            Some(j) if values_p[j] != values_q[j] => {
                first_link.push(link);
                (first_link.len() - 1) as PartId
            }
            Some(j) => of_link[object.joints[j].parent],
            None => 0,
        };
    }
    Parts { of_link, first_link }
}

/// The frame of `link` in an object the category defines: the link's pose composed with the
/// pivot of the joint that moves it (the object's rest frame for the root).
fn link_frame(object: &ArticulatedObject, poses: &[Isometry3], link: usize) -> Isometry3 {
    let pivot =
        object.joints.iter().find(|j| j.child == link).map_or(Point3::origin(), |j| j.pivot);
    poses[link] * Isometry3::translation(pivot.x, pivot.y, pivot.z)
}

/// The ground truth of a cross-instance pair: P observes `object_p`, Q observes `object_q`
/// (same links and joints by name, [`same_structure`]). Part k's motion maps its frame in
/// P's object onto its frame in Q's object ([`link_frame`] of the part's first link: the
/// joint's pivot and the link's orientation), so a hinge goes to the other object's hinge.
/// No flow and no point correspondences are defined between two shapes: the flow is
/// absent, `corr_mask` all false, `corr_index` all -1. Each joint is given in both objects.
pub fn cross_ground_truth(
    (object_p, object_q): (&ArticulatedObject, &ArticulatedObject),
    p: &Side,
    q: &Side,
    parts: &Parts,
) -> GroundTruth {
    let (norm_p, norm_q) = (&p.cloud.normalisation, &q.cloud.normalisation);
    let motions: Vec<Similarity> = parts
        .first_link
        .iter()
        .map(|&l| {
            let motion =
                link_frame(object_q, q.poses, l) * link_frame(object_p, p.poses, l).inverse();
            Similarity::between_normalised(&motion, norm_p, norm_q)
        })
        .collect();
    let part_p: Vec<PartId> = p.samples.iter().map(|s| parts.of_link[s.link]).collect();
    let part_q: Vec<PartId> = q.samples.iter().map(|s| parts.of_link[s.link]).collect();
    let n = part_p.len();
    let joints = joint_truths((object_p, object_q), p, q, parts);
    GroundTruth {
        part_p,
        part_q,
        motions,
        flow: None,
        corr_mask: vec![false; n],
        corr_index: vec![-1; n],
        joints,
    }
}

/// The joint of every moving part, in both objects (the same object for a pair of one
/// object): its axis and pivot posed in each side's normalised frame, its value in each
/// state.
pub(crate) fn joint_truths(
    (object_p, object_q): (&ArticulatedObject, &ArticulatedObject),
    p: &Side,
    q: &Side,
    parts: &Parts,
) -> Vec<JointTruth> {
    let (norm_p, norm_q) = (&p.cloud.normalisation, &q.cloud.normalisation);
    object_p
        .joints
        .iter()
        .zip(&object_q.joints)
        .enumerate()
        .filter(|(_, (j, _))| parts.of_link[j.child] != parts.of_link[j.parent])
        .map(|(index, (jp, jq))| {
            let (pose_p, pose_q) = (&p.poses[jp.parent], &q.poses[jq.parent]);
            JointTruth {
                part: parts.of_link[jp.child],
                kind: jp.kind,
                // Joint axes are unit when built (`Joint::revolute`, `prismatic`), so this
                // only removes the rotation's rounding; the fallback is never taken.
                axis_p: pairs::math::unit_or(&(pose_p.rotation * jp.axis), jp.axis),
                pivot_p: norm_p.apply(&(pose_p * jp.pivot)),
                axis_q: pairs::math::unit_or(&(pose_q.rotation * jq.axis), jq.axis),
                pivot_q: norm_q.apply(&(pose_q * jq.pivot)),
                value_p: p.values[index],
                value_q: q.values[index],
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use pairs::math::Vector3;

    #[test]
    fn links_that_moved_together_are_merged() {
        let still = Isometry3::identity();
        let turned = Isometry3::rotation(Vector3::z() * 0.3);
        let slid = Isometry3::translation(0.0, 0.0, 0.2);
        let parts = merge_links(&[still, turned, still, slid, turned], 1.0);
        assert_eq!(parts.of_link, vec![0, 1, 0, 2, 1]);
        assert_eq!(parts.first_link, vec![0, 1, 3]);
    }
}
