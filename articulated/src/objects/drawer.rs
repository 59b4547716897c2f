//! Drawers: an open-top box behind a front panel with a handle, sliding out along +z.

use pairs::math::{Point3, Real, Vector3};
use pairs::JointKind;

use super::articulated::Joint;
use super::handle::bar_handle;
use crate::mesh::Mesh;

/// A drawer whose front panel closes `z = front` over `x0..x1`, `y0..y1`, with a box
/// `depth` deep behind it; returns its mesh and the joint that pulls it out by up to
/// `max_travel`.
pub fn drawer(
    (x0, x1): (Real, Real),
    (y0, y1): (Real, Real),
    front: Real,
    depth: Real,
    wall: Real,
    max_travel: Real,
) -> (Mesh, Joint) {
    let back = front - depth;
    let (bx0, bx1, by0, by1) = (x0 + wall, x1 - wall, y0, y1 - 1.5 * wall);
    let mesh = Mesh::union([
        Mesh::cuboid(Point3::new(x0, y0, front), Point3::new(x1, y1, front + wall)),
        Mesh::cuboid(Point3::new(bx0, by0, back), Point3::new(bx1, by0 + wall, front)),
        Mesh::cuboid(Point3::new(bx0, by0, back), Point3::new(bx0 + wall, by1, front)),
        Mesh::cuboid(Point3::new(bx1 - wall, by0, back), Point3::new(bx1, by1, front)),
        Mesh::cuboid(Point3::new(bx0, by0, back), Point3::new(bx1, by1, back + wall)),
        bar_handle(
            Point3::new(x0 + 0.35 * (x1 - x0), 0.5 * (y0 + y1), front + wall),
            Point3::new(x0 + 0.65 * (x1 - x0), 0.5 * (y0 + y1), front + wall),
            Vector3::z(),
            0.025,
            0.006,
        ),
    ]);
    let joint = Joint {
        name: String::new(),
        kind: JointKind::Prismatic,
        parent: 0,
        child: 0,
        pivot: Point3::new(0.5 * (x0 + x1), 0.5 * (y0 + y1), front),
        axis: Vector3::z(),
        limits: (0.0, max_travel),
        rest: 0.0,
    };
    (mesh, joint)
}
