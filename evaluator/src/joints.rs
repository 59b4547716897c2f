//! Joint scores of the iteration board (first and last pass of `net-iter`) summed over
//! pairs with medians, from the same per-joint metric as `joints.csv`
//! (`pairs::metrics::joints`): joint type, axis angle `min(θ, 180° − θ)` and, for revolute
//! joints estimated as revolute, the distance between the estimated and the true axis lines
//! (normalised units). A joint whose part has no segment, or whose segment does not move
//! relative to the base, counts as a wrong type.

use pairs::metrics::{joint_errors, matched_iou};
use pairs::{Pair, Prediction};

/// Joint scores summed over pairs.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct JointScores {
    /// Ground-truth joints seen.
    pub joints: usize,
    /// Joints whose type was estimated correctly.
    pub type_correct: usize,
    /// Axis errors in degrees, one per joint with an estimate.
    pub axis_errors: Vec<f64>,
    /// Axis line distances, one per revolute joint estimated as revolute.
    pub pivot_distances: Vec<f64>,
}

impl JointScores {
    /// Adds another set of scores (e.g. one pair's) to these.
    pub fn merge(&mut self, other: JointScores) {
        self.joints += other.joints;
        self.type_correct += other.type_correct;
        self.axis_errors.extend(other.axis_errors);
        self.pivot_distances.extend(other.pivot_distances);
    }

    /// Adds one pair's prediction, scored by `pairs::metrics::joints` (the pivot distance
    /// is the distance between the estimated and the true axis lines).
    pub fn add(&mut self, pair: &Pair, prediction: &Prediction) {
        let truth = pair.truth();
        let Ok(matching) = matched_iou(&prediction.segments_p, &truth.part_p) else { return };
        let input = pair.input();
        for joint in joint_errors(
            &input.p.points,
            &prediction.segments_p,
            &prediction.motions,
            &matching,
            &truth.joints,
            input.p.normalisation.scale,
        ) {
            self.joints += 1;
            self.type_correct += usize::from(joint.type_correct());
            self.axis_errors.extend(joint.axis_deg);
            self.pivot_distances.extend(joint.line_distance);
        }
    }

    /// Fraction of joints with the right type.
    pub fn type_accuracy(&self) -> f64 {
        self.type_correct as f64 / self.joints.max(1) as f64
    }
}

/// The median of `values` (NaN when empty).
pub fn median(values: &[f64]) -> f64 {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    match v.len() {
        0 => f64::NAN,
        n if n % 2 == 1 => v[n / 2],
        n => (v[n / 2 - 1] + v[n / 2]) / 2.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use pairs::segments::complete_prediction;
    use pairs::synthetic::hinge_pair;

    #[test]
    fn the_true_segments_score_perfectly() {
        let pair = hinge_pair("t", 6, 0.8);
        let (input, truth) = (pair.input(), pair.truth());
        let prediction =
            complete_prediction(input, truth.flow.as_deref().expect("a flow"), &truth.part_p, true);
        let mut scores = JointScores::default();
        scores.add(&pair, &prediction);
        assert_eq!(scores.joints, 1);
        assert_eq!(scores.type_accuracy(), 1.0);
        assert!(scores.axis_errors[0] < 0.1, "{:?}", scores.axis_errors);
        assert!(scores.pivot_distances[0] < 1e-3, "{:?}", scores.pivot_distances);
        let one = complete_prediction(
            input,
            truth.flow.as_deref().expect("a flow"),
            &vec![0u8; truth.part_p.len()],
            true,
        );
        let mut none = JointScores::default();
        none.add(&pair, &one);
        assert_eq!((none.joints, none.type_correct), (1, 0));
        assert_eq!(median(&[3.0, 1.0, 2.0]), 2.0);
    }
}
