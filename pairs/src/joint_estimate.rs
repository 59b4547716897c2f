//! Joints estimated from predicted part motions (beyond the paper): each segment's motion
//! relative to a reference segment (the largest, taken as the static base) is classified as
//! revolute (it rotates) or prismatic (it only translates), with its axis and, for a
//! revolute joint, a pivot on the axis. Everything is in P's normalised frame, the frame of
//! [`crate::JointTruth::axis_p`] and [`crate::JointTruth::pivot_p`].

use crate::joints::JointKind;
use crate::math::{Point3, Real, Vector3};
use crate::screw::Screw;
use crate::transform::Similarity;

/// A joint estimated from two motions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointEstimate {
    /// Revolute or prismatic.
    pub kind: JointKind,
    /// Unit axis direction, P's normalised frame (for a revolute joint, the right-handed
    /// rotation axis; for a prismatic one, the direction of travel).
    pub axis: Vector3,
    /// A point on the axis: for a revolute joint the one nearest the segment's centroid; for
    /// a prismatic joint (whose axis has no position) the centroid itself.
    pub pivot: Point3,
    /// Rotation angle in radians, or translation distance in normalised units.
    pub value: Real,
}

/// Thresholds of [`estimate_joint`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointParams {
    /// A relative rotation of at least this many degrees makes a revolute joint.
    pub min_angle_deg: Real,
    /// Below `min_angle_deg`, a relative translation of at least this (normalised units)
    /// makes a prismatic joint; less is no joint (the segment moves with the base).
    pub min_translation: Real,
}

impl Default for JointParams {
    /// 5° and 0.01 (1% of the bounding-box diagonal).
    fn default() -> Self {
        Self { min_angle_deg: 5.0, min_translation: 0.01 }
    }
}

/// The motion of `part` seen from `base`: `base⁻¹ ∘ part`, a rigid motion of P's frame
/// (the shared scale of a pair's motions cancels; a small difference between separately
/// fitted scales is dropped).
pub fn relative_motion(base: &Similarity, part: &Similarity) -> Similarity {
    let inverse_rotation = base.rotation.transpose();
    Similarity {
        rotation: inverse_rotation * part.rotation,
        translation: inverse_rotation * (part.translation - base.translation) / base.scale,
        scale: 1.0,
    }
}

/// The joint that moves a segment with centroid `centroid` by `part` relative to `base`;
/// `None` when the relative motion is below both thresholds or not finite.
pub fn estimate_joint(
    base: &Similarity,
    part: &Similarity,
    centroid: &Point3,
    params: &JointParams,
) -> Option<JointEstimate> {
    let relative = relative_motion(base, part);
    if !relative.is_finite() {
        return None;
    }
    let screw = Screw::of(&relative);
    let t = relative.translation;
    match screw {
        Screw { axis, angle, pivot, .. } if angle.to_degrees() >= params.min_angle_deg => {
            // The axis point nearest the centroid.
            let pivot = pivot + axis * (centroid - pivot).dot(&axis);
            Some(JointEstimate { kind: JointKind::Revolute, axis, pivot, value: angle })
        }
        _ if t.norm() >= params.min_translation => Some(JointEstimate {
            kind: JointKind::Prismatic,
            axis: t / t.norm(),
            pivot: *centroid,
            value: t.norm(),
        }),
        _ => None,
    }
}

