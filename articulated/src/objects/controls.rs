//! Appliance controls on a front panel facing +z: knobs with a pointer ridge, push buttons
//! and displays.

use pairs::math::{Point3, Real, Vector3};

use crate::mesh::Mesh;

/// A round knob on the panel face through `centre` (normal +z): a cylinder `depth` proud
/// of the face with a pointer ridge across its front, turned by `angle` radians.
pub fn knob(centre: Point3, radius: Real, depth: Real, angle: Real) -> Mesh {
    let front = centre + Vector3::z() * depth;
    let dir = Vector3::new(-angle.sin(), angle.cos(), 0.0) * 0.8 * radius;
    Mesh::union([
        Mesh::cylinder(centre, front, radius, 12),
        Mesh::beam(front - dir, front + dir, 0.3 * radius, 0.5 * depth, Vector3::z()),
    ])
}

/// `count` knobs evenly spaced over `x0..x1` at height `y` on the face `z = z`, their
/// pointers at different settings.
pub fn knob_row((x0, x1): (Real, Real), y: Real, z: Real, count: u32, radius: Real) -> Mesh {
    let step = (x1 - x0) / count as Real;
    Mesh::union((0..count).map(|i| {
        let x = x0 + (i as Real + 0.5) * step;
        knob(Point3::new(x, y, z), radius, 0.8 * radius, 0.9 * i as Real)
    }))
}

/// A rectangular button or display centred at `(x, y)` on the face `z = z`, `size` wide and
/// high, `depth` proud of the face.
pub fn button(x: Real, y: Real, z: Real, size: (Real, Real), depth: Real) -> Mesh {
    let (hw, hh) = (0.5 * size.0, 0.5 * size.1);
    Mesh::cuboid(Point3::new(x - hw, y - hh, z), Point3::new(x + hw, y + hh, z + depth))
}
