//! The score of one pair, the one every consumer uses: the evaluator's rows and the passes
//! of its iterative rows, and the trainer's validation. A prediction is checked for shape
//! and finiteness ([`check_prediction`]), then scored against the ground truth
//! ([`score_pair`]): flow (EPE and the PCC curve), segmentation of P and Q (Rand index and
//! matched IoU), the matched parts' motions and the joints (docs/METRICS.md).

use super::{
    end_point_errors, joint_errors, joint_errors_of, matched_iou, motion_errors, pcc, pcc_at,
    pcc_auc, rand_index, segment_count, JointError, MetricError, PCC_THRESHOLDS,
};
use crate::joint_estimate::JointEstimate;
use crate::{GroundTruth, PairInput, Prediction};

/// Why a prediction cannot be scored (the pair counts as failed for its method).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ScoreError {
    /// A per-point array has the wrong length.
    #[error("{what} has {got} entries, expected {expected}")]
    Length {
        /// Which field (`flow`, `segments_p`, `segments_q`, `corr_mask`).
        what: &'static str,
        /// Entries returned.
        got: usize,
        /// Entries expected (points of P or Q).
        expected: usize,
    },
    /// A value is NaN or infinite.
    #[error("{what}[{index}] is not finite")]
    NotFinite {
        /// Which field.
        what: &'static str,
        /// First bad entry.
        index: usize,
    },
    /// A metric refused the prediction.
    #[error(transparent)]
    Metric(#[from] MetricError),
}

/// Checks every per-point field of `prediction` against the pair's sizes and finiteness.
pub fn check_prediction(prediction: &Prediction, input: &PairInput) -> Result<(), ScoreError> {
    let (n_p, n_q) = (input.p.len(), input.q.len());
    let length = |what, got, expected| {
        if got == expected {
            Ok(())
        } else {
            Err(ScoreError::Length { what, got, expected })
        }
    };
    length("segments_p", prediction.segments_p.len(), n_p)?;
    if !prediction.segments_q.is_empty() {
        length("segments_q", prediction.segments_q.len(), n_q)?;
    }
    if let Some(flow) = &prediction.flow {
        length("flow", flow.len(), n_p)?;
        if let Some(index) = flow.iter().position(|v| !v.iter().all(|c| c.is_finite())) {
            return Err(ScoreError::NotFinite { what: "flow", index });
        }
    }
    if let Some(mask) = &prediction.corr_mask {
        length("corr_mask", mask.len(), n_p)?;
        if let Some(index) = mask.iter().position(|v| !v.is_finite()) {
            return Err(ScoreError::NotFinite { what: "corr_mask", index });
        }
    }
    if let Some(index) = prediction.motions.iter().position(|m| !m.is_finite()) {
        return Err(ScoreError::NotFinite { what: "motions", index });
    }
    let joint_finite = |j: &Option<JointEstimate>| {
        j.as_ref().is_none_or(|j| {
            j.axis.iter().chain(j.pivot.iter()).chain([&j.value]).all(|v| v.is_finite())
        })
    };
    if let Some(index) = prediction.joints.iter().flatten().position(|j| !joint_finite(j)) {
        return Err(ScoreError::NotFinite { what: "joints", index });
    }
    Ok(())
}

/// Flow scores of one pair.
#[derive(Debug, Clone, PartialEq)]
pub struct FlowScore {
    /// End-point error (mean over P's points).
    pub epe: f64,
    /// The PCC curve at thresholds `0, 0.005, ..., 0.25`.
    pub pcc: [f64; PCC_THRESHOLDS],
}

impl FlowScore {
    /// PCC at 0.05.
    pub fn pcc_005(&self) -> f64 {
        pcc_at(&self.pcc, 0.05)
    }

    /// PCC at 0.10.
    pub fn pcc_010(&self) -> f64 {
        pcc_at(&self.pcc, 0.10)
    }

    /// Normalised area under the PCC curve.
    pub fn pcc_auc(&self) -> f64 {
        pcc_auc(&self.pcc)
    }
}

