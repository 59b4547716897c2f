//! Joint metrics in the field's conventions (Ditto, DigitalTwinArt; docs/METRICS.md,
//! "Joints"): every ground-truth joint is matched to a predicted joint through the part
//! matching of the IoU metric (the joint of the segment matched to the joint's part), then
//! scored by
//!
//! - type: the estimate's kind equals the truth's (a joint with no estimate is wrong);
//! - axis angle: `min(θ, 180° − θ)` between the two directions, in degrees;
//! - axis line distance, revolute joints estimated as revolute: the shortest distance
//!   between the two axis lines (normalised units of P);
//! - state error, when the type is right: the absolute difference of the angle turned
//!   (degrees, revolute) or the distance slid (P's normalised units, prismatic) between
//!   P's and Q's states.
//!
//! Predicted joints are the method's own when it gives them ([`joint_errors_of`], e.g. from
//! a prediction file) and otherwise come from the segments' motions through
//! [`crate::joint_estimate::estimate_joints`] (each segment relative to the largest one).

use crate::joint_estimate::{estimate_joints, JointEstimate, JointParams};
use crate::joints::{JointKind, JointTruth};
use crate::math::{Point3, Vector3};
use crate::transform::{axis_error_deg, Similarity};

use super::segmentation::PartMatching;

/// The scores of one ground-truth joint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointError {
    /// The true joint's kind.
    pub truth: JointKind,
    /// The matched estimate's kind; `None` when the joint's part has no segment or that
    /// segment does not move relative to the base.
    pub estimated: Option<JointKind>,
    /// Axis angle error `min(θ, 180° − θ)` in degrees, when there is an estimate.
    pub axis_deg: Option<f64>,
    /// Distance between the true and the estimated axis lines, for a revolute joint
    /// estimated as revolute.
    pub line_distance: Option<f64>,
    /// `|estimated − true|` state change, when the type is right: degrees for revolute
    /// joints, P's normalised units for prismatic ones.
    pub state_error: Option<f64>,
}

impl JointError {
    /// Whether the type is right.
    pub fn type_correct(&self) -> bool {
        self.estimated == Some(self.truth)
    }
}

/// Shortest distance between the line through `a` along `u` and the line through `b` along
/// `v` (directions need not be unit; parallel lines give the distance of `b` from the first
/// line).
pub fn line_to_line_distance(a: &Point3, u: &Vector3, b: &Point3, v: &Vector3) -> f64 {
    let (u, v) = (u.cast::<f64>(), v.cast::<f64>());
    let d = (b - a).cast::<f64>();
    let n = u.cross(&v);
    let n_norm = n.norm();
    let (u_norm, v_norm) = (u.norm(), v.norm());
    if u_norm == 0.0 || v_norm == 0.0 {
        return d.norm();
    }
    // Nearly parallel (sin of the angle below 1e-6): the distance of b from the first line.
    if n_norm <= 1e-6 * u_norm * v_norm {
        let along = u / u_norm;
        return (d - along * d.dot(&along)).norm();
    }
    d.dot(&n).abs() / n_norm
}

/// The true state change of `joint` between P and Q: degrees turned (revolute) or the
/// distance slid in P's normalised units (prismatic; `scale_p` is P's normalisation scale,
/// its bounding-box diagonal in object units).
pub fn true_state_change(joint: &JointTruth, scale_p: f32) -> f64 {
    let change = f64::from((joint.value_q - joint.value_p).abs());
    match joint.kind {
        JointKind::Revolute => change.to_degrees(),
        JointKind::Prismatic => change / f64::from(scale_p.max(f32::MIN_POSITIVE)),
    }
}

/// The estimate's state change in the units of [`true_state_change`]: its magnitude, as the
/// truth's (an axis and value may both be flipped).
fn estimated_state_change(estimate: &JointEstimate) -> f64 {
    let change = f64::from(estimate.value.abs());
    match estimate.kind {
        JointKind::Revolute => change.to_degrees(),
        JointKind::Prismatic => change,
    }
}

