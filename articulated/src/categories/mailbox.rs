//! Mailbox: a rural tunnel mailbox (flat floor, straight sides, arched roof) on two mounting
//! cleats; the arched front door drops forward about its bottom edge, and the signal flag's
//! arm on the side turns up from horizontal to upright.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TRAIN};
use crate::mesh::Mesh;
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The mailbox category.
pub const CATEGORY: Category = Category {
    name: "mailbox",
    description: "tunnel mailbox: arched front door revolute about its bottom edge, flag arm revolute on the side",
    splits: TRAIN,
    build,
};

/// Segments of a half circle.
const ARCH_SEGMENTS: u32 = 8;

fn build(rng: &mut Rng) -> ArticulatedObject {
    let (length, hw) = (rng.random_range(0.42..0.58), 0.5 * rng.random_range(0.15..0.22));
    let side_h = rng.random_range(0.1..0.14);
    let t = rng.random_range(0.003..0.005);
    let door_t = rng.random_range(0.005..0.009);
    let max_door = rng.random_range(95.0f32..110.0).to_radians();
    let arm_len = length * rng.random_range(0.5..0.65);
    let arm_w = rng.random_range(0.035..0.045);
    let (flag_w, flag_h) =
        (length * rng.random_range(0.21..0.26), side_h * rng.random_range(0.8..1.0));
    let max_flag = rng.random_range(85.0f32..95.0).to_radians();
    let flag_right = rng.random_bool(0.5);
    let hl = 0.5 * length;
    let mut body = Mesh::union([
        Mesh::cuboid(Point3::new(-hw, 0.0, -hl), Point3::new(hw, t, hl)),
        Mesh::cuboid(Point3::new(-hw, t, -hl), Point3::new(-hw + t, side_h, hl)),
        Mesh::cuboid(Point3::new(hw - t, t, -hl), Point3::new(hw, side_h, hl)),
        tombstone(hw, side_h, (-hl, -hl + t)),
    ]);
    for z in [-0.5 * hl, 0.5 * hl] {
        body.append(Mesh::cuboid(
            Point3::new(-0.6 * hw, -0.02, z - 0.02),
            Point3::new(0.6 * hw, 0.0, z + 0.02),
        ));
    }
    let step = std::f32::consts::PI / ARCH_SEGMENTS as Real;
    body.append(Mesh::union((0..ARCH_SEGMENTS).map(|i| {
        let points: Vec<Point3> = [i, i + 1]
            .into_iter()
            .flat_map(|k| {
                let (c, s) = ((k as Real * step).cos(), (k as Real * step).sin());
                [hw, hw - t]
                    .into_iter()
                    .flat_map(move |r| [-hl, hl].map(|z| Point3::new(r * c, side_h + r * s, z)))
            })
            .collect();
        Mesh::hull(&points)
    })));
    let door = Mesh::union([
        tombstone(hw + 0.004, side_h, (hl, hl + door_t)),
        Mesh::cuboid(
            Point3::new(-0.02, side_h + 0.6 * hw, hl + door_t),
            Point3::new(0.02, side_h + 0.75 * hw, hl + door_t + 0.015),
        ),
    ]);
    // The flag turns on a pin through the side wall near the back; its arm lies forward
    // along the wall when down, with the flag standing up from the arm's tip.
    let s = if flag_right { 1.0 } else { -1.0 };
    let (x0, x1) = (s * hw, s * (hw + 0.004));
    let (pin_y, pin_z) = (0.55 * side_h, -hl + 0.06);
    let (lo, hi) = (x0.min(x1), x0.max(x1));
    let tip = pin_z + arm_len;
    let flag = Mesh::union([
        Mesh::cuboid(
            Point3::new(lo, pin_y - 0.5 * arm_w, pin_z - 0.5 * arm_w),
            Point3::new(hi, pin_y + 0.5 * arm_w, tip),
        ),
        Mesh::cuboid(
            Point3::new(lo, pin_y - 0.5 * arm_w, tip - flag_w),
            Point3::new(hi, pin_y + flag_h, tip),
        ),
    ]);
    body.append(Mesh::cylinder(
        Point3::new(x1, pin_y, pin_z),
        Point3::new(x1 + s * 0.003, pin_y, pin_z),
        0.4 * arm_w,
        10,
    ));
    let mut object = ArticulatedObject::new("mailbox", Link { name: "box".into(), mesh: body });
    // Turning about +x swings the door's top forward and down.
    let drop = Joint::hinge(Point3::new(0.0, 0.0, hl), Vector3::x(), max_door);
    object.attach(0, Link { name: "door".into(), mesh: door }, drop);
    let raise = Joint::hinge(Point3::new(x0, pin_y, pin_z), -Vector3::x(), max_flag);
    object.attach(0, Link { name: "flag".into(), mesh: flag }, raise);
    object
}

/// A flat end piece between `z.0` and `z.1`: a rectangle `side_h` tall and `hw` half wide
/// under a half disc, one convex hull.
fn tombstone(hw: Real, side_h: Real, z: (Real, Real)) -> Mesh {
    let step = std::f32::consts::PI / ARCH_SEGMENTS as Real;
    let outline: Vec<(Real, Real)> = (0..=ARCH_SEGMENTS)
        .map(|k| (hw * (k as Real * step).cos(), side_h + hw * (k as Real * step).sin()))
        .chain([(-hw, 0.0), (hw, 0.0)])
        .collect();
    let points: Vec<Point3> = outline
        .iter()
        .flat_map(|&(x, y)| [Point3::new(x, y, z.0), Point3::new(x, y, z.1)])
        .collect();
    Mesh::hull(&points)
}
