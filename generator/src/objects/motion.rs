//! Joint constructors: hinges and slides that rest closed at 0 and open to a maximum.

use pairs::math::{Point3, Real, Vector3};
use pairs::JointKind;

use super::articulated::Joint;

/// A revolute joint about `axis` through `pivot`, from 0 (closed, the rest value) to
/// `max_angle` radians; the right-hand rule about `axis` gives the opening direction.
pub fn hinge(pivot: Point3, axis: Vector3, max_angle: Real) -> Joint {
    Joint {
        kind: JointKind::Revolute,
        parent: 0,
        child: 0,
        pivot,
        axis: axis.normalize(),
        limits: (0.0, max_angle),
        rest: 0.0,
    }
}

/// A prismatic joint along `axis`, from 0 (retracted, the rest value) to `max_travel`.
pub fn slide(axis: Vector3, max_travel: Real) -> Joint {
    Joint {
        kind: JointKind::Prismatic,
        parent: 0,
        child: 0,
        pivot: Point3::origin(),
        axis: axis.normalize(),
        limits: (0.0, max_travel),
        rest: 0.0,
    }
}