/// Scores one true joint against the estimate matched to it.
pub fn score_joint(
    joint: &JointTruth,
    estimate: Option<&JointEstimate>,
    scale_p: f32,
) -> JointError {
    let Some(estimate) = estimate else {
        return JointError {
            truth: joint.kind,
            estimated: None,
            axis_deg: None,
            line_distance: None,
            state_error: None,
        };
    };
    let both_revolute = joint.kind == JointKind::Revolute && estimate.kind == JointKind::Revolute;
    let line_distance = both_revolute.then(|| {
        line_to_line_distance(&estimate.pivot, &estimate.axis, &joint.pivot_p, &joint.axis_p)
    });
    let state_error = (estimate.kind == joint.kind)
        .then(|| (estimated_state_change(estimate) - true_state_change(joint, scale_p)).abs());
    JointError {
        truth: joint.kind,
        estimated: Some(estimate.kind),
        axis_deg: Some(f64::from(axis_error_deg(&estimate.axis, &joint.axis_p))),
        line_distance,
        state_error,
    }
}

/// Scores every true joint of a pair: the joints are estimated from the predicted segments
/// of P (`segments`, with `motions[segment]`) and matched through `matching` (the part →
/// segment matching of [`super::matched_iou`]). `scale_p` is P's normalisation scale.
pub fn joint_errors(
    points_p: &[Point3],
    segments: &[u32],
    motions: &[Similarity],
    matching: &PartMatching,
    truth: &[JointTruth],
    scale_p: f32,
) -> Vec<JointError> {
    let estimates = estimate_joints(points_p, segments, motions, &JointParams::default());
    joint_errors_of(&estimates, matching, truth, scale_p)
}

/// Every ground-truth joint scored against `estimates[s]`, the joint a method gives segment
/// `s` (its own estimate, or [`estimate_joints`]'), where `s` is the segment matched to the
/// joint's part; a joint whose part has no matched segment, or whose segment has no joint,
/// is scored as missed.
pub fn joint_errors_of(
    estimates: &[Option<JointEstimate>],
    matching: &PartMatching,
    truth: &[JointTruth],
    scale_p: f32,
) -> Vec<JointError> {
    truth
        .iter()
        .map(|joint| {
            let estimate = matching
                .segment
                .get(usize::from(joint.part))
                .copied()
                .flatten()
                .and_then(|s| estimates.get(s as usize).copied().flatten());
            score_joint(joint, estimate.as_ref(), scale_p)
        })
        .collect()
}

