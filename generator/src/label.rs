//! Labelling: which links form one rigid part in a pair, and the pair's ground truth.

use pairs::math::{Isometry3, Point3, Real};
use pairs::{Cloud, GroundTruth, JointTruth, PartId, Similarity};

use crate::objects::ArticulatedObject;
use crate::sampling::SurfacePoint;

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
    let same = |a: &Isometry3, b: &Isometry3| {
        a.rotation.angle_to(&b.rotation) < SAME_ROTATION
            && (a.translation.vector - b.translation.vector).norm() < SAME_TRANSLATION * size
    };
    let mut first_link: Vec<usize> = Vec::new();
    let of_link = link_motions
        .iter()
        .enumerate()
        .map(|(link, m)| {
            let part =
                first_link.iter().position(|&r| same(m, &link_motions[r])).unwrap_or_else(|| {
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
    let joints = object
        .joints
        .iter()
        .enumerate()
        .filter(|(_, j)| parts.of_link[j.child] != parts.of_link[j.parent])
        .map(|(index, j)| {
            let (pose_p, pose_q) = (&p.poses[j.parent], &q.poses[j.parent]);
            JointTruth {
                part: parts.of_link[j.child],
                kind: j.kind,
                // Joint axes are unit when built (`Joint::revolute`, `prismatic`), so this
                // only removes the rotation's rounding; the fallback is never taken.
                axis_p: pairs::math::unit_or(&(pose_p.rotation * j.axis), j.axis),
                pivot_p: norm_p.apply(&(pose_p * j.pivot)),
                axis_q: pairs::math::unit_or(&(pose_q.rotation * j.axis), j.axis),
                pivot_q: norm_q.apply(&(pose_q * j.pivot)),
                value_p: p.values[index],
                value_q: q.values[index],
            }
        })
        .collect();
    GroundTruth { part_p, part_q, motions, flow, corr_mask, corr_index, joints }
}

/// Index of the point of `cloud` labelled `part` nearest to `x`, or -1 if there is none.
fn nearest_of_part(x: &Point3, part: PartId, cloud: &[Point3], labels: &[PartId]) -> i32 {
    cloud
        .iter()
        .zip(labels)
        .enumerate()
        .filter(|(_, (_, &l))| l == part)
        .map(|(i, (c, _))| (i, (c - x).norm_squared()))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map_or(-1, |(i, _)| i as i32)
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
