//! Faucet: a body on a deck plate; a spout on a collar round the body swivels about the
//! body's axis, and a lever on top of the body tilts up to open.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TEST};
use crate::mesh::Mesh;
use crate::objects::arm::Section;
use crate::objects::tube::tube;
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The faucet category.
pub const CATEGORY: Category = Category {
    name: "faucet",
    description: "body on a deck plate; spout revolute about the body's vertical axis; lever revolute tilting up",
    splits: TEST,
    build,
};

/// The spout: a collar of staves round the body over heights `ys`, and a tube reaching
/// forward from it that turns down into a nozzle.
fn spout(rng: &mut Rng, body: Real, (y0, y1): (Real, Real)) -> Mesh {
    let wall = rng.random_range(0.006..0.008);
    let radius = rng.random_range(0.35..0.45) * (y1 - y0);
    let rise = rng.random_range(0.0f32..8.0).to_radians();
    let length = rng.random_range(0.14..0.24);
    let mid = 0.5 * (y0 + y1);
    let start = Point3::new(0.0, mid, body + 0.5 * wall);
    let end = start + Vector3::new(0.0, rise.sin(), rise.cos()) * length;
    let drop = rng.random_range(0.025f32..0.045).min(mid - 0.03);
    let nozzle = end - Vector3::y() * drop;
    Mesh::union([
        tube(Point3::new(0.0, y0, 0.0), Point3::new(0.0, y1, 0.0), body, wall, 10),
        Mesh::cylinder(start, end, radius, 12),
        Mesh::sphere(end, radius, 12),
        Mesh::cylinder(end, nozzle, radius, 12),
        Mesh::cylinder(nozzle, nozzle - Vector3::y() * 0.012, 1.15 * radius, 12),
    ])
}

/// The lever on the body's top at height `top`, pointing forward (`side` = 1) or back
/// (-1), and the cartridge cheeks that hold its hub; returns the cheeks (part of the body),
/// the lever, and the joint that lifts the lever's tip.
fn lever(rng: &mut Rng, body: Real, top: Real, side: Real) -> (Mesh, Mesh, Joint) {
    let hub = rng.random_range(0.5..0.65) * body;
    let half = rng.random_range(0.6..0.7) * body;
    let tilt = rng.random_range(10.0f32..25.0).to_radians();
    let length = rng.random_range(0.07..0.11);
    let (width, thick) = (rng.random_range(0.7..0.9) * 2.0 * half, rng.random_range(0.008..0.012));
    let paddle = rng.random_range(0.025..0.035);
    let lift = rng.random_range(30.0f32..45.0).to_radians();
    let pivot = Point3::new(0.0, top + hub + 0.002, 0.0);
    let out = Vector3::new(0.0, tilt.sin(), side * tilt.cos());
    let tip = pivot + out * length;
    // The hub touches the cheeks through its flat ends, whatever the lever's angle.
    let cheeks = Section { half, cheek: 0.25 * body, depth: 2.4 * hub }
        .fork(Point3::new(0.0, top, 0.0), pivot);
    let mesh = Mesh::union([
        Mesh::cylinder(pivot - Vector3::x() * half, pivot + Vector3::x() * half, hub, 12),
        Mesh::beam(pivot, tip, width, thick, Vector3::y()),
        Mesh::beam(tip - out * (0.3 * length), tip, paddle, 1.2 * thick, Vector3::y()),
    ]);
    // Turning about -x lifts a forward tip; a backward one turns about +x.
    (cheeks, mesh, Joint::revolute(pivot, Vector3::x() * -side, (0.0, lift)))
}

fn build(rng: &mut Rng) -> ArticulatedObject {
    let body = rng.random_range(0.022..0.03);
    let plate = (body + rng.random_range(0.012..0.02), rng.random_range(0.008..0.012));
    let top = plate.1 + rng.random_range(0.11..0.16);
    let collar_foot = plate.1 + rng.random_range(0.02..0.035);
    let collar = (collar_foot, collar_foot + rng.random_range(0.03..0.04));
    let swivel = rng.random_range(50.0f32..70.0).to_radians();
    let side = if rng.random_bool(0.7) { 1.0 } else { -1.0 };
    let (cheeks, lever_mesh, hinge) = lever(rng, body, top, side);
    let root = Mesh::union([
        cheeks,
        Mesh::cylinder(Point3::origin(), Point3::new(0.0, plate.1, 0.0), plate.0, 16),
        Mesh::cylinder(Point3::new(0.0, plate.1, 0.0), Point3::new(0.0, top, 0.0), body, 16),
        Mesh::cylinder(
            Point3::new(0.0, plate.1, 0.0),
            Point3::new(0.0, plate.1 + 0.008, 0.0),
            body + 0.004,
            16,
        ),
    ]);
    let mut object = ArticulatedObject::new("faucet", Link { name: "body".into(), mesh: root });
    let spout_mesh = spout(rng, body, collar);
    let turn = Joint::revolute(Point3::origin(), Vector3::y(), (-swivel, swivel));
    object.attach(0, Link { name: "spout".into(), mesh: spout_mesh }, turn);
    object.attach(0, Link { name: "lever".into(), mesh: lever_mesh }, hinge);
    object
}
