//! Robot arm: a flanged base and pedestal; a turret turning about the vertical; an upper
//! arm and a forearm pitching about horizontal axes, and on some arms a wrist with a
//! gripper, each hinged to the previous link.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TRAIN};
use crate::mesh::Mesh;
use crate::objects::arm::{heading, Section};
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The robot arm category.
pub const CATEGORY: Category = Category {
    name: "robot_arm",
    description: "base; turret revolute about the vertical; upper arm, forearm and maybe a wrist revolute about horizontal axes in a chain",
    splits: TRAIN,
    build,
};

/// A gripper hinged at `pivot`, pointing along `dir`: a fork, a palm and two fingers.
fn gripper(pivot: Point3, dir: Vector3, section: &Section) -> Mesh {
    let (depth, outer) = (section.depth, section.outer());
    let palm = pivot + dir * (1.2 * depth);
    let finger = |x: Real| {
        let root = Point3::new(x, palm.y, palm.z);
        Mesh::beam(root, root + dir * (2.0 * depth), 0.5 * depth, 0.25 * outer, Vector3::x())
    };
    Mesh::union([
        section.fork(pivot, palm),
        Mesh::beam(palm, palm + dir * (0.4 * depth), 1.2 * depth, 2.0 * outer, Vector3::x()),
        finger(0.7 * outer),
        finger(-0.7 * outer),
    ])
}

fn build(rng: &mut Rng) -> ArticulatedObject {
    let (base_r, base_h) = (rng.random_range(0.12..0.18), rng.random_range(0.025..0.04));
    let pedestal = (base_r * rng.random_range(0.55..0.7), base_h + rng.random_range(0.08..0.18));
    let turret_top = pedestal.1 + rng.random_range(0.05..0.08);
    let section = Section {
        half: rng.random_range(0.03..0.045),
        cheek: rng.random_range(0.015..0.025),
        depth: rng.random_range(0.06..0.09),
    };
    let (depth, outer) = (section.depth, section.outer());
    let shoulder = Point3::new(0.0, turret_top + 0.5 * depth + rng.random_range(0.01..0.02), 0.0);
    let root = Mesh::union([
        Mesh::cylinder(Point3::origin(), Point3::new(0.0, base_h, 0.0), base_r, 16),
        Mesh::cylinder(
            Point3::new(0.0, base_h, 0.0),
            Point3::new(0.0, pedestal.1, 0.0),
            pedestal.0,
            16,
        ),
    ]);
    // A square turret, with its motor beside the shoulder fork, outside every arm link's
    // slab; its corners show it turning.
    let r = pedestal.0;
    let turret = Mesh::union([
        Mesh::cuboid(
            Point3::new(-0.85 * r, pedestal.1, -r),
            Point3::new(0.85 * r, turret_top, 0.7 * r),
        ),
        section.fork(Point3::new(0.0, turret_top, 0.0), shoulder),
        Mesh::cuboid(
            Point3::new(outer + 0.005, pedestal.1 + 0.01, -0.6 * r),
            Point3::new(outer + 0.07, turret_top + 0.05, 0.05),
        ),
    ]);
    let mut object = ArticulatedObject::new("robot_arm", Link { name: "base".into(), mesh: root });
    let spin = rng.random_range(120.0f32..170.0).to_radians();
    let mut parent = object.attach(
        0,
        Link { name: "turret".into(), mesh: turret },
        Joint::revolute(Point3::origin(), Vector3::y(), (-spin, spin)),
    );
    let lean = rng.random_range(-5.0f32..15.0);
    let elbow = shoulder + heading(lean.to_radians()) * rng.random_range(0.3..0.45);
    let reach = rng.random_range(70.0f32..90.0);
    let tip = elbow + heading(reach.to_radians()) * rng.random_range(0.25..0.4);
    // The chain never folds tighter than 65 degrees at the elbow, nor points the forearm
    // steeper than 30 degrees off straight down, so the arm cannot reach into its base.
    let swing = rng.random_range(30.0f32..45.0);
    let upper = Link { name: "upper arm".into(), mesh: section.bar(shoulder, elbow) };
    let shoulder_joint =
        Joint::revolute(shoulder, Vector3::x(), (-swing.to_radians(), swing.to_radians()));
    parent = object.attach(parent, upper, shoulder_joint);
    let close =
        rng.random_range(40.0f32..60.0).min(115.0 - (reach - lean)).min(150.0 - reach - swing);
    let open = rng.random_range(50.0f32..70.0);
    let forearm = Link { name: "forearm".into(), mesh: section.fork_to_bar(elbow, tip) };
    parent = object.attach(
        parent,
        forearm,
        Joint::revolute(elbow, Vector3::x(), (-open.to_radians(), close.to_radians())),
    );
    let cock = rng.random_range(10.0f32..30.0);
    let hand = gripper(tip, heading((reach + cock).to_radians()), &section);
    if rng.random_bool(0.5) {
        // Folding in, the palm stops short of the forearm.
        let flex =
            (rng.random_range(70.0f32..90.0), rng.random_range(70.0f32..90.0).min(110.0 - cock));
        let wrist = Joint::revolute(tip, Vector3::x(), (-flex.0.to_radians(), flex.1.to_radians()));
        object.attach(parent, Link { name: "gripper".into(), mesh: hand }, wrist);
    } else {
        object.links[parent].mesh.append(hand);
    }
    object
}
