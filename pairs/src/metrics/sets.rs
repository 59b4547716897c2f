//! Segmentation metrics of a set of K views, in MultiBodySync's conventions: one matching of
//! true parts to predicted segments for the whole set (the multi-scan scores), and one per
//! view (the per-scan scores). docs/METRICS.md, "Sets".

use super::motion::{motion_errors, MotionErrors};
use super::segmentation::{matched_iou, rand_index};
use super::MetricError;
use crate::set::SetTruth;
use crate::set_method::SetPrediction;

/// The segmentation scores of one set.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SetScores {
    /// Multi-scan mIoU: the K views' points pooled, one Hungarian matching of set parts to
    /// segments for all of them, the mean IoU over set parts. A segment id must name the
    /// same part in every view to score here.
    pub multi_scan_iou: f64,
    /// Per-scan mIoU: each view matched on its own, the mean over views of its mean IoU.
    pub per_scan_iou: f64,
    /// Multi-scan Rand index: over the point pairs of the pooled views.
    pub multi_scan_ri: f64,
    /// Per-scan Rand index: the mean over views of each view's Rand index.
    pub per_scan_ri: f64,
}

/// Scores the predicted segments of every view (`predicted[k]`, one id per point of view k)
/// against the set parts (`truth[k]`).
pub fn score_set(predicted: &[Vec<u32>], truth: &[Vec<u8>]) -> Result<SetScores, MetricError> {
    if predicted.len() != truth.len() {
        return Err(MetricError::LengthMismatch {
            what: "views",
            predicted: predicted.len(),
            truth: truth.len(),
        });
    }
    if truth.is_empty() {
        return Err(MetricError::Empty("views"));
    }
    let (mut per_iou, mut per_ri) = (0.0, 0.0);
    for (p, t) in predicted.iter().zip(truth) {
        per_iou += matched_iou(p, t)?.mean_iou();
        per_ri += rand_index(p, t)?;
    }
    let pooled_p: Vec<u32> = predicted.concat();
    let pooled_t: Vec<u8> = truth.concat();
    let k = truth.len() as f64;
    Ok(SetScores {
        multi_scan_iou: matched_iou(&pooled_p, &pooled_t)?.mean_iou(),
        per_scan_iou: per_iou / k,
        multi_scan_ri: rand_index(&pooled_p, &pooled_t)?,
        per_scan_ri: per_ri / k,
    })
}

/// Everything scored on one set: the segmentation scores and the motion errors.
#[derive(Debug, Clone, PartialEq)]
pub struct SetScore {
    /// Multi-scan and per-scan mIoU and RI ([`score_set`]).
    pub scores: SetScores,
    /// For every view k >= 1 and every set part matched (by the multi-scan matching) to a
    /// segment with a motion to view k, the rotation and translation errors of that motion
    /// against the part's true motion from view 0 to view k; empty when the prediction has no
    /// motions.
    pub motions: MotionErrors,
}

