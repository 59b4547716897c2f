//! Carcasses: hollow boxes open at the front, the bodies of fridges, ovens, wardrobes and
//! safes, which doors close and drawers and racks slide into.

use pairs::math::{Point3, Real};

use crate::mesh::Mesh;

/// A box spanning `min..max` whose sides, top, bottom and back are `wall` thick, open at
/// its front face `z = max.z`. The walls do not overlap, so no hidden faces are sampled
/// beyond their thin edges.
pub fn open_box(min: Point3, max: Point3, wall: Real) -> Mesh {
    let (a, b) = (min, max);
    let (ix0, ix1) = (a.x + wall, b.x - wall);
    Mesh::union([
        Mesh::cuboid(a, Point3::new(ix0, b.y, b.z)),
        Mesh::cuboid(Point3::new(ix1, a.y, a.z), b),
        Mesh::cuboid(Point3::new(ix0, a.y, a.z), Point3::new(ix1, a.y + wall, b.z)),
        Mesh::cuboid(Point3::new(ix0, b.y - wall, a.z), Point3::new(ix1, b.y, b.z)),
        Mesh::cuboid(Point3::new(ix0, a.y + wall, a.z), Point3::new(ix1, b.y - wall, a.z + wall)),
    ])
}

/// The cavity of [`open_box`]`(min, max, wall)`: its inner corners, the front one on the
/// open face.
pub fn cavity(min: Point3, max: Point3, wall: Real) -> (Point3, Point3) {
    (
        Point3::new(min.x + wall, min.y + wall, min.z + wall),
        Point3::new(max.x - wall, max.y - wall, max.z),
    )
}
