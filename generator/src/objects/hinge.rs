//! Joint constructors for the usual hinges and slides: closed at rest (value 0), opening up
//! to a limit. `ArticulatedObject::attach` fills in the parent and child.

use pairs::math::{Point3, Real, Vector3};
use pairs::JointKind;

use super::articulated::Joint;
use crate::mesh::Mesh;

/// A revolute joint about the line through `pivot` along `axis` (normalised here), closed at
/// 0 and opening by up to `max_angle` radians (right-hand rule about `axis`).
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

/// A prismatic joint along `axis` (normalised here), closed at 0 and sliding out by up to
/// `max_travel`; `at` marks where the slide is, for readers of the joint.
pub fn slide(at: Point3, axis: Vector3, max_travel: Real) -> Joint {
    Joint {
        kind: JointKind::Prismatic,
        parent: 0,
        child: 0,
        pivot: at,
        axis: axis.normalize(),
        limits: (0.0, max_travel),
        rest: 0.0,
    }
}

/// Coaxial contact pads for a hinge: two thin discs of `radius` meeting on the plane through
/// `pivot` normal to `axis`, the parent's on the -`axis` side and the child's on the +`axis`
/// side; each goes inside its own link's hinge part, where the two links touch.
///
/// Turning about the axis keeps the pads in contact, and the checks' convex distance query
/// (GJK) between thin, centrally symmetric pieces stays within their thickness of the truth,
/// where between thick flush faces it can be off by half their thickness.
pub fn contact_pads(pivot: Point3, axis: Vector3, radius: Real) -> (Mesh, Mesh) {
    let step = axis.normalize() * pad_thickness(radius);
    (
        Mesh::cylinder(pivot - step, pivot, radius, 12),
        Mesh::cylinder(pivot, pivot + step, radius, 12),
    )
}

/// Thickness of a contact pad `size` across: thin enough that the checks' distance query
/// errs by less than a fraction of a millimetre, thick enough to keep a proper hull.
pub fn pad_thickness(size: Real) -> Real {
    (0.02 * size).max(2e-4)
}
