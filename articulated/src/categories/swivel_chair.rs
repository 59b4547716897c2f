//! Swivel chair: a star base on casters with a gas-lift column; the seat with its back (and
//! maybe armrests) swivels about the column, and on some chairs the lift raises it.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TEST};
use crate::mesh::Mesh;
use crate::objects::tube::tube;
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The swivel chair category.
pub const CATEGORY: Category = Category {
    name: "swivel_chair",
    description: "star base on casters; seat with back and maybe armrests revolute about the column, maybe a prismatic gas lift",
    splits: TEST,
    build,
};

/// Bore of the gas-lift sleeve: the piston column's radius.
const BORE: Real = 0.016;

/// The star base with casters and the gas-lift sleeve; returns it and the sleeve's top.
fn base(rng: &mut Rng) -> (Mesh, Real) {
    let legs = if rng.random_bool(0.8) { 5 } else { 4 };
    let reach = rng.random_range(0.27..0.34);
    let wheel = rng.random_range(0.025..0.035);
    let sleeve = rng.random_range(0.18..0.24);
    let tip = 2.0 * wheel + 0.015;
    let hub_top = tip + 0.08;
    let mut mesh = Mesh::union([
        Mesh::cylinder(
            Point3::new(0.0, tip + 0.005, 0.0),
            Point3::new(0.0, hub_top, 0.0),
            0.045,
            12,
        ),
        tube(
            Point3::new(0.0, hub_top, 0.0),
            Point3::new(0.0, hub_top + sleeve, 0.0),
            BORE,
            0.009,
            10,
        ),
    ]);
    for k in 0..legs {
        let angle = k as Real * std::f32::consts::TAU / legs as Real;
        let (out, side) = (
            Vector3::new(angle.sin(), 0.0, angle.cos()),
            Vector3::new(angle.cos(), 0.0, -angle.sin()),
        );
        let foot = Point3::new(0.0, tip, 0.0) + out * reach;
        let axle = foot - Vector3::y() * (tip - wheel);
        mesh.append(Mesh::beam(
            Point3::new(0.0, tip + 0.04, 0.0),
            foot + Vector3::y() * 0.0175,
            0.045,
            0.035,
            Vector3::y(),
        ));
        mesh.append(Mesh::cylinder(foot, axle, 0.008, 6));
        mesh.append(Mesh::cylinder(axle - side * 0.012, axle + side * 0.012, wheel, 10));
    }
    (mesh, hub_top + sleeve)
}

/// The seat, its back and maybe armrests, with the seat pan's underside at height `y`.
fn seat(rng: &mut Rng, y: Real) -> Mesh {
    let (w, d) = (rng.random_range(0.44..0.54), rng.random_range(0.4..0.5));
    let cushion = rng.random_range(0.05..0.09);
    let back_h = rng.random_range(0.35..0.65);
    let recline = rng.random_range(5.0f32..18.0).to_radians();
    let (hw, front, back) = (0.5 * w, 0.45 * d, -0.55 * d);
    let top = y + 0.015 + cushion;
    let back_foot = Point3::new(0.0, top + 0.05, back - 0.04);
    let back_up = Vector3::new(0.0, recline.cos(), -recline.sin());
    let mut mesh = Mesh::union([
        Mesh::cuboid(Point3::new(-hw, y, back), Point3::new(hw, y + 0.015, front)),
        Mesh::cuboid(
            Point3::new(0.01 - hw, y + 0.015, back + 0.01),
            Point3::new(hw - 0.01, top, front - 0.01),
        ),
        // The spine keeps clear of the lift's mechanism box, which the seat turns above.
        Mesh::beam(
            Point3::new(0.0, y - 0.01, back + 0.05),
            Point3::new(0.0, y - 0.01, back - 0.04),
            0.06,
            0.02,
            Vector3::y(),
        ),
        Mesh::beam(
            Point3::new(0.0, y - 0.015, back - 0.04),
            back_foot + back_up * 0.12,
            0.06,
            0.02,
            Vector3::z(),
        ),
        Mesh::beam(back_foot, back_foot + back_up * back_h, 0.9 * w, 0.05, Vector3::z()),
    ]);
    if rng.random_bool(0.6) {
        let (post_x, rise) = (hw + 0.025, rng.random_range(0.18..0.25));
        let arm = Mesh::union([
            Mesh::beam(
                Point3::new(hw - 0.05, y + 0.0075, -0.05),
                Point3::new(post_x, y + 0.0075, -0.05),
                0.05,
                0.015,
                Vector3::y(),
            ),
            Mesh::beam(
                Point3::new(post_x, y, -0.05),
                Point3::new(post_x, top + rise, -0.05),
                0.05,
                0.025,
                Vector3::z(),
            ),
            Mesh::cuboid(
                Point3::new(post_x - 0.035, top + rise, back + 0.05),
                Point3::new(post_x + 0.035, top + rise + 0.03, front - 0.08),
            ),
        ]);
        mesh.append(arm.clone().mirrored_x());
        mesh.append(arm);
    }
    mesh
}

fn build(rng: &mut Rng) -> ArticulatedObject {
    let (base_mesh, sleeve_top) = base(rng);
    let exposed = rng.random_range(0.03..0.06);
    let swivel = rng.random_range(70.0f32..100.0).to_radians();
    let lift = rng.random_bool(0.5);
    let travel = rng.random_range(0.08..0.12);
    let plate = sleeve_top + exposed;
    // The piston reaches deep into the sleeve, so it stays inside when raised; the
    // mechanism box under the seat is what shows the lift moving.
    let mechanism = Mesh::union([
        Mesh::cylinder(
            Point3::new(0.0, sleeve_top - 0.15, 0.0),
            Point3::new(0.0, plate, 0.0),
            BORE,
            12,
        ),
        Mesh::cuboid(Point3::new(-0.12, plate, -0.11), Point3::new(0.12, plate + 0.06, 0.11)),
        Mesh::beam(
            Point3::new(0.1, plate + 0.02, 0.05),
            Point3::new(0.2, plate + 0.015, 0.08),
            0.02,
            0.01,
            Vector3::y(),
        ),
    ]);
    let mut seat_mesh = seat(rng, plate + 0.06);
    let mut object =
        ArticulatedObject::new("swivel_chair", Link { name: "base".into(), mesh: base_mesh });
    let axis_point = Point3::new(0.0, plate, 0.0);
    let parent = if lift {
        let slide = Joint::prismatic(axis_point, Vector3::y(), (0.0, travel));
        object.attach(0, Link { name: "gas lift".into(), mesh: mechanism }, slide)
    } else {
        seat_mesh.append(mechanism);
        0
    };
    let turn = Joint::revolute(axis_point, Vector3::y(), (-swivel, swivel));
    object.attach(parent, Link { name: "seat".into(), mesh: seat_mesh }, turn);
    object
}
