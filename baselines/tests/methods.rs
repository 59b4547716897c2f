//! The requirements on the methods that estimate their own flow (NRR, NN, ICP, ED,
//! FPFH): non-rigid fits beat rigid ICP on the true flow of an articulated pair, and
//! degenerate inputs give a valid prediction or the input error they call for.

mod support;

use baselines::{methods, EmbeddedDeformation, IcpFlow, Nrr, NrrParams};
use pairs::math::Vector3;
use pairs::Method;
use support::{
    assert_outcome, assert_valid, degenerate_inputs, epe_to_truth, expected_input_error,
};

/// The flows are compared by EPE against the true flow, not by how close the moved P lies
/// to Q: a fit can hug Q's surface while sliding every point to the wrong place.
///
/// The pair is the planted lamp (`support::lamp`) rather than the hinge: the hinge's two
/// flat squares are nearly interchangeable, so NRR's FPFH matches on it are mostly wrong
/// (about 15% land within 0.05 of their true target at 0.2 rad, against about 40% on the
/// lamp) and pull NRR off (EPE 0.12 at 0.2 rad where ICP has 0.012 and the zero flow 0.034);
/// at the hinge's 0.8 rad, ICP and ED themselves end up worse than the zero flow. The lamp's
/// base and arm are boxes of different shapes, so descriptors and closest points both point
/// to the true motion, and at these angles the articulation is small enough for closest
/// points: the non-rigid fits must then follow the arm, which one rigid motion cannot.
#[test]
fn non_rigid_methods_beat_rigid_icp_on_the_true_flow_of_an_articulated_pair() {
    for (axis, angle) in
        [(Vector3::y(), 0.3), (Vector3::y(), 0.4), (Vector3::y(), 0.6), (Vector3::x(), 0.4)]
    {
        let pair = support::lamp(axis, angle);
        let input = pair.input();
        let case = format!("lamp turned {angle} rad about {:?}", axis.as_slice());
        let icp = epe_to_truth(&pair, &IcpFlow::default().predict(input).expect("icp"));
        let ed_prediction = EmbeddedDeformation::default().predict(input).expect("ed");
        let ed = epe_to_truth(&pair, &ed_prediction);
        let nrr_prediction = Nrr::default().predict(input).expect("nrr");
        let nrr = epe_to_truth(&pair, &nrr_prediction);
        assert!(ed < icp, "{case}: ED EPE {ed} vs ICP EPE {icp}");
        assert!(nrr < icp, "{case}: NRR EPE {nrr} vs ICP EPE {icp}");
        assert_valid("ed", input, &ed_prediction);
        assert_valid("nrr", input, &nrr_prediction);
    }
}

/// On the hinge turned by 0.4 rad (small enough for closest points), ED and NRR's
/// registration without its descriptor matches both beat ICP on the true flow; with the
/// default descriptor weight NRR does not (see the lamp test above for why).
#[test]
fn closest_point_non_rigid_fits_beat_rigid_icp_on_the_true_flow_of_the_hinge() {
    let pair = pairs::synthetic::hinge_pair("hinge", 12, 0.4);
    let input = pair.input();
    let icp = epe_to_truth(&pair, &IcpFlow::default().predict(input).expect("icp"));
    let ed = epe_to_truth(&pair, &EmbeddedDeformation::default().predict(input).expect("ed"));
    let no_features = NrrParams { weight_features: 0.0, ..NrrParams::default() };
    let nrr = epe_to_truth(&pair, &Nrr::with_params(no_features).predict(input).expect("nrr"));
    assert!(ed < icp, "ED EPE {ed} vs ICP EPE {icp}");
    assert!(nrr < icp, "NRR (no descriptor matches) EPE {nrr} vs ICP EPE {icp}");
}

#[test]
fn every_method_reports_a_valid_flow_on_the_hinge() {
    let pair = support::hinge();
    for method in methods() {
        let prediction = method.predict(pair.input()).expect("predicts");
        assert_valid(method.name(), pair.input(), &prediction);
        assert!(prediction.flow.is_some(), "{}: reports its flow", method.name());
    }
}

/// Methods see P and Q only: the flow cases are well-formed pairs for them and must be
/// predicted; too few points and NaN points must be refused with exactly that input error.
#[test]
fn degenerate_inputs_give_a_valid_prediction_or_the_right_error() {
    for (case, input, _) in degenerate_inputs() {
        for method in methods() {
            let name = format!("{} on {case}", method.name());
            let expected = expected_input_error(case, false);
            assert_outcome(&name, method.name(), &input, method.predict(&input), expected);
        }
    }
}
