//! Reference rows that need no learning: `one-part` (the whole of P is one rigid part, fitted
//! to whatever flow it is given) and the `gt` oracle, which the runner answers from the
//! ground truth itself (see [`crate::rows::registry::Runner::Oracle`]).

use pairs::math::Vector3;
use pairs::segments::complete_prediction;
use pairs::{MethodError, PairInput, Prediction, Segmenter};

/// Everything in one segment, with one rigid motion fitted to the flow; its flow is that
/// motion's displacement field, the best single rigid explanation of the input flow.
#[derive(Debug, Clone, Copy, Default)]
pub struct OnePart;

impl Segmenter for OnePart {
    fn name(&self) -> &str {
        "one-part"
    }

    fn segment(&self, input: &PairInput, flow: &[Vector3]) -> Result<Prediction, MethodError> {
        if flow.len() != input.p.len() {
            let msg = format!("flow has {} vectors for {} points", flow.len(), input.p.len());
            return Err(MethodError::new(self.name(), &input.id, msg));
        }
        let mut prediction = complete_prediction(input, flow, &vec![0u8; flow.len()], false);
        let motion =
            prediction.motions.first().copied().unwrap_or_else(pairs::Similarity::identity);
        prediction.flow = Some(input.p.points.iter().map(|p| motion.apply(p) - p).collect());
        Ok(prediction)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use pairs::metrics::score_pair;
    use pairs::synthetic::hinge_pair;

    #[test]
    fn one_part_scores_the_hand_computed_ri_and_iou() {
        // Two parts of 16 points. One segment: of the C(32,2) = 496 point pairs, the
        // 2 * C(16,2) = 240 inside a part agree, the 256 across parts do not: RI = 240/496.
        // Part 0 matches the segment with IoU 16/32, part 1 is left unmatched (0).
        let pair = hinge_pair("toy", 4, 0.8);
        let prediction = OnePart
            .segment(pair.input(), pair.truth().flow.as_deref().expect("a flow"))
            .expect("segments");
        let score = score_pair(&prediction, pair.input(), pair.truth()).expect("scores");
        assert!((score.p.rand_index - 240.0 / 496.0).abs() < 1e-12);
        assert!((score.p.iou_sum / f64::from(score.parts) - 0.25).abs() < 1e-12);
        assert_eq!(score.segments, 1);
        // Its flow is one rigid motion: exact on the fixed half, wrong on the moving one.
        let flow = score.flow.expect("one-part reports its flow");
        assert!(flow.epe > 0.01);
    }

    #[test]
    fn one_part_refuses_a_flow_of_the_wrong_length() {
        let pair = hinge_pair("toy", 4, 0.8);
        let err = OnePart
            .segment(pair.input(), &pair.truth().flow.as_deref().expect("a flow")[1..])
            .expect_err("refused");
        assert!(err.to_string().contains("31 vectors for 32 points"), "{err}");
    }
}