/// Segmentation scores of one side (P or Q) of one pair.
#[derive(Debug, Clone, PartialEq)]
pub struct SegmentScore {
    /// Rand index.
    pub rand_index: f64,
    /// Sum of the matched IoUs over the side's ground-truth parts (the dataset IoU is the
    /// sum over pairs divided by the number of parts over pairs).
    pub iou_sum: f64,
    /// Ground-truth parts of the side (the IoU's denominator).
    pub parts: u32,
}

/// Everything scored on one pair.
#[derive(Debug, Clone, PartialEq)]
pub struct PairScore {
    /// Flow scores, when the method reports a flow.
    pub flow: Option<FlowScore>,
    /// Segmentation of P.
    pub p: SegmentScore,
    /// Segmentation of Q, when the method segments Q.
    pub q: Option<SegmentScore>,
    /// Ground-truth parts of the pair.
    pub parts: u32,
    /// Distinct segments predicted on P.
    pub segments: u32,
    /// Rotation errors (degrees) of the matched parts' motions.
    pub rotation_deg: Vec<f64>,
    /// Translation errors of the matched parts' motions.
    pub translation: Vec<f64>,
    /// Every ground-truth joint scored against the matched segment's joint: the method's own
    /// when it gives joints, else the one estimated from the segment's motion
    /// (`pairs::metrics::joints`); empty when the prediction has neither.
    pub joints: Vec<JointError>,
}

