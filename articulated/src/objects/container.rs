//! Containers: open-top boxes, lids hinged on their back edge (with or without hinge
//! knuckles) and front latches.
//!
//! A lid modelled with its back-bottom edge on (or just in front of) the hinge axis and all
//! of it above and in front of that edge swings up and back without entering the box it
//! closes.

use pairs::math::{Point3, Real, Vector3};

use super::articulated::Joint;
use crate::mesh::Mesh;

/// Four walls `wall` thick standing on the outer footprint `x` by `z`, from `y.0` to `y.1`;
/// the front and back walls span the full width, the side walls fit between them.
pub fn box_walls(x: (Real, Real), y: (Real, Real), z: (Real, Real), wall: Real) -> Mesh {
    let ((x0, x1), (y0, y1), (z0, z1)) = (x, y, z);
    Mesh::union([
        Mesh::cuboid(Point3::new(x0, y0, z0), Point3::new(x1, y1, z0 + wall)),
        Mesh::cuboid(Point3::new(x0, y0, z1 - wall), Point3::new(x1, y1, z1)),
        Mesh::cuboid(Point3::new(x0, y0, z0 + wall), Point3::new(x0 + wall, y1, z1 - wall)),
        Mesh::cuboid(Point3::new(x1 - wall, y0, z0 + wall), Point3::new(x1, y1, z1 - wall)),
    ])
}

/// An open-top box: [`box_walls`] on a floor `wall` thick.
pub fn open_box(x: (Real, Real), y: (Real, Real), z: (Real, Real), wall: Real) -> Mesh {
    Mesh::union([
        Mesh::cuboid(Point3::new(x.0, y.0, z.0), Point3::new(x.1, y.0 + wall, z.1)),
        box_walls(x, (y.0 + wall, y.1), z, wall),
    ])
}

/// Four round feet `height` tall and `radius` thick standing at (+-`x`, +-`z`), under a
/// container whose bottom is at `height`.
pub fn corner_feet(x: Real, z: Real, height: Real, radius: Real) -> Mesh {
    Mesh::union(
        [(-x, -z), (-x, z), (x, -z), (x, z)].map(|(x, z)| {
            Mesh::cylinder(Point3::new(x, 0.0, z), Point3::new(x, height, z), radius, 8)
        }),
    )
}

/// The hinge of a lid whose back-bottom edge runs along x through `pivot`: turning about
/// -x lifts the lid's front edge up and back, up to `max_angle` radians.
pub fn back_hinge(pivot: Point3, max_angle: Real) -> Joint {
    Joint::hinge(pivot, -Vector3::x(), max_angle)
}

/// Hinges with knuckles for a lid closing a box at height `top` whose back face is
/// z = `back`: one hinge `length` long around each of `centres` (x), with barrels of
/// `radius` on an axis that runs `radius` behind the back face. The two outer thirds of
/// every hinge belong to the box, the middle third to the lid. Every point of a lid that
/// starts at the back face is at least `radius` from the axis, so the lid swings against
/// the box's barrels without entering them. Returns (box part, lid part, joint).
pub fn knuckle_hinges(
    centres: &[Real],
    length: Real,
    (top, back): (Real, Real),
    radius: Real,
    max_angle: Real,
) -> (Mesh, Mesh, Joint) {
    let z = back - radius;
    let barrel = |x0: Real, x1: Real| {
        Mesh::cylinder(Point3::new(x0, top, z), Point3::new(x1, top, z), radius, 10)
    };
    let third = length / 3.0;
    let fixed = Mesh::union(centres.iter().flat_map(|&c| {
        [barrel(c - 1.5 * third, c - 0.5 * third), barrel(c + 0.5 * third, c + 1.5 * third)]
    }));
    let moving = Mesh::union(centres.iter().map(|&c| barrel(c - 0.5 * third, c + 0.5 * third)));
    (fixed, moving, back_hinge(Point3::new(0.0, top, z), max_angle))
}

/// A front latch centred on `x`, `width` wide, for a lid that closes a box at height `top`
/// whose front face is z = `front`: a hasp `drop` long hanging from the lid in front of the
/// face, and a catch on the face just under it, both `proud` thick; returns (hasp, catch).
/// The hasp's lowest corner is the farthest point from a back hinge, so it swings clear.
pub fn front_latch(
    x: Real,
    width: Real,
    top: Real,
    front: Real,
    drop: Real,
    proud: Real,
) -> (Mesh, Mesh) {
    let hw = 0.5 * width;
    let hasp = Mesh::cuboid(
        Point3::new(x - hw, top - drop, front),
        Point3::new(x + hw, top, front + proud),
    );
    let catch = Mesh::cuboid(
        Point3::new(x - 1.4 * hw, top - 2.0 * drop, front),
        Point3::new(x + 1.4 * hw, top - drop, front + 1.5 * proud),
    );
    (hasp, catch)
}
