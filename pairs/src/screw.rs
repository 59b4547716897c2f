//! Rigid motions as screws (Chasles' theorem): a rotation by an angle about an axis line
//! through a pivot, plus a slide along that axis. The screw gives the SE(3) geodesic between
//! the identity and a motion (`exp(τ log M)`), which keeps a hinged part turning about its
//! hinge when a motion is animated, and the joint estimates' axes and pivots.

use nalgebra::Matrix3 as Matrix3d;

use crate::math::{Point3, Real, Rotation3, Vector3};
use crate::transform::Similarity;

/// A rigid motion as a screw; `x -> rotation about (pivot, axis) by angle, then + slide·axis`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Screw {
    /// Unit axis (any unit vector when the angle is 0).
    pub axis: Vector3,
    /// Rotation angle in radians, 0 to π.
    pub angle: Real,
    /// The point of the axis line nearest the origin (the origin when the angle is 0).
    pub pivot: Point3,
    /// Translation along the axis; with angle 0, the whole translation is `slide · axis`.
    pub slide: Real,
}

impl Screw {
    /// The screw of the rigid part of `m` (its rotation and translation; scale ignored).
    pub fn of(m: &Similarity) -> Self {
        let t = m.translation;
        match Rotation3::from_matrix(&m.rotation).axis_angle() {
            Some((axis, angle)) if angle > 1e-6 => {
                let axis = axis.into_inner();
                let slide = t.dot(&axis);
                // Points c of the axis satisfy (I - R) c = t - slide·a, singular along a;
                // the pseudo-inverse gives the solution nearest the origin.
                let system = Matrix3d::<f64>::identity() - m.rotation.cast::<f64>();
                let rhs = (t - axis * slide).cast::<f64>();
                let pivot = system
                    .pseudo_inverse(1e-9)
                    .map_or(Point3::origin(), |inv| Point3::from((inv * rhs).cast::<Real>()));
                Self { axis, angle, pivot, slide }
            }
            _ => {
                let norm = t.norm();
                let axis = if norm > 0.0 { t / norm } else { Vector3::z() };
                Self { axis, angle: 0.0, pivot: Point3::origin(), slide: norm }
            }
        }
    }

    /// The motion a fraction `tau` along the screw (0: identity, 1: the whole motion).
    pub fn at(&self, tau: Real) -> Similarity {
        let rotation = Rotation3::new(self.axis * (self.angle * tau)).into_inner();
        let translation =
            self.pivot.coords - rotation * self.pivot.coords + self.axis * (self.slide * tau);
        Similarity { rotation, translation, scale: 1.0 }
    }
}

/// The similarity `m` a fraction `tau` of the way from the identity: its rigid part along
/// the screw (the SE(3) geodesic), its scale geometrically (`scale^tau`).
pub fn interpolate_screw(m: &Similarity, tau: Real) -> Similarity {
    Similarity { scale: m.scale.powf(tau), ..Screw::of(m).at(tau) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::transform::rotation_about;

    #[test]
    fn a_hinge_turns_about_its_pivot_all_the_way() {
        let hinge = Similarity::from_isometry(&rotation_about(
            &Point3::new(1.0, 2.0, 0.0),
            &Vector3::z(),
            2.0,
        ));
        let screw = Screw::of(&hinge);
        assert!((screw.pivot - Point3::new(1.0, 2.0, 0.0)).norm() < 1e-5);
        assert!(screw.slide.abs() < 1e-6);
        let x = Point3::new(3.0, 2.0, 0.5);
        for k in 0..=10 {
            let m = interpolate_screw(&hinge, k as Real / 10.0);
            // Every intermediate position stays at distance 2 from the hinge line.
            let r = m.apply(&x) - Point3::new(1.0, 2.0, 0.5);
            assert!((r.norm() - 2.0).abs() < 1e-4);
        }
        assert!((interpolate_screw(&hinge, 1.0).apply(&x) - hinge.apply(&x)).norm() < 1e-5);
        assert!((interpolate_screw(&hinge, 0.0).apply(&x) - x).norm() < 1e-6);
    }

    #[test]
    fn a_slide_is_linear_and_a_screw_advances_along_its_axis() {
        let slide =
            Similarity { translation: Vector3::new(0.0, 0.4, 0.0), ..Similarity::identity() };
        let half = interpolate_screw(&slide, 0.5);
        assert!((half.translation - Vector3::new(0.0, 0.2, 0.0)).norm() < 1e-6);
        let turn = rotation_about(&Point3::new(0.0, 1.0, 0.0), &Vector3::x(), 1.0);
        let screw = Similarity {
            translation: turn.translation.vector + Vector3::new(0.3, 0.0, 0.0),
            ..Similarity::from_isometry(&turn)
        };
        let s = Screw::of(&screw);
        assert!((s.slide - 0.3).abs() < 1e-5);
        assert!((s.pivot - Point3::new(0.0, 1.0, 0.0)).norm() < 1e-5);
        let end = interpolate_screw(&screw, 1.0);
        assert!((end.translation - screw.translation).norm() < 1e-5);
    }
}
