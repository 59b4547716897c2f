//! Conformance of `pairs::metrics::conventions` with the reference implementations: the
//! fixture holds the values PARIS's and DigitalTwinArt's own metric functions computed on
//! fixed cases (`fixtures/joint_conventions/make_fixtures.py` says how); ours must agree to
//! 1e-6 on every case.

use nalgebra::{Matrix3, Vector3};
use pairs::metrics::conventions::{
    axis_angle_deg, axis_distance, rotation_state_deg, translation_state, AxisLine, JointConvention,
};
use serde_json::Value;

fn vector(v: &Value) -> Vector3<f64> {
    let a: Vec<f64> = serde_json::from_value(v.clone()).expect("three numbers");
    Vector3::new(a[0], a[1], a[2])
}

fn matrix(v: &Value) -> Matrix3<f64> {
    let rows: Vec<Vec<f64>> = serde_json::from_value(v.clone()).expect("a 3 x 3 matrix");
    Matrix3::from_fn(|r, c| rows[r][c])
}

fn close(ours: f64, theirs: &Value, what: &str) {
    let theirs = theirs.as_f64().expect("a number");
    assert!((ours - theirs).abs() <= 1e-6, "{what}: ours {ours}, reference {theirs}");
}

#[test]
fn every_fixture_case_agrees_with_the_reference_implementations() {
    let text = include_str!("fixtures/joint_conventions/joint_conventions.json");
    let fixture: Value = serde_json::from_str(text).expect("the fixture parses");
    let axes = fixture["axes"].as_array().expect("axis cases");
    assert!(axes.len() >= 7);
    for (i, case) in axes.iter().enumerate() {
        let predicted = AxisLine {
            origin: vector(&case["pred_origin"]),
            direction: vector(&case["pred_direction"]),
        };
        let truth = AxisLine {
            origin: vector(&case["true_origin"]),
            direction: vector(&case["true_direction"]),
        };
        let (p, d) = (JointConvention::Paris, JointConvention::DigitalTwinArt);
        let angle = |c| axis_angle_deg(c, &predicted.direction, &truth.direction);
        close(angle(p), &case["paris_angle_deg"], &format!("axis case {i}: PARIS angle"));
        close(angle(d), &case["dta_angle_deg"], &format!("axis case {i}: DTA angle"));
        let distance = |c| axis_distance(c, &predicted, &truth);
        close(distance(p), &case["paris_distance"], &format!("axis case {i}: PARIS distance"));
        close(
            distance(d),
            &case["dta_reported_distance"],
            &format!("axis case {i}: DTA distance (x 10)"),
        );
    }
    for (i, case) in fixture["rotations"].as_array().expect("rotation cases").iter().enumerate() {
        let ours =
            rotation_state_deg(&matrix(&case["pred_rotation"]), &matrix(&case["true_rotation"]));
        close(ours, &case["paris_state_deg"], &format!("rotation case {i}: PARIS"));
        close(ours, &case["dta_state_deg"], &format!("rotation case {i}: DTA"));
    }
    for (i, case) in
        fixture["translations"].as_array().expect("translation cases").iter().enumerate()
    {
        let ours = translation_state(
            &vector(&case["pred_translation"]),
            &vector(&case["true_translation"]),
        );
        close(ours, &case["paris_state"], &format!("translation case {i}: PARIS"));
        close(ours, &case["dta_state"], &format!("translation case {i}: DTA"));
    }
}
