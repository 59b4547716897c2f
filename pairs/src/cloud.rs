//! Point clouds and their normalisation (bounding box centred at the origin, diagonal 1).

use crate::math::{Point3, Real, Vector3};

/// How a cloud was normalised: `normalised = (object - centre) / scale`.
///
/// `centre` is the centre of the cloud's axis-aligned bounding box and `scale` the length of
/// its diagonal, both in the object's frame (object units), so that anything computed in the
/// normalised frame can be mapped back.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Normalisation {
    /// Centre of the axis-aligned bounding box, object frame.
    pub centre: Vector3,
    /// Length of the bounding-box diagonal, object units; always > 0.
    pub scale: Real,
}

impl Normalisation {
    /// The identity normalisation (centre 0, scale 1).
    pub const IDENTITY: Self = Self { centre: Vector3::new(0.0, 0.0, 0.0), scale: 1.0 };

    /// The normalisation of a set of points, or `None` if the set is empty, holds a
    /// non-finite coordinate, or its bounding box has a zero diagonal.
    pub fn of_points(points: &[Point3]) -> Option<Self> {
        if !points.iter().all(|p| p.coords.iter().all(|c| c.is_finite())) {
            return None;
        }
        let (lo, hi) = crate::math::bounds(points)?;
        let scale = (hi - lo).norm();
        (scale > 0.0 && scale.is_finite())
            .then(|| Self { centre: (lo.coords + hi.coords) * 0.5, scale })
    }

    /// Maps a point from the object frame to the normalised frame.
    pub fn apply(&self, p: &Point3) -> Point3 {
        Point3::from((p.coords - self.centre) / self.scale)
    }

    /// Maps a point from the normalised frame back to the object frame.
    pub fn invert(&self, p: &Point3) -> Point3 {
        Point3::from(p.coords * self.scale + self.centre)
    }
}

/// An `N x 3` point cloud in its own normalised frame, with the normalisation that made it.
#[derive(Debug, Clone, PartialEq)]
pub struct Cloud {
    /// Points in the normalised frame (normalised units).
    pub points: Vec<Point3>,
    /// The map from the object frame to this cloud's normalised frame.
    pub normalisation: Normalisation,
}

impl Cloud {
    /// Normalises points given in the object frame; `None` under the conditions of
    /// [`Normalisation::of_points`].
    pub fn normalise(points: &[Point3]) -> Option<Self> {
        let normalisation = Normalisation::of_points(points)?;
        let points = points.iter().map(|p| normalisation.apply(p)).collect();
        Some(Self { points, normalisation })
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Whether the cloud has no points.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normalised_cloud_has_unit_diagonal_centred_box() {
        let pts =
            [Point3::new(1.0, 2.0, 3.0), Point3::new(4.0, 6.0, 3.0), Point3::new(2.0, 2.0, 3.0)];
        let cloud = Cloud::normalise(&pts).expect("non-degenerate");
        let n = Normalisation::of_points(&cloud.points).expect("non-degenerate");
        assert!(n.centre.norm() < 1e-6);
        assert!((n.scale - 1.0).abs() < 1e-6);
        for (p, q) in pts.iter().zip(&cloud.points) {
            assert!((cloud.normalisation.invert(q) - p).norm() < 1e-5);
        }
    }

    #[test]
    fn degenerate_inputs_have_no_normalisation() {
        assert!(Normalisation::of_points(&[]).is_none());
        assert!(Normalisation::of_points(&[Point3::new(1.0, 1.0, 1.0); 3]).is_none());
        assert!(Normalisation::of_points(&[Point3::origin(), Point3::new(f32::NAN, 0.0, 0.0)])
            .is_none());
    }
}
