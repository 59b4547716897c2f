//! Microwave oven: a box with a cavity and a turntable (which is not a joint: it is
//! symmetric), a control panel with a display, buttons and a dial beside it, and a glazed
//! door hinged on the side away from the panel.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TEST};
use crate::mesh::Mesh;
use crate::objects::carcass::{cavity, open_box};
use crate::objects::container::corner_feet;
use crate::objects::controls::{button, knob};
use crate::objects::door::HingeSide;
use crate::objects::handle::bar_handle;
use crate::objects::joints::{mirrored_part, vertical_hinge};
use crate::objects::panel::framed_panel;
use crate::objects::{ArticulatedObject, Link};
use crate::seed::Rng;

/// The microwave category.
pub const CATEGORY: Category = Category {
    name: "microwave",
    description: "box with a turntable cavity and a control panel; glazed door revolute about a vertical side hinge",
    splits: TEST,
    build,
};

/// The control panel over `x0..x1`, `y0..y1` on the face `z = z`: a display on top, a grid
/// of buttons, a dial and a door-release button at the bottom.
fn controls((x0, x1): (Real, Real), (y0, y1): (Real, Real), z: Real, rows: u32) -> Mesh {
    let (cx, w, h) = (0.5 * (x0 + x1), x1 - x0, y1 - y0);
    let mut mesh = Mesh::union([
        button(cx, y1 - 0.12 * h, z, (0.7 * w, 0.1 * h), 0.004),
        knob(Point3::new(cx, y0 + 0.3 * h, z), 0.22 * w, 0.02, 0.6),
        button(cx, y0 + 0.09 * h, z, (0.6 * w, 0.08 * h), 0.008),
    ]);
    let pitch = 0.35 * h / rows as Real;
    for r in 0..rows {
        for c in 0..3 {
            let (x, y) = (x0 + (0.25 + 0.25 * c as Real) * w, y1 - 0.25 * h - r as Real * pitch);
            mesh.append(button(x, y, z, (0.18 * w, 0.6 * pitch), 0.004));
        }
    }
    mesh
}

fn build(rng: &mut Rng) -> ArticulatedObject {
    let w = rng.random_range(0.45..0.6);
    let h = rng.random_range(0.26..0.34);
    let d = rng.random_range(0.34..0.45);
    let wall = rng.random_range(0.012..0.02);
    let panel = w * rng.random_range(0.2..0.26);
    let t = rng.random_range(0.03..0.045);
    let foot = rng.random_range(0.008..0.015);
    let rows = rng.random_range(2..5u32);
    let max_open = rng.random_range(95.0f32..115.0).to_radians();
    let panel_left = rng.random_bool(0.25);
    let (hw, hd, g) = (0.5 * w, 0.5 * d, 0.003);
    // Built with the panel on the right and the hinge on the left, then mirrored if needed.
    let xp = hw - panel;
    let (lo, hi) = (Point3::new(-hw, foot, -hd), Point3::new(xp, h, hd));
    let (inner_lo, inner_hi) = cavity(lo, hi, wall);
    let plate_r = 0.42 * (inner_hi.x - inner_lo.x).min(inner_hi.z - inner_lo.z);
    let (cx, cz, floor) =
        (0.5 * (inner_lo.x + inner_hi.x), 0.5 * (inner_lo.z + inner_hi.z), inner_lo.y);
    let mut body = Mesh::union([
        open_box(lo, hi, wall),
        Mesh::cuboid(Point3::new(xp, foot, -hd), Point3::new(hw, h, hd + t)),
        controls((xp + 0.01, hw - 0.01), (foot + 0.02, h - 0.02), hd + t, rows),
        // The turntable: a glass plate on a hub, turning about its own axis (a symmetry).
        Mesh::cylinder(Point3::new(cx, floor, cz), Point3::new(cx, floor + 0.012, cz), 0.08, 10),
        Mesh::cylinder(
            Point3::new(cx, floor + 0.012, cz),
            Point3::new(cx, floor + 0.018, cz),
            plate_r,
            16,
        ),
    ]);
    body.append(corner_feet(hw - 0.04, hd - 0.04, foot, 0.015));
    let x1 = xp - g;
    let dw = x1 + hw;
    let border = [0.12 * dw, 0.22 * dw, 0.18 * h, 0.14 * h];
    let mut door = framed_panel((-hw, x1), (foot, h), hd, t, border, 0.006);
    let hx = x1 - 0.08 * dw;
    let (ya, yb) = (foot + 0.3 * (h - foot), foot + 0.7 * (h - foot));
    door.append(bar_handle(
        Point3::new(hx, ya, hd + t),
        Point3::new(hx, yb, hd + t),
        Vector3::z(),
        0.03,
        0.008,
    ));
    let mut hinge = vertical_hinge(Point3::new(-hw, foot, hd), HingeSide::Left, max_open);
    if panel_left {
        (door, body, hinge) = mirrored_part(door, body, &hinge);
    }
    let mut object = ArticulatedObject::new("microwave", Link { name: "body".into(), mesh: body });
    object.attach(0, Link { name: "door".into(), mesh: door }, hinge);
    object
}