/// Joint scores summed over pairs (the iteration board's joint columns): how many true
/// joints were seen, how many got the right type, and the axis errors and axis-line
/// distances of those with an estimate.
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
    /// The summed scores of `errors` (one pair's [`JointError`]s, say).
    pub fn of(errors: &[JointError]) -> Self {
        let mut scores = JointScores::default();
        for joint in errors {
            scores.joints += 1;
            scores.type_correct += usize::from(joint.type_correct());
            scores.axis_errors.extend(joint.axis_deg);
            scores.pivot_distances.extend(joint.line_distance);
        }
        scores
    }

    /// Adds another set of scores (e.g. one pair's) to these.
    pub fn merge(&mut self, other: JointScores) {
        self.joints += other.joints;
        self.type_correct += other.type_correct;
        self.axis_errors.extend(other.axis_errors);
        self.pivot_distances.extend(other.pivot_distances);
    }

    /// Fraction of joints with the right type.
    pub fn type_accuracy(&self) -> f64 {
        self.type_correct as f64 / self.joints.max(1) as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn revolute(axis: Vector3, pivot: Point3, value: f32) -> JointEstimate {
        JointEstimate { kind: JointKind::Revolute, axis, pivot, value }
    }

    fn truth(kind: JointKind, axis: Vector3, pivot: Point3, p: f32, q: f32) -> JointTruth {
        JointTruth {
            part: 1,
            kind,
            axis_p: axis,
            pivot_p: pivot,
            axis_q: axis,
            pivot_q: pivot,
            value_p: p,
            value_q: q,
        }
    }

    #[test]
    fn line_distances_by_hand() {
        // The x axis and a line along y through (0, 0, 2): skew, 2 apart.
        let d = line_to_line_distance(
            &Point3::origin(),
            &Vector3::x(),
            &Point3::new(5.0, 0.0, 2.0),
            &Vector3::y(),
        );
        assert!((d - 2.0).abs() < 1e-12, "{d}");
        // Parallel lines 3 apart (and opposite directions).
        let d = line_to_line_distance(
            &Point3::origin(),
            &Vector3::z(),
            &Point3::new(3.0, 0.0, 7.0),
            &(-Vector3::z() * 2.0),
        );
        assert!((d - 3.0).abs() < 1e-12, "{d}");
        // Intersecting lines: 0.
        let d = line_to_line_distance(
            &Point3::new(1.0, 1.0, 1.0),
            &Vector3::x(),
            &Point3::new(1.0, 1.0, 1.0),
            &Vector3::new(0.0, 1.0, 1.0),
        );
        assert!(d.abs() < 1e-12, "{d}");
    }

    #[test]
    fn a_revolute_joint_by_hand() {
        // Truth: hinge along z through (0.1, 0, 0), turned from 10° to 40° (30°).
        let t = truth(
            JointKind::Revolute,
            Vector3::z(),
            Point3::new(0.1, 0.0, 0.0),
            10f32.to_radians(),
            40f32.to_radians(),
        );
        // Estimate: the axis flipped and tilted by 10° about x, through (0.1, 0.05, 0),
        // turning 25°.
        let tilt = 10f32.to_radians();
        let axis = -Vector3::new(0.0, -tilt.sin(), tilt.cos());
        let e = revolute(axis, Point3::new(0.1, 0.05, 0.0), 25f32.to_radians());
        let s = score_joint(&t, Some(&e), 2.0);
        assert!(s.type_correct());
        // A flipped axis is the same line: min(170°, 10°) = 10°.
        assert!((s.axis_deg.unwrap() - 10.0).abs() < 1e-3, "{s:?}");
        // The tilted line passes through (0.1, 0.05, 0) in the plane x = 0.1, the true axis
        // is the line x = 0.1, y = 0: both lie in the plane x = 0.1 and are not parallel, so
        // they meet: distance 0.
        assert!(s.line_distance.unwrap().abs() < 1e-6, "{s:?}");
        assert!((s.state_error.unwrap() - 5.0).abs() < 1e-3, "{s:?}");
    }

    #[test]
    fn prismatic_state_in_normalised_units_and_wrong_types() {
        // Slid 0.4 object units; P's diagonal is 2 object units, so 0.2 normalised units.
        let t = truth(JointKind::Prismatic, Vector3::x(), Point3::origin(), 0.1, 0.5);
        assert!((true_state_change(&t, 2.0) - 0.2).abs() < 1e-6);
        let e = JointEstimate {
            kind: JointKind::Prismatic,
            axis: Vector3::new(1.0, 1.0, 0.0) / 2f32.sqrt(),
            pivot: Point3::new(3.0, 3.0, 3.0),
            value: 0.25,
        };
        let s = score_joint(&t, Some(&e), 2.0);
        assert!((s.axis_deg.unwrap() - 45.0).abs() < 1e-3, "{s:?}");
        assert_eq!(s.line_distance, None, "no line distance for prismatic joints");
        assert!((s.state_error.unwrap() - 0.05).abs() < 1e-6, "{s:?}");
        // A revolute estimate of a prismatic joint: wrong type, axis scored, no state.
        let r = revolute(Vector3::x(), Point3::origin(), 1.0);
        let s = score_joint(&t, Some(&r), 2.0);
        assert!(!s.type_correct());
        assert_eq!((s.state_error, s.line_distance), (None, None));
        assert!(s.axis_deg.unwrap().abs() < 1e-3);
        // No estimate at all.
        let s = score_joint(&t, None, 2.0);
        assert!(!s.type_correct());
        assert_eq!(s.axis_deg, None);
    }
}
