//! Scissors: two blades with handle loops, turning about a pivot screw.

use pairs::math::{Isometry3, Point3, Real, Vector3};
use pairs::JointKind;
use rand::Rng as _;

use super::catalog::{Category, TEST};
use crate::mesh::Mesh;
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The scissors category.
pub const CATEGORY: Category = Category {
    name: "scissors",
    description: "two blades with handle loops; the upper blade is revolute about the pivot screw",
    splits: TEST,
    build,
};

/// One blade in the plane z = `z`: a tapered blade along +x, a shank along -x and a loop
/// on the `side` (+1 or -1) of the x axis.
fn blade(length: Real, width: Real, thickness: Real, z: Real, side: Real) -> Mesh {
    let blade_len = 0.55 * length;
    let shank_len = 0.2 * length;
    let loop_r = 0.09 * length;
    let half_t = thickness * 0.5;
    // A blade is two boxes: a wide root and a narrower tip, for a tapered outline.
    let root = Mesh::cuboid(
        Point3::new(0.0, -0.5 * width, z - half_t),
        Point3::new(0.6 * blade_len, 0.5 * width, z + half_t),
    );
    let tip = Mesh::cuboid(
        Point3::new(0.6 * blade_len, -0.3 * width, z - half_t),
        Point3::new(blade_len, 0.25 * width, z + half_t),
    );
    let shank = Mesh::oriented_cuboid(
        &Isometry3::new(
            Vector3::new(-0.5 * shank_len, side * 0.3 * loop_r, z),
            Vector3::z() * (side * -0.3),
        ),
        Vector3::new(0.55 * shank_len, 0.3 * width, half_t),
    );
    let ring = Mesh::ring(
        Point3::new(-shank_len - 0.6 * loop_r, side * 1.1 * loop_r, z),
        loop_r,
        0.15 * loop_r,
        12,
    );
    Mesh::union([root, tip, shank, ring])
}

fn build(rng: &mut Rng) -> ArticulatedObject {
    let length = rng.random_range(0.15..0.25);
    let width = length * rng.random_range(0.1..0.16);
    let thickness = rng.random_range(0.002..0.004);
    let max_open = rng.random_range(40.0f32..65.0).to_radians();
    let mut lower = blade(length, width, thickness, 0.0, 1.0);
    // The pivot screw's head shows below the lower blade; it stops at the blade's top face
    // so that the upper blade turns on it without the two passing through each other.
    lower.append(Mesh::cylinder(
        Point3::new(0.0, 0.0, -1.5 * thickness),
        Point3::new(0.0, 0.0, 0.5 * thickness),
        0.25 * width,
        10,
    ));
    // The upper blade lies one thickness above the lower one; its loop is on the other side
    // of the pivot line, so that opening the blades spreads the loops as in real scissors.
    let upper = blade(length, width, thickness, thickness * 1.05, -1.0);
    let mut object =
        ArticulatedObject::new("scissors", Link { name: "lower blade".into(), mesh: lower });
    let pivot = Joint {
        name: String::new(),
        kind: JointKind::Revolute,
        parent: 0,
        child: 0,
        pivot: Point3::origin(),
        axis: Vector3::z(),
        limits: (0.0, max_open),
        rest: 0.0,
    };
    object.attach(0, Link { name: "upper blade".into(), mesh: upper }, pivot);
    object
}
