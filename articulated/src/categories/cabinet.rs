//! Cabinet: a carcass with a drawer on top and a hinged door below.

use pairs::math::Point3;
use rand::Rng as _;

use super::catalog::{Category, TEST};
use crate::mesh::Mesh;
use crate::objects::door::{front_door, HingeSide};
use crate::objects::drawer::drawer;
use crate::objects::{ArticulatedObject, Link};
use crate::seed::Rng;

/// The cabinet category.
pub const CATEGORY: Category = Category {
    name: "cabinet",
    description:
        "carcass with a prismatic drawer on top and a revolute door below (hinge left or right)",
    splits: TEST,
    build,
};

fn build(rng: &mut Rng) -> ArticulatedObject {
    let w = rng.random_range(0.4..0.8);
    let h = rng.random_range(0.6..1.2);
    let d = rng.random_range(0.35..0.55);
    let t = rng.random_range(0.015..0.025);
    let drawer_h = h * rng.random_range(0.18..0.3);
    let side = if rng.random_bool(0.5) { HingeSide::Left } else { HingeSide::Right };
    let max_door = rng.random_range(100.0f32..125.0).to_radians();
    let max_travel = d * rng.random_range(0.5..0.8);
    let (hw, hd) = (w * 0.5, d * 0.5);
    let split = h - t - drawer_h;
    let carcass = Mesh::union([
        Mesh::cuboid(Point3::new(-hw, 0.0, -hd), Point3::new(-hw + t, h, hd)),
        Mesh::cuboid(Point3::new(hw - t, 0.0, -hd), Point3::new(hw, h, hd)),
        Mesh::cuboid(Point3::new(-hw, h - t, -hd), Point3::new(hw, h, hd)),
        Mesh::cuboid(Point3::new(-hw, 0.0, -hd), Point3::new(hw, t, hd)),
        Mesh::cuboid(Point3::new(-hw, 0.0, -hd), Point3::new(hw, h, -hd + t)),
        Mesh::cuboid(Point3::new(-hw + t, split - t, -hd + t), Point3::new(hw - t, split, hd)),
    ]);
    let mut object =
        ArticulatedObject::new("cabinet", Link { name: "carcass".into(), mesh: carcass });
    let gap = 0.004;
    let (drawer_mesh, slide) = drawer(
        (-hw + t + gap, hw - t - gap),
        (split + gap, h - t - gap),
        hd - t,
        d - 2.0 * t,
        t * 0.6,
        max_travel,
    );
    object.attach(0, Link { name: "drawer".into(), mesh: drawer_mesh }, slide);
    let (door_mesh, hinge) = front_door((-hw, hw), (t, split - t), hd, t, side, max_door);
    object.attach(0, Link { name: "door".into(), mesh: door_mesh }, hinge);
    object
}
