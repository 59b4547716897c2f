//! Hinged doors: a panel with a handle near its free edge.

use pairs::math::{Point3, Real, Vector3};
use pairs::JointKind;

use super::articulated::Joint;
use super::handle::bar_handle;
use crate::mesh::Mesh;

/// Which side of a door its hinge is on, seen from the front.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HingeSide {
    /// Hinge at the door's lowest x.
    Left,
    /// Hinge at the door's highest x.
    Right,
}

/// A vertical door closing the front face `z = front` over `x0..x1`, `y0..y1`, with the
/// hinge on `side`; returns its mesh and the joint that opens it outwards by up to
/// `max_angle` radians.
pub fn front_door(
    (x0, x1): (Real, Real),
    (y0, y1): (Real, Real),
    front: Real,
    thickness: Real,
    side: HingeSide,
    max_angle: Real,
) -> (Mesh, Joint) {
    let panel = Mesh::cuboid(Point3::new(x0, y0, front), Point3::new(x1, y1, front + thickness));
    let width = x1 - x0;
    let (handle_x, hinge_x, axis) = match side {
        HingeSide::Left => (x1 - 0.1 * width, x0, -Vector3::y()),
        HingeSide::Right => (x0 + 0.1 * width, x1, Vector3::y()),
    };
    let (ya, yb) = (y0 + 0.4 * (y1 - y0), y0 + 0.6 * (y1 - y0));
    let z = front + thickness;
    let handle = bar_handle(
        Point3::new(handle_x, ya, z),
        Point3::new(handle_x, yb, z),
        Vector3::z(),
        0.03 * width.max(0.3),
        0.006,
    );
    let joint = Joint {
        name: String::new(),
        kind: JointKind::Revolute,
        parent: 0,
        child: 0,
        pivot: Point3::new(hinge_x, y0, front),
        axis,
        limits: (0.0, max_angle),
        rest: 0.0,
    };
    (Mesh::union([panel, handle]), joint)
}