/// Scores a set prediction against the set's truth: [`score_set`] on its segments, and the
/// motion of each matched part to every view k >= 1 (`pairs::metrics::motion_errors` under
/// the multi-scan matching).
pub fn score_set_prediction(
    prediction: &SetPrediction,
    truth: &SetTruth,
) -> Result<SetScore, MetricError> {
    let scores = score_set(&prediction.segments, &truth.parts)?;
    let mut motions = MotionErrors::default();
    if !prediction.motions.is_empty() {
        let matching = matched_iou(&prediction.segments.concat(), &truth.parts.concat())?;
        for (predicted, true_motions) in prediction.motions.iter().zip(&truth.motions).skip(1) {
            let errors = motion_errors(&matching, predicted, true_motions);
            motions.rotation_deg.extend(errors.rotation_deg);
            motions.translation.extend(errors.translation);
        }
    }
    Ok(SetScore { scores, motions })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn consistent_labels_score_one_and_swapped_ids_only_per_scan() {
        let truth = vec![vec![0, 0, 1, 1], vec![0, 1, 1, 1]];
        let exact = score_set(&[vec![5, 5, 7, 7], vec![5, 7, 7, 7]], &truth).expect("scores");
        assert_eq!(
            exact,
            SetScores {
                multi_scan_iou: 1.0,
                per_scan_iou: 1.0,
                multi_scan_ri: 1.0,
                per_scan_ri: 1.0
            }
        );
        // View 1 right on its own but with the two ids swapped: per-scan scores stay 1, the
        // pooled matching cannot fit both views.
        let swapped = score_set(&[vec![5, 5, 7, 7], vec![7, 5, 5, 5]], &truth).expect("scores");
        assert_eq!((swapped.per_scan_iou, swapped.per_scan_ri), (1.0, 1.0));
        // Pooled: part 0 = points {0,1,4}, part 1 = {2,3,5,6,7}; segment 5 = {0,1,5,6,7},
        // segment 7 = {2,3,4}. Matching 0->5: IoU 2/6, 1->7: 2/6; or 0->7: 1/5, 1->5:
        // 3/7. The best total is 1/3 + 1/3 = 0.667 (against 0.2 + 0.429 = 0.629).
        assert!((swapped.multi_scan_iou - 1.0 / 3.0).abs() < 1e-12, "{swapped:?}");
        // Rand index over the C(8, 2) = 28 pooled pairs: pairs together in the truth
        // C(3,2) + C(5,2) = 13, in the prediction C(5,2) + C(3,2) = 13, in both 5 (cells
        // {0,1}, {5,6,7}, {2,3}: 1 + 3 + 1); agreements 28 + 2 * 5 - 13 - 13 = 12.
        assert!((swapped.multi_scan_ri - 12.0 / 28.0).abs() < 1e-12, "{swapped:?}");
    }

    #[test]
    fn motion_errors_of_every_part_in_every_view_under_the_multi_scan_matching() {
        use crate::math::{Rotation3, Vector3};
        let set = crate::synthetic::hinge_set("h", 4, &[0.0, 0.5, -0.4]);
        let truth = set.truth();
        // The truth under other ids (part p is segment 1 - p), with part 1's motion to view
        // 2 turned by 10 degrees more and moved by 0.25.
        let segments: Vec<Vec<u32>> =
            truth.parts.iter().map(|v| v.iter().map(|&p| 1 - u32::from(p)).collect()).collect();
        let mut motions: Vec<Vec<_>> = truth.motions.iter().map(|m| vec![m[1], m[0]]).collect();
        let turn = Rotation3::from_axis_angle(&Vector3::z_axis(), 10f32.to_radians());
        motions[2][0].rotation = turn.matrix() * motions[2][0].rotation;
        motions[2][0].translation += Vector3::new(0.0, 0.25, 0.0);
        let prediction = SetPrediction { segments, motions };
        let score = score_set_prediction(&prediction, truth).expect("scores");
        assert_eq!(score.scores.multi_scan_iou, 1.0);
        // Two parts in views 1 and 2: four errors, one of them the turn.
        let mut rotation = score.motions.rotation_deg.clone();
        rotation.sort_by(f64::total_cmp);
        assert_eq!(rotation.len(), 4);
        assert!(rotation[..3].iter().all(|&e| e < 1e-2), "{rotation:?}");
        assert!((rotation[3] - 10.0).abs() < 1e-2, "{rotation:?}");
        let moved: Vec<f64> =
            score.motions.translation.iter().copied().filter(|&t| t > 1e-6).collect();
        assert_eq!(moved.len(), 1);
        assert!((moved[0] - 0.25).abs() < 1e-6, "{moved:?}");
    }

    #[test]
    fn mismatched_views_are_errors() {
        assert!(score_set(&[vec![0]], &[vec![0], vec![0]]).is_err());
        assert!(score_set(&[vec![0, 1]], &[vec![0]]).is_err());
        assert!(score_set(&[], &[]).is_err());
    }
}
