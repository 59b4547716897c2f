//! Motion metrics beyond the paper: for each ground-truth part matched to a predicted
//! segment, the rotation error (degrees) and translation error of the segment's motion, and
//! whether the number of predicted segments equals the number of parts.

use super::segmentation::PartMatching;
use crate::transform::{rotation_error_deg, Similarity};

/// Motion errors of one pair's matched parts.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MotionErrors {
    /// Per matched part with a predicted motion, the geodesic rotation error in degrees.
    pub rotation_deg: Vec<f64>,
    /// Per matched part with a predicted motion, `||t̂ - t||` in Q's normalised units.
    pub translation: Vec<f64>,
}

/// Errors of the predicted segment motions (`motions[segment]`) against the ground-truth
/// part motions, for every part that `matching` paired with a segment that has a finite
/// motion. Parts without one are skipped (their IoU already counts them as wrong).
pub fn motion_errors(
    matching: &PartMatching,
    motions: &[Similarity],
    truth: &[Similarity],
) -> MotionErrors {
    let mut errors = MotionErrors::default();
    for (part, segment) in matching.segment.iter().enumerate() {
        let predicted = segment.and_then(|s| motions.get(s as usize)).filter(|m| m.is_finite());
        if let (Some(m), Some(t)) = (predicted, truth.get(part)) {
            errors.rotation_deg.push(f64::from(rotation_error_deg(&m.rotation, &t.rotation)));
            errors.translation.push(f64::from((m.translation - t.translation).norm()));
        }
    }
    errors
}

/// Number of distinct segment ids in a prediction.
pub fn segment_count(segments: &[u32]) -> usize {
    let mut ids = segments.to_vec();
    ids.sort_unstable();
    ids.dedup();
    ids.len()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{Matrix3, Rotation3, Vector3};

    #[test]
    fn hand_computed_errors() {
        let turn = |deg: f32| Similarity {
            rotation: *Rotation3::from_axis_angle(&Vector3::z_axis(), deg.to_radians()).matrix(),
            translation: Vector3::new(deg / 100.0, 0.0, 0.0),
            scale: 1.0,
        };
        let truth = [Similarity::identity(), turn(30.0), turn(60.0)];
        // Part 0 -> segment 1 (10 degrees off), part 1 -> segment 0 (exact), part 2 unmatched.
        let matching =
            PartMatching { segment: vec![Some(1), Some(0), None], iou: vec![0.5, 1.0, 0.0] };
        let errors = motion_errors(&matching, &[turn(30.0), turn(10.0)], &truth);
        assert_eq!(errors.rotation_deg.len(), 2);
        assert!((errors.rotation_deg[0] - 10.0).abs() < 1e-3);
        assert!(errors.rotation_deg[1].abs() < 1e-2);
        assert!((errors.translation[0] - 0.1).abs() < 1e-6);
        assert_eq!(errors.translation[1], 0.0);
        let broken = Similarity { rotation: Matrix3::from_element(f32::NAN), ..turn(0.0) };
        assert!(motion_errors(&matching, &[broken], &truth).rotation_deg.is_empty());
    }

    #[test]
    fn segment_count_counts_distinct_ids() {
        assert_eq!(segment_count(&[4, 4, 9, 0]), 3);
        assert_eq!(segment_count(&[]), 0);
    }
}
