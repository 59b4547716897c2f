//! Joint errors in the conventions of the image-based methods' papers, so that a number can
//! be read the way PARIS (Liu et al. 2023) or DigitalTwinArt (Weng et al. 2024; ArtGS
//! reports in its protocol) would print it. They differ from each other and from this
//! project's own joint metric ([`super::joints`]) in three places:
//!
//! | | axis angle | axis line distance | revolute state | prismatic state |
//! |---|---|---|---|---|
//! | PARIS (`systems/criterions.py`) | `acos(abs(cos θ))` | **0 when the directions are exactly parallel**, else the skew-line distance | geodesic angle of `R̂ Rᵀ` | `‖d̂ â − d a‖` |
//! | DigitalTwinArt (`utils/articulation_utils.py`) | `min(θ, 180° − θ)` | the distance of the true origin from the predicted line when `‖â × a‖ < 1e-6`, else the skew-line distance; **reported × 10** (`eval/eval_results.py`) | geodesic angle of `R̂ Rᵀ` | `‖t̂ − t‖` |
//!
//! Every function takes f64 and follows its reference's arithmetic; the conformance test
//! checks them against values the reference functions computed
//! (`pairs/tests/fixtures/joint_conventions/`), to 1e-6. One deliberate difference: the
//! cosine is clamped to [-1, 1] before `acos` (DigitalTwinArt's is not, and returns NaN when
//! rounding pushes it past 1).

use nalgebra::{Matrix3, Vector3};

/// Whose convention a joint error follows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum JointConvention {
    /// PARIS (`3dlg-hcvc/paris`, `systems/criterions.py`: `axis_metrics`,
    /// `geodesic_distance`, `translational_error`).
    Paris,
    /// DigitalTwinArt (`NVlabs/DigitalTwinArt`, `utils/articulation_utils.py`:
    /// `line_distance`, `eval_axis_and_state`; the distance × 10 of `eval/eval_results.py`).
    /// ArtGS reports in this protocol.
    DigitalTwinArt,
}

impl JointConvention {
    /// Every convention.
    pub const ALL: [JointConvention; 2] = [JointConvention::Paris, JointConvention::DigitalTwinArt];

    /// The short name used in tables (`paris`, `dta`).
    pub fn as_str(self) -> &'static str {
        match self {
            JointConvention::Paris => "paris",
            JointConvention::DigitalTwinArt => "dta",
        }
    }
}

/// A joint axis as a line: a point on it and a direction (any length).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxisLine {
    /// A point on the axis.
    pub origin: Vector3<f64>,
    /// Its direction; need not be unit.
    pub direction: Vector3<f64>,
}

/// The angle between the predicted and the true axis directions, degrees, sign-blind in
/// both conventions (PARIS: `acos(abs(cos θ))`; DigitalTwinArt: `min(θ, 180° − θ)`).
pub fn axis_angle_deg(
    convention: JointConvention,
    predicted: &Vector3<f64>,
    truth: &Vector3<f64>,
) -> f64 {
    let cos = (predicted.dot(truth) / (predicted.norm() * truth.norm())).clamp(-1.0, 1.0);
    match convention {
        JointConvention::Paris => cos.abs().acos().to_degrees(),
        JointConvention::DigitalTwinArt => {
            let angle = cos.acos().to_degrees();
            angle.min(180.0 - angle)
        }
    }
}

/// The distance between the predicted and the true axis lines as the convention reports it:
/// PARIS gives 0 for exactly parallel directions (whatever their offset); DigitalTwinArt
/// gives the true origin's distance from the predicted line (`‖(o − ô) × â‖`) when the
/// directions are within 1e-6 of parallel, and multiplies every distance by 10.
pub fn axis_distance(convention: JointConvention, predicted: &AxisLine, truth: &AxisLine) -> f64 {
    let normal = predicted.direction.cross(&truth.direction);
    match convention {
        JointConvention::Paris => {
            if normal == Vector3::zeros() {
                0.0
            } else {
                (truth.origin - predicted.origin).dot(&normal).abs() / normal.norm()
            }
        }
        JointConvention::DigitalTwinArt => {
            let distance = if normal.norm() < 1e-6 {
                (truth.origin - predicted.origin).cross(&predicted.direction).norm()
            } else {
                normal.dot(&(predicted.origin - truth.origin)).abs() / normal.norm()
            };
            10.0 * distance
        }
    }
}

/// The revolute state error, degrees: the geodesic angle of `R̂ Rᵀ` between the predicted
/// and the true rotations of the part (the same in both conventions).
pub fn rotation_state_deg(predicted: &Matrix3<f64>, truth: &Matrix3<f64>) -> f64 {
    let cos = (((predicted * truth.transpose()).trace() - 1.0) * 0.5).clamp(-1.0, 1.0);
    cos.acos().to_degrees()
}

/// The prismatic state error: the distance between the predicted and the true translations
/// of the part (DigitalTwinArt `‖t̂ − t‖`; PARIS `‖d̂ â − d a‖` with unit directions, the
/// same for translations `t = d a`).
pub fn translation_state(predicted: &Vector3<f64>, truth: &Vector3<f64>) -> f64 {
    (predicted - truth).norm()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parallel_offset_axes_separate_the_conventions() {
        let predicted = AxisLine { origin: Vector3::new(0.3, 0.0, 0.0), direction: Vector3::y() };
        let truth = AxisLine { origin: Vector3::new(0.0, 0.0, 0.4), direction: Vector3::y() };
        // PARIS: parallel lines are 0 apart; DigitalTwinArt: 0.5 apart, reported as 5.
        assert_eq!(axis_distance(JointConvention::Paris, &predicted, &truth), 0.0);
        let dta = axis_distance(JointConvention::DigitalTwinArt, &predicted, &truth);
        assert!((dta - 5.0).abs() < 1e-12, "{dta}");
        // Opposite directions are the same axis in both.
        let flipped = Vector3::new(0.0, -1.0, 0.0);
        for convention in JointConvention::ALL {
            assert_eq!(axis_angle_deg(convention, &flipped, &Vector3::y()), 0.0);
        }
    }
}
