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
