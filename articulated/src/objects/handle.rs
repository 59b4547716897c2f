//! Bar handles of doors, drawers and lids.

use pairs::math::{Point3, Real, Vector3};

use crate::mesh::Mesh;

/// A bar handle from `a` to `b`, standing off the surface along `out` by `standoff`: a bar
/// plus two posts.
pub fn bar_handle(a: Point3, b: Point3, out: Vector3, standoff: Real, radius: Real) -> Mesh {
    // No direction out: the handle stands off along z.
    let lift = pairs::math::unit_or(&out, Vector3::z()) * standoff;
    Mesh::union([
        Mesh::cylinder(a + lift, b + lift, radius, 8),
        Mesh::cylinder(a, a + lift, radius * 0.8, 6),
        Mesh::cylinder(b, b + lift, radius * 0.8, 6),
    ])
}
