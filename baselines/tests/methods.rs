//! The requirements on the methods that estimate their own flow (NRR, NN, ICP, ED,
//! FPFH): non-rigid fits beat rigid ICP on a two-part pair, and degenerate inputs give a
//! valid prediction or an error.

mod support;

use baselines::registration::mean_closest_distance;
use baselines::{methods, EmbeddedDeformation, IcpFlow, Nrr};
use pairs::math::Point3;
use pairs::{Method, PairInput, Prediction};
use support::{assert_valid, degenerate_inputs, hinge};

/// Mean distance from P moved by the prediction's flow to Q.
fn distance_to_q(input: &PairInput, prediction: &Prediction) -> f32 {
    let flow = prediction.flow.as_ref().expect("a flow method reports its flow");
    let moved: Vec<Point3> = input.p.points.iter().zip(flow).map(|(x, f)| x + f).collect();
    mean_closest_distance(&moved, &input.q.points)
}

#[test]
fn non_rigid_methods_fit_a_two_part_pair_better_than_rigid_icp() {
    let pair = hinge();
    let input = pair.input();
    let icp = distance_to_q(input, &IcpFlow::default().predict(input).expect("icp"));
    let ed = distance_to_q(input, &EmbeddedDeformation::default().predict(input).expect("ed"));
    let nrr_prediction = Nrr::default().predict(input).expect("nrr");
    let nrr = distance_to_q(input, &nrr_prediction);
    assert!(ed < icp, "ED {ed} vs ICP {icp}");
    assert!(nrr < icp, "NRR {nrr} vs ICP {icp}");
    assert_valid("nrr", input, &nrr_prediction);
}

#[test]
fn every_method_reports_a_valid_flow_on_the_hinge() {
    let pair = hinge();
    for method in methods() {
        let prediction = method.predict(pair.input()).expect("predicts");
        assert_valid(method.name(), pair.input(), &prediction);
        assert!(prediction.flow.is_some(), "{}: reports its flow", method.name());
    }
}

#[test]
fn degenerate_inputs_give_a_valid_prediction_or_an_error() {
    for (case, input, _) in degenerate_inputs() {
        for method in methods() {
            let name = format!("{} on {case}", method.name());
            match method.predict(&input) {
                Ok(prediction) => assert_valid(&name, &input, &prediction),
                Err(e) => assert!(!e.to_string().is_empty(), "{name}"),
            }
            if ["collinear", "three points", "repeated point"].contains(&case) {
                method.predict(&input).expect(&name);
            }
        }
    }
}
