//! Scalar and geometric types shared by every crate, so that no crate picks its own.

/// Scalar type of every coordinate, flow vector and motion parameter.
pub type Real = f32;
/// A point in 3D (a cloud point, a pivot).
pub type Point3 = nalgebra::Point3<Real>;
/// A vector in 3D (a flow vector, an axis, a translation).
pub type Vector3 = nalgebra::Vector3<Real>;
/// A 3x3 matrix (a rotation stored row by row in files).
pub type Matrix3 = nalgebra::Matrix3<Real>;
/// A rotation in 3D.
pub type Rotation3 = nalgebra::Rotation3<Real>;
/// A unit quaternion.
pub type UnitQuaternion = nalgebra::UnitQuaternion<Real>;
/// A rigid transform (rotation then translation).
pub type Isometry3 = nalgebra::Isometry3<Real>;
/// A translation in 3D.
pub type Translation3 = nalgebra::Translation3<Real>;
/// A unit-length vector (an axis).
pub type UnitVector3 = nalgebra::Unit<Vector3>;

/// `v` scaled to unit length, or `fallback` when its norm is zero (or underflows to zero),
/// where `nalgebra`'s `normalize` would give NaNs (which is why the workspace's
/// `clippy.toml` bans it). Wherever `normalize` gives no NaN, the result is bit for bit
/// `normalize`'s: a vector however short keeps its direction, so a cross product of nearly
/// parallel vectors is not mistaken for a degenerate one.
///
/// ```
/// use pairs::math::{unit_or, Vector3};
/// assert_eq!(unit_or(&Vector3::new(0.0, 3.0, 4.0), Vector3::x()), Vector3::new(0.0, 0.6, 0.8));
/// let tiny = unit_or(&Vector3::new(0.0, 3e-10, 4e-10), Vector3::x());
/// assert!((tiny - Vector3::new(0.0, 0.6, 0.8)).norm() < 1e-6);
/// assert_eq!(unit_or(&Vector3::zeros(), Vector3::x()), Vector3::x());
/// ```
pub fn unit_or(v: &Vector3, fallback: Vector3) -> Vector3 {
    try_unit(v).unwrap_or(fallback)
}

/// `v` scaled to unit length, or `None` when its norm is zero (see [`unit_or`]).
pub fn try_unit(v: &Vector3) -> Option<Vector3> {
    v.try_normalize(0.0)
}

/// A unit vector perpendicular to the unit vector `axis` (from the coordinate axis least
/// aligned with it), for building a frame about an axis that comes without one.
///
/// ```
/// use pairs::math::{perpendicular, Vector3};
/// for axis in [Vector3::x(), Vector3::y(), Vector3::new(0.6, 0.0, 0.8)] {
///     let p = perpendicular(&axis);
///     assert!(p.dot(&axis).abs() < 1e-6 && (p.norm() - 1.0).abs() < 1e-6);
/// }
/// ```
pub fn perpendicular(axis: &Vector3) -> Vector3 {
    let a = axis.abs();
    let least = if a.x <= a.y && a.x <= a.z {
        Vector3::x()
    } else if a.y <= a.z {
        Vector3::y()
    } else {
        Vector3::z()
    };
    // `least` is at most 1/√3 along a unit `axis`, so the cross product has norm ≥ √(2/3).
    unit_or(&axis.cross(&least), Vector3::x())
}

/// The axis-aligned bounding box of `points`: its lowest and highest corner, or `None` when
/// there are no points. The one bounding-box loop of the workspace.
///
/// ```
/// use pairs::math::{bounds, Point3};
/// let points = [Point3::new(1.0, -2.0, 0.5), Point3::new(-1.0, 3.0, 0.0)];
/// assert_eq!(bounds(&points), Some((Point3::new(-1.0, -2.0, 0.0), Point3::new(1.0, 3.0, 0.5))));
/// assert_eq!(bounds(std::iter::empty::<Point3>()), None);
/// ```
pub fn bounds<P: std::borrow::Borrow<Point3>>(
    points: impl IntoIterator<Item = P>,
) -> Option<(Point3, Point3)> {
    points.into_iter().fold(None, |b, p| {
        let p = p.borrow();
        Some(match b {
            None => (*p, *p),
            Some((lo, hi)) => (lo.inf(p), hi.sup(p)),
        })
    })
}
