//! Safe: a heavy box with thick walls and a shelf, closed by a thick door whose inner step
//! fits the opening; the door carries a spoked handle wheel (part of the door, not a joint)
//! and a combination dial, and swings on knuckles outside the body's side.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, VALIDATION};
use crate::mesh::Mesh;
use crate::objects::carcass::{cavity, open_box};
use crate::objects::controls::knob;
use crate::objects::door::HingeSide;
use crate::objects::joints::{knuckles, mirrored_part, vertical_hinge};
use crate::objects::{ArticulatedObject, Link};
use crate::seed::Rng;

/// The safe category.
pub const CATEGORY: Category = Category {
    name: "safe",
    description:
        "thick-walled box; thick door with a handle wheel, revolute about an outside side hinge",
    splits: VALIDATION,
    build,
};

/// A handle wheel of `spokes` spokes with ball ends, `radius` across, standing off the face
/// `z = z` at `(x, y)`.
fn handle_wheel(x: Real, y: Real, z: Real, radius: Real, spokes: u32) -> Mesh {
    let hub = Point3::new(x, y, z + 0.04);
    let mut mesh = Mesh::union([
        Mesh::cylinder(Point3::new(x, y, z), hub, 0.025, 12),
        Mesh::cylinder(hub, hub + Vector3::z() * 0.02, 0.035, 12),
    ]);
    for i in 0..spokes {
        let a = i as Real * std::f32::consts::TAU / spokes as Real + 0.3;
        let end = hub + Vector3::new(a.cos(), a.sin(), 0.0) * radius + Vector3::z() * 0.01;
        mesh.append(Mesh::beam(hub + Vector3::z() * 0.01, end, 0.014, 0.014, Vector3::z()));
        mesh.append(Mesh::sphere(end, 0.018, 12));
    }
    mesh
}

fn build(rng: &mut Rng) -> ArticulatedObject {
    let w = rng.random_range(0.35..0.6);
    let h = w * rng.random_range(0.9..1.6);
    let d = rng.random_range(0.35..0.55);
    let wall = rng.random_range(0.04..0.07);
    let t = rng.random_range(0.06..0.1);
    let spokes = rng.random_range(3..6u32);
    let max_open = rng.random_range(95.0f32..120.0).to_radians();
    let hinge_right = rng.random_bool(0.5);
    let (hw, hd, foot, kr, c) = (0.5 * w, 0.5 * d, 0.03, 0.015, 0.006);
    let (lo, hi) = (Point3::new(-hw, foot, -hd), Point3::new(hw, h, hd));
    let (inner_lo, inner_hi) = cavity(lo, hi, wall);
    let mut body = open_box(lo, hi, wall);
    if h - 2.0 * wall > 0.35 {
        let y = 0.5 * (inner_lo.y + inner_hi.y);
        body.append(Mesh::cuboid(
            Point3::new(inner_lo.x, y, inner_lo.z),
            Point3::new(inner_hi.x, y + 0.012, hd - wall - 0.02),
        ));
    }
    for x in [-hw + 0.05, hw - 0.05] {
        body.append(Mesh::cuboid(
            Point3::new(x - 0.03, 0.0, -hd + 0.02),
            Point3::new(x + 0.03, foot, hd - 0.02),
        ));
    }
    // Built hinged on the left: the axis runs just outside the body's side, so the door's
    // step (which fits the opening with clearance `c`) swings clear of the wall.
    let mut door = Mesh::union([
        Mesh::cuboid(Point3::new(-hw, foot, hd), Point3::new(hw, h, hd + t)),
        Mesh::cuboid(
            Point3::new(inner_lo.x + c, inner_lo.y + c, hd - 0.8 * wall),
            Point3::new(inner_hi.x - c, inner_hi.y - c, hd),
        ),
        handle_wheel(0.15 * w, foot + 0.45 * (h - foot), hd + t, 0.28 * w, spokes),
        knob(Point3::new(0.15 * w, foot + 0.78 * (h - foot), hd + t), 0.05, 0.025, 0.4),
    ]);
    let pivot = Point3::new(-hw - kr, foot, hd);
    let span = |f: Real| (foot + f * (h - foot), foot + (f + 0.2) * (h - foot));
    let mut fixed = Mesh::default();
    for f in [0.1, 0.7] {
        let (frame, leaf) = knuckles(pivot, span(f), kr, 3);
        fixed.append(frame);
        door.append(leaf);
    }
    let mut hinge = vertical_hinge(pivot, HingeSide::Left, max_open);
    if hinge_right {
        (door, fixed, hinge) = mirrored_part(door, fixed, &hinge);
    }
    body.append(fixed);
    let mut object = ArticulatedObject::new("safe", Link { name: "body".into(), mesh: body });
    object.attach(0, Link { name: "door".into(), mesh: door }, hinge);
    object
}
