//! Toilet: a pedestal and bowl with a tank behind; the seat and the lid turn up about the
//! same hinge axis at the back of the bowl.
//!
//! The lid lies on the seat and can never pass through it, so the lid is the seat's child
//! and opens relative to it. The joint ranges are a box, so the seat's range and the lid's
//! relative range add up to the widest angle the lid can reach before it meets the tank;
//! the tank stands just far enough behind the hinge for that.

use pairs::math::{Point3, Real};
use rand::Rng as _;

use super::catalog::{Category, TEST};
use crate::mesh::Mesh;
use crate::objects::container::back_hinge;
use crate::objects::shell::{oval_frustum, oval_wall};
use crate::objects::{ArticulatedObject, Link};
use crate::seed::Rng;

/// The toilet category.
pub const CATEGORY: Category = Category {
    name: "toilet",
    description: "bowl and tank on a pedestal; seat revolute at the back of the bowl, lid revolute on the seat about the same axis",
    splits: TEST,
    build,
};

fn build(rng: &mut Rng) -> ArticulatedObject {
    let (rx, rz) = (rng.random_range(0.17..0.2), rng.random_range(0.22..0.27));
    let rim = rng.random_range(0.38..0.43);
    let rim_wall = rng.random_range(0.035..0.05);
    let depth = rim * rng.random_range(0.15..0.25);
    let (ts, tl) = (rng.random_range(0.015..0.025), rng.random_range(0.018..0.03));
    let seat_width = rim_wall + rng.random_range(0.01..0.025);
    let hinge_back = rng.random_range(0.03..0.05);
    let (tank_w, tank_h) = (2.0 * rx * rng.random_range(0.85..1.0), rng.random_range(0.28..0.4));
    let (tank_d, cover) = (rng.random_range(0.15..0.22), rng.random_range(0.02..0.03));
    let widest = rng.random_range(95.0f32..108.0).to_radians();
    let seat_max = widest * rng.random_range(0.4..0.6);
    let seat_top = rim + ts;
    let hinge_z = -rz - hinge_back;
    let hinge_half = 0.5 * rx;
    let post_r = 1.1 * ts;
    // The tank cover's top-front edge is the first thing the lid's back face can meet: keep
    // it behind that face at the widest angle, with 1 cm to spare.
    let (s, c) = (widest.sin(), widest.cos());
    let edge_y = tank_h + cover - ts;
    let edge_behind = (tl + 0.01 - c * edge_y) / s;
    let tank_front = hinge_z - edge_behind - 0.01;
    let tank_back = tank_front - tank_d;
    let mut bowl = Mesh::union([
        bowl_mesh((rx, rz), rim, depth, rim_wall),
        Mesh::cuboid(
            Point3::new(-hinge_half - 0.03, 0.55 * rim, tank_back),
            Point3::new(hinge_half + 0.03, rim, -0.8 * rz),
        ),
        tank_mesh(0.5 * tank_w, (rim, rim + tank_h), (tank_back, tank_front), cover),
    ]);
    for side in [-1.0, 1.0] {
        let (a, b) = (side * hinge_half, side * (hinge_half + 0.03));
        bowl.append(Mesh::cylinder(
            Point3::new(a, seat_top, hinge_z),
            Point3::new(b, seat_top, hinge_z),
            post_r,
            10,
        ));
    }
    // The seat's bar reaches back to the hinge axis along its top-back edge, between posts.
    let seat = Mesh::union([
        oval_wall(Point3::new(0.0, rim, 0.0), ts, (rx, rz), (rx, rz), seat_width, 16),
        Mesh::cuboid(
            Point3::new(-hinge_half, rim, hinge_z),
            Point3::new(hinge_half, seat_top, -rz + 0.04),
        ),
    ]);
    // The lid's back-most point lies on the hinge axis; it reaches just past the seat's front.
    let lid_rz = 0.5 * (rz + 0.005 - hinge_z);
    let (lid_rx, lid_z) = (rx + 0.005, hinge_z + lid_rz);
    let lid = oval_frustum(
        Point3::new(0.0, seat_top, lid_z),
        tl,
        (lid_rx, lid_rz),
        (lid_rx - 0.01, lid_rz - 0.01),
        16,
    );
    let mut object = ArticulatedObject::new("toilet", Link { name: "bowl".into(), mesh: bowl });
    let pivot = Point3::new(0.0, seat_top, hinge_z);
    let seat_link =
        object.attach(0, Link { name: "seat".into(), mesh: seat }, back_hinge(pivot, seat_max));
    object.attach(
        seat_link,
        Link { name: "lid".into(), mesh: lid },
        back_hinge(pivot, widest - seat_max),
    );
    object
}

/// Pedestal and bowl: solid oval frustums up to the bowl's inside, `depth` under the rim at
/// height `rim`, then a rim wall `wall` thick with outer half-axes `radii` at the top.
fn bowl_mesh(radii: (Real, Real), rim: Real, depth: Real, wall: Real) -> Mesh {
    let (rx, rz) = radii;
    let waist = (0.95 * rx, 0.95 * rz);
    Mesh::union([
        oval_frustum(
            Point3::new(0.0, 0.0, -0.1 * rz),
            0.45 * rim,
            (0.6 * rx, 0.75 * rz),
            (0.5 * rx, 0.6 * rz),
            12,
        ),
        oval_frustum(
            Point3::new(0.0, 0.45 * rim, 0.0),
            0.55 * rim - depth,
            (0.55 * rx, 0.65 * rz),
            waist,
            16,
        ),
        oval_wall(Point3::new(0.0, rim - depth, 0.0), depth, waist, radii, wall, 16),
    ])
}

/// The tank: a box `hw` half wide over heights `y` and depths `z` (back, front), under a
/// cover `cover` thick that overhangs it by 1 cm, with a flush button on top.
fn tank_mesh(hw: Real, y: (Real, Real), z: (Real, Real), cover: Real) -> Mesh {
    let (top, middle) = (y.1 + cover, 0.5 * (z.0 + z.1));
    Mesh::union([
        Mesh::cuboid(Point3::new(-hw, y.0, z.0), Point3::new(hw, y.1, z.1)),
        Mesh::cuboid(
            Point3::new(-hw - 0.01, y.1, z.0 - 0.01),
            Point3::new(hw + 0.01, top, z.1 + 0.01),
        ),
        Mesh::cylinder(
            Point3::new(0.0, top, middle),
            Point3::new(0.0, top + 0.008, middle),
            0.025,
            12,
        ),
    ])
}
