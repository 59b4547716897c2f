//! Joint builders with the axis conventions of doors, flaps, lids and slides: which way an
//! axis points so that a positive value opens a part outwards, hinge knuckles that keep a
//! door touching its frame at every angle, and mirror images for left-right pairs.

use pairs::math::{Point3, Real, Vector3};
use pairs::JointKind;

use super::articulated::Joint;
use super::door::HingeSide;
use crate::mesh::Mesh;

/// A vertical hinge through `pivot` for a door in front of the plane `z = pivot.z` that
/// extends from the hinge towards +x (`Left`) or -x (`Right`); positive angles swing its
/// free edge out towards +z. With the pivot on the door's back face (or further out), no
/// part of the door that lies in front of that plane ever swings behind it on the frame's
/// side of the hinge.
pub fn vertical_hinge(pivot: Point3, side: HingeSide, max_angle: Real) -> Joint {
    let axis = match side {
        HingeSide::Left => -Vector3::y(),
        HingeSide::Right => Vector3::y(),
    };
    Joint::hinge(pivot, axis, max_angle)
}

/// The hinge of a door over `x0..x1` standing on `y` in front of the frame's face
/// `z = front`, `thickness` thick, that falls open towards +z (ovens, dishwashers): the
/// axis runs along x on the door's outer bottom edge, so the door stays above it and in
/// front of the frame up to a right angle. Returns two brackets for the frame, under the
/// door's bottom corners, which hold the axis so that the door touches the frame at every
/// angle, and the joint.
pub fn drop_hinge(
    (x0, x1): (Real, Real),
    y: Real,
    front: Real,
    thickness: Real,
    max_angle: Real,
) -> (Mesh, Joint) {
    let bracket = |x: Real| {
        Mesh::cuboid(Point3::new(x, y - 0.015, front), Point3::new(x + 0.03, y, front + thickness))
    };
    let joint =
        Joint::hinge(Point3::new(0.5 * (x0 + x1), y, front + thickness), Vector3::x(), max_angle);
    (Mesh::union([bracket(x0), bracket(x1 - 0.03)]), joint)
}

/// The joint mirrored through the plane x = 0, for the other part of a left-right pair: a
/// mirrored rotation turns the other way about the mirrored axis.
pub fn mirrored_x(joint: &Joint) -> Joint {
    let mirror = |v: Vector3| Vector3::new(-v.x, v.y, v.z);
    let axis = match joint.kind {
        JointKind::Revolute => -mirror(joint.axis),
        JointKind::Prismatic => mirror(joint.axis),
    };
    let pivot = Point3::from(mirror(joint.pivot.coords));
    Joint { pivot, axis, ..joint.clone() }
}

/// A hinged part mirrored through the plane x = 0, for objects built with their hinge on
/// one side and drawn on either: the part's mesh, what its hinge fixes to the frame, and
/// its joint.
pub fn mirrored_part(mesh: Mesh, fixed: Mesh, joint: &Joint) -> (Mesh, Mesh, Joint) {
    (mesh.mirrored_x(), fixed.mirrored_x(), mirrored_x(joint))
}

/// Hinge knuckles on the vertical axis through `pivot` over `y0..y1`: `count` coaxial
/// barrels of `radius` end to end, alternately the frame's (first and last) and the
/// door's, returned as (frame, door). Coaxial barrels touch at every angle.
pub fn knuckles(pivot: Point3, (y0, y1): (Real, Real), radius: Real, count: u32) -> (Mesh, Mesh) {
    let step = (y1 - y0) / count as Real;
    let barrel = |i: u32| {
        let at = |y: Real| Point3::new(pivot.x, y, pivot.z);
        Mesh::cylinder(at(y0 + i as Real * step), at(y0 + (i + 1) as Real * step), radius, 10)
    };
    let frame = Mesh::union((0..count).step_by(2).map(barrel));
    let door = Mesh::union((1..count).step_by(2).map(barrel));
    (frame, door)
}
