//! Turning a segmentation of P into a full [`Prediction`], the way every segmenter does it:
//! compact segment ids, one rigid motion per segment fitted to the flow, and Q's labels by
//! transferring P's labels through those motions to Q's nearest points.

use crate::math::{Point3, Vector3};
use crate::method::Prediction;
use crate::pair::PairInput;
use crate::parts::SegmentId;
use crate::transform::{fit_similarity_weighted, Similarity};

/// Relabels arbitrary segment ids as `0..K` in order of first appearance.
pub fn compact_labels<T: Copy + PartialEq>(raw: &[T]) -> Vec<SegmentId> {
    let mut order: Vec<T> = Vec::new();
    raw.iter()
        .map(|&r| {
            let k = order.iter().position(|&o| o == r).unwrap_or_else(|| {
                order.push(r);
                order.len() - 1
            });
            k as SegmentId
        })
        .collect()
}

/// The motion of each segment `0..K` that best maps its points of P onto `p + flow`
/// (Umeyama: rotation, translation and scale, because P and Q are normalised separately);
/// identity for a segment whose fit is degenerate or empty.
pub fn fit_segment_motions(
    p: &[Point3],
    flow: &[Vector3],
    segments: &[SegmentId],
) -> Vec<Similarity> {
    let count = segments.iter().max().map_or(0, |&m| m as usize + 1);
    let moved: Vec<Point3> = p.iter().zip(flow).map(|(x, f)| x + f).collect();
    (0..count as SegmentId)
        .map(|k| {
            let weights: Vec<f32> =
                segments.iter().map(|&l| if l == k { 1.0 } else { 0.0 }).collect();
            fit_similarity_weighted(p, &moved, &weights, true).unwrap_or_else(Similarity::identity)
        })
        .collect()
}

/// Q's segment ids: each point of Q takes the label of the nearest point of P after P's
/// points were moved by their segment's motion. Empty when P is empty.
pub fn transfer_labels(
    p: &[Point3],
    segments: &[SegmentId],
    motions: &[Similarity],
    q: &[Point3],
) -> Vec<SegmentId> {
    let placed: Vec<Point3> = p
        .iter()
        .zip(segments)
        .map(|(x, &l)| motions.get(l as usize).map_or(*x, |m| m.apply(x)))
        .collect();
    if placed.is_empty() {
        return Vec::new();
    }
    q.iter()
        .map(|y| {
            let nearest = placed
                .iter()
                .enumerate()
                .min_by(|(_, a), (_, b)| {
                    (*a - y).norm_squared().total_cmp(&(*b - y).norm_squared())
                })
                .map_or(0, |(i, _)| i);
            segments[nearest]
        })
        .collect()
}

/// A complete prediction from P's segments (any ids) and the flow they were found on:
/// compact ids, per-segment motions fitted on `flow`, Q labelled by [`transfer_labels`].
/// `flow` is reported in the prediction only when `report_flow` is set (a segmenter run on
/// someone else's flow does not claim it as its own).
pub fn complete_prediction<T: Copy + PartialEq>(
    input: &PairInput,
    flow: &[Vector3],
    raw_segments: &[T],
    report_flow: bool,
) -> Prediction {
    let segments_p = compact_labels(raw_segments);
    let motions = fit_segment_motions(&input.p.points, flow, &segments_p);
    let segments_q = transfer_labels(&input.p.points, &segments_p, &motions, &input.q.points);
    Prediction {
        flow: report_flow.then(|| flow.to_vec()),
        segments_p,
        segments_q,
        motions,
        corr_mask: None,
        segment_probs: None,
        joints: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synthetic::hinge_pair;

    #[test]
    fn compact_labels_orders_by_first_appearance() {
        assert_eq!(compact_labels(&[7, 7, 3, 7, 9, 3]), vec![0, 0, 1, 0, 2, 1]);
        assert_eq!(compact_labels::<u8>(&[]), Vec::<u32>::new());
    }

    #[test]
    fn ground_truth_segments_reproduce_the_truth() {
        let pair = hinge_pair("t", 5, 0.7);
        let (input, truth) = (pair.input(), pair.truth());
        let flow = truth.flow.as_deref().expect("a single-object pair has a flow");
        let pred = complete_prediction(input, flow, &truth.part_p, false);
        assert!(pred.flow.is_none());
        assert_eq!(pred.segments_p, compact_labels(&truth.part_p));
        assert_eq!(pred.segments_q, compact_labels(&truth.part_q));
        for (k, m) in pred.motions.iter().enumerate() {
            let gt = &truth.motions[truth.part_p
                [pred.segments_p.iter().position(|&l| l as usize == k).unwrap()]
                as usize];
            assert!((m.rotation - gt.rotation).norm() < 1e-4);
            assert!((m.translation - gt.translation).norm() < 1e-4);
            assert!((m.scale - gt.scale).abs() < 1e-4);
        }
    }
}
