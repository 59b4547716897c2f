//! The ground truth stored with every pair (DESIGN.md, "Shared definitions").

use crate::joints::JointTruth;
use crate::math::{Point3, Vector3};
use crate::parts::PartId;
use crate::transform::Similarity;

/// Everything a method must recover for one pair, with the frames of DESIGN.md.
#[derive(Debug, Clone, PartialEq)]
pub struct GroundTruth {
    /// Part id of every point of P.
    pub part_p: Vec<PartId>,
    /// Part id of every point of Q (part k in P is part k in Q).
    pub part_q: Vec<PartId>,
    /// `motions[k]` maps part k from P's normalised frame to Q's normalised frame; all share
    /// one scale.
    pub motions: Vec<Similarity>,
    /// Per point of P: `motions[part_p[i]](p_i) - p_i`, Q's normalised units. `None` for a
    /// cross-instance pair (XF2F, XF2P): no flow is defined between two different shapes,
    /// and an absent flow is never read as zero.
    pub flow: Option<Vec<Vector3>>,
    /// Per point of P: whether the moved point is present in Q (all false for a
    /// cross-instance pair: no point of one object has a counterpart on another).
    pub corr_mask: Vec<bool>,
    /// Per point of P: index of the nearest point of Q of the same part to the moved point
    /// where `corr_mask` holds, else -1.
    pub corr_index: Vec<i32>,
    /// The joint that moves each moving part (part 0, the base, has none).
    pub joints: Vec<JointTruth>,
}

impl GroundTruth {
    /// Number of parts of the pair.
    pub fn num_parts(&self) -> usize {
        self.motions.len()
    }
}

/// Index of the point of `cloud` labelled `part` nearest to `x`, or -1 if there is none
/// (the target of a pair's `corr_index`; the first of equally near points).
pub fn nearest_of_part(x: &Point3, part: PartId, cloud: &[Point3], labels: &[PartId]) -> i32 {
    cloud
        .iter()
        .zip(labels)
        .enumerate()
        .filter(|(_, (_, &l))| l == part)
        .map(|(i, (c, _))| (i, (c - x).norm_squared()))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map_or(-1, |(i, _)| i as i32)
}
