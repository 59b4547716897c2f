//! The requirements on every flow segmenter (SeqRANSAC, SC, JLC), table-driven:
//! exact recovery of a two-part hinge, robustness to noise and outliers, and degenerate
//! inputs.

mod support;

use baselines::segmenters;
use support::{assert_valid, corrupt_flow, degenerate_inputs, hinge, max_rotation_error, min_iou};

#[test]
fn exact_flow_recovers_both_parts_and_their_motions() {
    let pair = hinge();
    for segmenter in segmenters() {
        let prediction = segmenter.segment(pair.input(), &pair.truth().flow).expect("segments");
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
        let flow = corrupt_flow(&pair.truth().flow, 0.05, 0.10, seed);
        for segmenter in segmenters() {
            let prediction = segmenter.segment(pair.input(), &flow).expect("segments");
            let iou = min_iou(&prediction, &pair.truth().part_p);
            assert!(iou > 0.8, "{} seed {seed}: IoU {iou}", segmenter.name());
        }
    }
}

#[test]
fn degenerate_inputs_give_a_valid_prediction_or_an_error() {
    for (case, input, flow) in degenerate_inputs() {
        for segmenter in segmenters() {
            let name = format!("{} on {case}", segmenter.name());
            match segmenter.segment(&input, &flow) {
                Ok(prediction) => assert_valid(&name, &input, &prediction),
                Err(e) => assert!(!e.to_string().is_empty(), "{name}"),
            }
            // Inputs that are degenerate but well defined must get a prediction.
            if ["collinear", "zero flow", "three points", "repeated point"].contains(&case) {
                let prediction = segmenter.segment(&input, &flow).expect(&name);
                if case == "zero flow" {
                    assert_eq!(prediction.motions.len(), 1, "{name}: one rigid part");
                }
            }
        }
    }
}

#[test]
fn results_depend_on_the_pair_not_on_the_call() {
    let pair = hinge();
    let flow = corrupt_flow(&pair.truth().flow, 0.05, 0.10, 9);
    for segmenter in segmenters() {
        let a = segmenter.segment(pair.input(), &flow).expect("segments");
        let b = segmenter.segment(pair.input(), &flow).expect("segments");
        assert_eq!(a, b, "{}: deterministic", segmenter.name());
    }
}