/// Scores a checked prediction against the ground truth.
pub fn score_pair(
    prediction: &Prediction,
    input: &PairInput,
    truth: &GroundTruth,
) -> Result<PairScore, ScoreError> {
    check_prediction(prediction, input)?;
    // A cross-instance pair has no true flow: its flow is not scored (never against zero).
    let flow = match (&prediction.flow, &truth.flow) {
        (Some(flow), Some(true_flow)) => {
            let errors = end_point_errors(flow, true_flow)?;
            let epe = errors.iter().sum::<f64>() / errors.len() as f64;
            Some(FlowScore { epe, pcc: pcc(&errors) })
        }
        _ => None,
    };
    let matching = matched_iou(&prediction.segments_p, &truth.part_p)?;
    let p = SegmentScore {
        rand_index: rand_index(&prediction.segments_p, &truth.part_p)?,
        iou_sum: matching.iou.iter().sum(),
        parts: matching.iou.len() as u32,
    };
    let q = if prediction.segments_q.is_empty() {
        None
    } else {
        let q_matching = matched_iou(&prediction.segments_q, &truth.part_q)?;
        Some(SegmentScore {
            rand_index: rand_index(&prediction.segments_q, &truth.part_q)?,
            iou_sum: q_matching.iou.iter().sum(),
            parts: q_matching.iou.len() as u32,
        })
    };
    let motion = motion_errors(&matching, &prediction.motions, &truth.motions);
    let joints = if let Some(estimates) = &prediction.joints {
        joint_errors_of(estimates, &matching, &truth.joints, input.p.normalisation.scale)
    } else if prediction.motions.is_empty() {
        Vec::new()
    } else {
        joint_errors(
            &input.p.points,
            &prediction.segments_p,
            &prediction.motions,
            &matching,
            &truth.joints,
            input.p.normalisation.scale,
        )
    };
    Ok(PairScore {
        flow,
        p,
        q,
        parts: matching.iou.len() as u32,
        segments: segment_count(&prediction.segments_p) as u32,
        rotation_deg: motion.rotation_deg,
        translation: motion.translation,
        joints,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Vector3;
    use crate::synthetic::hinge_pair;

    fn truth_prediction(pair: &crate::Pair) -> Prediction {
        let t = pair.truth();
        Prediction {
            flow: t.flow.clone(),
            segments_p: crate::parts::part_segments(&t.part_p),
            segments_q: crate::parts::part_segments(&t.part_q),
            motions: t.motions.clone(),
            ..Prediction::default()
        }
    }

    #[test]
    fn a_relabelled_truth_scores_perfectly() {
        let pair = hinge_pair("t", 4, 0.5);
        let mut prediction = truth_prediction(&pair);
        for s in prediction.segments_p.iter_mut().chain(prediction.segments_q.iter_mut()) {
            *s = 7 - *s;
        }
        let truth_motions = std::mem::take(&mut prediction.motions);
        prediction.motions = vec![crate::Similarity::identity(); 8];
        prediction.motions[7] = truth_motions[0];
        prediction.motions[6] = truth_motions[1];
        let score = score_pair(&prediction, pair.input(), pair.truth()).expect("scores");
        assert_eq!((score.p.rand_index, score.p.iou_sum, score.parts), (1.0, 2.0, 2));
        assert_eq!(score.q.expect("Q is segmented").iou_sum, 2.0);
        assert!(score.rotation_deg.iter().all(|&e| e < 1e-2), "{:?}", score.rotation_deg);
        assert_eq!(score.flow.expect("flow").epe, 0.0);
    }

    #[test]
    fn pcc_of_a_known_error_distribution() {
        // Errors 0.018 on the first half of the points, 0.2 on the second half.
        let pair = hinge_pair("t", 4, 0.5);
        let mut prediction = truth_prediction(&pair);
        let flow = prediction.flow.as_mut().expect("flow");
        let n = flow.len();
        for (i, f) in flow.iter_mut().enumerate() {
            f.z += if i < n / 2 { 0.018 } else { 0.2 };
        }
        let score = score_pair(&prediction, pair.input(), pair.truth()).expect("scores");
        let flow = score.flow.expect("flow");
        assert!((flow.epe - 0.109).abs() < 1e-6);
        assert_eq!((flow.pcc_005(), flow.pcc_010()), (0.5, 0.5));
        assert_eq!((flow.pcc[3], flow.pcc[4], flow.pcc[50]), (0.0, 0.5, 1.0));
    }

    #[test]
    fn malformed_predictions_name_the_field() {
        let pair = hinge_pair("t", 4, 0.5);
        type Breakage = fn(&mut Prediction);
        let cases: [(Breakage, &str); 4] = [
            (|p| p.segments_p.truncate(31), "segments_p has 31 entries, expected 32"),
            (|p| p.segments_q.truncate(3), "segments_q has 3 entries, expected 32"),
            (
                |p| p.flow.as_mut().expect("flow")[5] = Vector3::new(0.0, f32::NAN, 0.0),
                "flow[5] is not finite",
            ),
            (|p| p.motions[1].translation.x = f32::INFINITY, "motions[1] is not finite"),
        ];
        for (break_it, message) in cases {
            let mut prediction = truth_prediction(&pair);
            break_it(&mut prediction);
            let err = score_pair(&prediction, pair.input(), pair.truth()).expect_err(message);
            assert_eq!(err.to_string(), message);
        }
    }

    #[test]
    fn the_true_segments_give_every_joint_and_one_segment_none() {
        use crate::metrics::JointScores;
        use crate::segments::complete_prediction;
        let pair = hinge_pair("t", 6, 0.8);
        let (input, truth) = (pair.input(), pair.truth());
        let flow = truth.flow.as_deref().expect("a flow");
        let right = complete_prediction(input, flow, &truth.part_p, true);
        let scores = JointScores::of(&score_pair(&right, input, truth).expect("scores").joints);
        assert_eq!(scores.joints, 1);
        assert_eq!(scores.type_accuracy(), 1.0);
        assert!(scores.axis_errors[0] < 0.1, "{:?}", scores.axis_errors);
        assert!(scores.pivot_distances[0] < 1e-3, "{:?}", scores.pivot_distances);
        let one = complete_prediction(input, flow, &vec![0u8; truth.part_p.len()], true);
        let none = JointScores::of(&score_pair(&one, input, truth).expect("scores").joints);
        assert_eq!((none.joints, none.type_correct), (1, 0));
    }
}