/// Joints of every segment relative to the largest segment of `labels` (ties to the lower
/// id): per segment `0..K` its estimate, `None` for the base itself and for segments that
/// do not move relative to it. `motions[k]` is segment k's motion.
pub fn estimate_joints(
    points: &[Point3],
    labels: &[u32],
    motions: &[Similarity],
    params: &JointParams,
) -> Vec<Option<JointEstimate>> {
    let k = motions.len();
    let mut sizes = vec![0usize; k];
    let mut sums = vec![Vector3::zeros(); k];
    for (p, &l) in points.iter().zip(labels) {
        if let Some(size) = sizes.get_mut(l as usize) {
            *size += 1;
            sums[l as usize] += p.coords;
        }
    }
    let Some(base) = (0..k).max_by(|&a, &b| sizes[a].cmp(&sizes[b]).then(b.cmp(&a))) else {
        return Vec::new();
    };
    (0..k)
        .map(|s| {
            if s == base || sizes[s] == 0 {
                return None;
            }
            let centroid = Point3::from(sums[s] / sizes[s] as Real);
            estimate_joint(&motions[base], &motions[s], &centroid, params)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Isometry3;
    use crate::transform::rotation_about;
    use std::f32::consts::FRAC_PI_2;

    fn similarity(iso: &Isometry3) -> Similarity {
        Similarity::from_isometry(iso)
    }

    #[test]
    fn a_quarter_turn_about_a_vertical_hinge() {
        // Rotating 90° about z through (1, 0, 0) maps (2, 0, 0) to (1, 1, 0): by hand,
        // R = [[0, -1, 0], [1, 0, 0], [0, 0, 1]], t = (1, -1, 0).
        let part =
            similarity(&rotation_about(&Point3::new(1.0, 0.0, 0.0), &Vector3::z(), FRAC_PI_2));
        assert!((part.translation - Vector3::new(1.0, -1.0, 0.0)).norm() < 1e-6);
        let centroid = Point3::new(2.0, 0.0, 0.3);
        let joint =
            estimate_joint(&Similarity::identity(), &part, &centroid, &JointParams::default())
                .expect("a joint");
        assert_eq!(joint.kind, JointKind::Revolute);
        assert!((joint.axis - Vector3::z()).norm() < 1e-5);
        assert!((joint.value - FRAC_PI_2).abs() < 1e-5);
        // The pivot is the axis point nearest the centroid: (1, 0, 0.3).
        assert!((joint.pivot - Point3::new(1.0, 0.0, 0.3)).norm() < 1e-5, "{}", joint.pivot);
    }

    #[test]
    fn a_moving_base_cancels_out() {
        // The same hinge, with the whole object also turned and shifted (and scaled, as
        // between two normalised frames): the joint is unchanged.
        let hinge = rotation_about(&Point3::new(1.0, 0.0, 0.0), &Vector3::z(), FRAC_PI_2);
        let global =
            rotation_about(&Point3::new(0.2, 0.5, -0.1), &Vector3::new(1.0, 1.0, 0.0), 0.7);
        let (hinge, global) = (similarity(&hinge), similarity(&global));
        let base = Similarity { scale: 0.8, ..global };
        // part = base ∘ hinge: x -> s R_g (R_h x + t_h) + t_g.
        let part = Similarity {
            rotation: base.rotation * hinge.rotation,
            translation: base.rotation * hinge.translation * base.scale + base.translation,
            scale: base.scale,
        };
        let joint =
            estimate_joint(&base, &part, &Point3::new(2.0, 0.0, 0.0), &JointParams::default())
                .expect("a joint");
        assert_eq!(joint.kind, JointKind::Revolute);
        assert!((joint.axis - Vector3::z()).norm() < 1e-4);
        assert!((joint.pivot - Point3::new(1.0, 0.0, 0.0)).norm() < 1e-4);
    }

    #[test]
    fn a_drawer_slides_and_a_still_part_has_no_joint() {
        let drawer =
            Similarity { translation: Vector3::new(0.0, 0.2, 0.0), ..Similarity::identity() };
        let centroid = Point3::new(0.1, 0.0, 0.0);
        let joint =
            estimate_joint(&Similarity::identity(), &drawer, &centroid, &JointParams::default())
                .expect("a joint");
        assert_eq!(joint.kind, JointKind::Prismatic);
        assert!((joint.axis - Vector3::y()).norm() < 1e-6);
        assert!((joint.value - 0.2).abs() < 1e-6);
        let still =
            Similarity { translation: Vector3::new(0.0, 0.005, 0.0), ..Similarity::identity() };
        assert!(estimate_joint(
            &Similarity::identity(),
            &still,
            &centroid,
            &JointParams::default()
        )
        .is_none());
    }

    #[test]
    fn joints_are_relative_to_the_largest_segment() {
        let points: Vec<Point3> = (0..10).map(|i| Point3::new(i as Real * 0.1, 0.0, 0.0)).collect();
        // Segment 1 (7 points) is the base; segment 0 slides relative to it.
        let labels = [0, 0, 0, 1, 1, 1, 1, 1, 1, 1];
        let shift = Vector3::new(0.0, 0.0, 0.3);
        let base =
            Similarity { translation: Vector3::new(0.1, 0.0, 0.0), ..Similarity::identity() };
        let slid = Similarity { translation: base.translation + shift, ..base };
        let joints = estimate_joints(&points, &labels, &[slid, base], &JointParams::default());
        assert_eq!(joints.len(), 2);
        assert!(joints[1].is_none());
        let j = joints[0].expect("segment 0 slides");
        assert_eq!(j.kind, JointKind::Prismatic);
        assert!((j.axis - Vector3::z()).norm() < 1e-6);
        assert!((j.pivot - Point3::new(0.1, 0.0, 0.0)).norm() < 1e-6);
        assert!(estimate_joints(&[], &[], &[], &JointParams::default()).is_empty());
    }
}
