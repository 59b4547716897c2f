//! Joint constructors: a hinge or a slide, closed (value 0) at rest, ready for
//! [`ArticulatedObject::attach`](super::ArticulatedObject::attach), which fills in the
//! parent and child.

use pairs::math::{Point3, Real, Vector3};
use pairs::JointKind;

use super::articulated::Joint;

/// A revolute joint turning about the unit `axis` through `pivot`, within `limits`
/// (radians, holding 0, the rest state).
pub fn revolute(pivot: Point3, axis: Vector3, limits: (Real, Real)) -> Joint {
    Joint { kind: JointKind::Revolute, parent: 0, child: 0, pivot, axis, limits, rest: 0.0 }
}

/// A prismatic joint sliding along the unit `axis` within `limits` (object units, holding
/// 0, the rest state); `at` is a point on the slide, kept as the joint's pivot.
pub fn prismatic(at: Point3, axis: Vector3, limits: (Real, Real)) -> Joint {
    Joint { kind: JointKind::Prismatic, parent: 0, child: 0, pivot: at, axis, limits, rest: 0.0 }
}
