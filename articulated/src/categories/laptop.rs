//! Laptop: a base with keyboard, trackpad and hinge barrels; a lid with a screen that opens
//! about the back edge of the base.

use pairs::math::{Point3, Vector3};
use pairs::JointKind;
use rand::Rng as _;

use super::catalog::{Category, TRAIN_AND_TEST};
use crate::mesh::Mesh;
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The laptop category.
pub const CATEGORY: Category = Category {
    name: "laptop",
    description: "base with keyboard and trackpad; lid with screen, revolute about the back edge",
    splits: TRAIN_AND_TEST,
    build,
};

fn build(rng: &mut Rng) -> ArticulatedObject {
    let w = rng.random_range(0.28..0.38);
    let d = rng.random_range(0.19..0.26);
    let h = rng.random_range(0.012..0.022);
    let t = rng.random_range(0.005..0.01);
    let max_open = rng.random_range(110.0f32..150.0).to_radians();
    let (hw, hd) = (w * 0.5, d * 0.5);
    let base = Mesh::union([
        Mesh::cuboid(Point3::new(-hw, 0.0, -hd), Point3::new(hw, h, hd)),
        Mesh::cuboid(
            Point3::new(-0.42 * w, h, -0.42 * d),
            Point3::new(0.42 * w, h + 0.002, 0.08 * d),
        ),
        Mesh::cuboid(
            Point3::new(-0.15 * w, h, 0.16 * d),
            Point3::new(0.15 * w, h + 0.001, 0.42 * d),
        ),
        Mesh::cylinder(Point3::new(-hw, h, -hd), Point3::new(-0.7 * hw, h, -hd), 0.5 * h, 10),
        Mesh::cylinder(Point3::new(0.7 * hw, h, -hd), Point3::new(hw, h, -hd), 0.5 * h, 10),
    ]);
    // At rest the lid lies closed on the base, screen facing down.
    let gap = 0.003;
    let lid = Mesh::union([
        Mesh::cuboid(Point3::new(-hw, h + gap, -hd), Point3::new(hw, h + gap + t, hd)),
        Mesh::cuboid(
            Point3::new(-0.46 * w, h + gap - 0.001, -0.44 * d),
            Point3::new(0.46 * w, h + gap, 0.44 * d),
        ),
    ]);
    let mut object = ArticulatedObject::new("laptop", Link { name: "base".into(), mesh: base });
    // Turning about -x lifts the lid's front edge up and back.
    let hinge = Joint {
        name: String::new(),
        kind: JointKind::Revolute,
        parent: 0,
        child: 0,
        pivot: Point3::new(0.0, h, -hd),
        axis: -Vector3::x(),
        limits: (0.0, max_open),
        rest: 0.0,
    };
    object.attach(0, Link { name: "lid".into(), mesh: lid }, hinge);
    object
}
