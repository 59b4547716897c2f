//! The requirements on every flow segmenter (SeqRANSAC, SC, JLC), table-driven:
//! exact recovery of a two-part hinge, robustness to noise and outliers, and degenerate
//! inputs (a valid prediction or the input error each calls for).

mod support;

use baselines::jlinkage::JLinkageError;
use baselines::ransac::SeqRansacError;
use baselines::segmenters;
use support::{
    assert_outcome, corrupt_flow, degenerate_inputs, expected_input_error, hinge,
    max_rotation_error, min_iou,
};

#[test]
fn exact_flow_recovers_both_parts_and_their_motions() {
    let pair = hinge();
    for segmenter in segmenters() {
        let prediction = segmenter
            .segment(pair.input(), pair.truth().flow.as_deref().expect("a flow"))
            .expect("segments");
        let (iou, rot) =
            (min_iou(&prediction, &pair.truth().part_p), max_rotation_error(&prediction, &pair));
        assert!(iou > 0.95, "{}: IoU {iou}", segmenter.name());
        assert!(rot < 1.0, "{}: rotation error {rot} deg", segmenter.name());
        assert!(prediction.flow.is_none(), "{}: a segmenter reports no flow", segmenter.name());
    }
}

#[test]
fn noisy_flow_with_outliers_still_finds_the_parts() {
    let pair = hinge();
    for seed in 0..3 {
        // 5% Gaussian flow noise and 10% outliers, as defined in `support::corrupt_flow`.
        let flow = corrupt_flow(pair.truth().flow.as_deref().expect("a flow"), 0.05, 0.10, seed);
        for segmenter in segmenters() {
            let prediction = segmenter.segment(pair.input(), &flow).expect("segments");
            let iou = min_iou(&prediction, &pair.truth().part_p);
            assert!(iou > 0.8, "{} seed {seed}: IoU {iou}", segmenter.name());
        }
    }
}

/// The degenerate case a segmenter reports when P's points cannot carry a rigid motion
/// (collinear or repeated points): SeqRANSAC finds no consensus, J-Linkage no hypothesis.
fn no_motion_error(error: &pairs::MethodError) -> Option<String> {
    let source = error.source.as_ref();
    if let Some(e @ SeqRansacError::NoConsensus { .. }) = source.downcast_ref() {
        return Some(e.to_string());
    }
    if let Some(e @ JLinkageError::NoHypothesis { .. }) = source.downcast_ref() {
        return Some(e.to_string());
    }
    None
}

/// Inputs that are degenerate but well defined must get a valid prediction (the zero flow
/// one rigid part), or, where P's points cannot carry a motion, the segmenter's own
/// degenerate-case error (never one segment in silence); too few points, a flow of the
/// wrong length and NaN points or flow vectors must be refused with exactly that input
/// error.
#[test]
fn degenerate_inputs_give_a_valid_prediction_or_the_right_error() {
    let mut reported = Vec::new();
    for (case, input, flow) in degenerate_inputs() {
        for segmenter in segmenters() {
            let name = format!("{} on {case}", segmenter.name());
            let result = segmenter.segment(&input, &flow);
            if let Some(message) = result.as_ref().err().and_then(no_motion_error) {
                assert!(["collinear", "repeated point"].contains(&case), "{name}: {message}");
                reported.push(name);
                continue;
            }
            if case == "zero flow" {
                let prediction = result.as_ref().expect("the zero flow is segmented");
                assert_eq!(prediction.motions.len(), 1, "{name}: one rigid part");
            }
            let expected = expected_input_error(case, true);
            assert_outcome(&name, segmenter.name(), &input, result, expected);
        }
    }
    for expected in ["seqransac on collinear", "seqransac on repeated point"] {
        assert!(reported.iter().any(|r| r == expected), "{expected}: reported {reported:?}");
    }
}

#[test]
fn results_depend_on_the_pair_not_on_the_call() {
    let pair = hinge();
    let flow = corrupt_flow(pair.truth().flow.as_deref().expect("a flow"), 0.05, 0.10, 9);
    for segmenter in segmenters() {
        let a = segmenter.segment(pair.input(), &flow).expect("segments");
        let b = segmenter.segment(pair.input(), &flow).expect("segments");
        assert_eq!(a, b, "{}: deterministic", segmenter.name());
    }
}
