//! Folding chair: two side frames, each a front leg running up and back into a back post,
//! carry a backrest; the seat pivots about an axle between them and folds up, and on some
//! chairs the back legs fold forward against the front legs.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TEST};
use crate::mesh::Mesh;
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The folding chair category.
pub const CATEGORY: Category = Category {
    name: "folding_chair",
    description: "side frames with backrest; seat revolute about its axle folding up, maybe back legs revolute folding forward",
    splits: TEST,
    build,
};

/// The seat, `w` wide, pivoting about the x axis through `(0, y, 0)`: `front` ahead of the
/// axle and `back` behind it, a panel or slats on two rails.
fn seat(rng: &mut Rng, w: Real, y: Real, (front, back): (Real, Real)) -> Mesh {
    let t = rng.random_range(0.015..0.025);
    let hw = 0.5 * w - 0.005;
    let mut mesh = Mesh::union([
        Mesh::cylinder(Point3::new(-0.5 * w, y, 0.0), Point3::new(0.5 * w, y, 0.0), 0.6 * t, 10),
        Mesh::cylinder(Point3::new(-hw, y, front), Point3::new(hw, y, front), 0.5 * t, 10),
    ]);
    let rail = Mesh::cuboid(
        Point3::new(hw - 0.03, y - 0.5 * t - 0.02, -back),
        Point3::new(hw - 0.01, y, front),
    );
    mesh.append(rail.clone().mirrored_x());
    mesh.append(rail);
    let slats = if rng.random_bool(0.4) { rng.random_range(4..7) } else { 1 };
    let pitch = (front + back) / slats as Real;
    let gap = if slats > 1 { 0.2 * pitch } else { 0.0 };
    for k in 0..slats {
        let z0 = -back + k as Real * pitch;
        mesh.append(Mesh::cuboid(
            Point3::new(-hw, y - 0.5 * t, z0),
            Point3::new(hw, y + 0.5 * t, z0 + pitch - gap),
        ));
    }
    mesh
}

fn build(rng: &mut Rng) -> ArticulatedObject {
    let w = rng.random_range(0.38..0.46);
    let d = rng.random_range(0.36..0.44);
    let y_seat = rng.random_range(0.42..0.47);
    let tube = rng.random_range(0.02..0.026);
    let lean = rng.random_range(14.0f32..22.0).to_radians();
    let height = y_seat + rng.random_range(0.35..0.45);
    let front = d * rng.random_range(0.55..0.65);
    let fold = rng.random_range(75.0f32..88.0).to_radians();
    let legs_fold = rng.random_bool(0.6);
    let y_knee = y_seat - rng.random_range(0.03..0.07);
    let splay = rng.random_range(0.2..0.28);
    // The side frame's line, through the seat axle at (0, y_seat, 0), leaning back.
    let up = Vector3::new(0.0, lean.cos(), -lean.sin());
    let on_frame = |y: Real| Point3::new(0.0, y_seat, 0.0) + up * ((y - y_seat) / lean.cos());
    let (inner, outer) = (0.5 * w, 0.5 * w + tube);
    let at = |p: Point3, x: Real| Point3::new(x, p.y, p.z);
    let post_x = inner + 0.5 * tube;
    let side = Mesh::beam(
        at(on_frame(0.0), post_x),
        at(on_frame(height), post_x),
        tube,
        tube,
        Vector3::x(),
    );
    let back_panel = Mesh::beam(
        on_frame(height - rng.random_range(0.15..0.22)),
        on_frame(height - 0.03),
        w + tube,
        0.015,
        Vector3::z(),
    );
    let front_bar =
        Mesh::beam(at(on_frame(0.08), -outer), at(on_frame(0.08), outer), 0.02, 0.02, Vector3::y());
    let mut frame = Mesh::union([side.clone().mirrored_x(), side, back_panel, front_bar]);
    // Back legs: from the knee on the frame down and back to the floor, braced low down.
    let knee = on_frame(y_knee);
    let foot = Point3::new(0.0, 0.0, knee.z - splay);
    let leg_x = outer + 0.5 * tube;
    let brace = knee + (foot - knee) * 0.65;
    let leg = Mesh::union([
        Mesh::beam(at(knee, leg_x), at(foot, leg_x), tube, tube, Vector3::x()),
        Mesh::cylinder(at(knee, outer), at(knee, outer + tube + 0.004), 0.6 * tube, 10),
    ]);
    let legs = Mesh::union([
        leg.clone().mirrored_x(),
        leg,
        Mesh::beam(at(brace, -outer - tube), at(brace, outer + tube), 0.02, 0.02, Vector3::y()),
    ]);
    // Folded, the back legs stop short of the front legs so their brace clears them.
    // The frame's foot never sits on the knee; if it did, the legs would point straight down.
    let down_front = pairs::math::unit_or(&(on_frame(0.0) - knee), -Vector3::y());
    let spread = down_front.angle(&(foot - knee)) - 8f32.to_radians();
    let folding_legs = if legs_fold {
        Some(legs)
    } else {
        frame.append(legs);
        None
    };
    let seat_mesh = seat(rng, w, y_seat, (front, d - front));
    let mut object =
        ArticulatedObject::new("folding_chair", Link { name: "frame".into(), mesh: frame });
    let axle = Point3::new(0.0, y_seat, 0.0);
    object.attach(
        0,
        Link { name: "seat".into(), mesh: seat_mesh },
        Joint::revolute(axle, -Vector3::x(), (0.0, fold)),
    );
    if let Some(legs) = folding_legs {
        let hinge = Joint::revolute(knee, -Vector3::x(), (0.0, spread));
        object.attach(0, Link { name: "back legs".into(), mesh: legs }, hinge);
    }
    object
}
