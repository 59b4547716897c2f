//! Washing machine (front loader): a box with a worktop, a control strip with a program
//! dial, display and buttons, a detergent drawer that pulls out of the strip, and a round
//! glazed porthole door that swings open about hinge knuckles on one side.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TEST};
use crate::mesh::Mesh;
use crate::objects::carcass::open_box;
use crate::objects::container::corner_feet;
use crate::objects::controls::{button, knob};
use crate::objects::door::HingeSide;
use crate::objects::drawer::drawer;
use crate::objects::joints::{knuckles, mirrored_part, vertical_hinge};
use crate::objects::round::annulus;
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The washing machine category.
pub const CATEGORY: Category = Category {
    name: "washing_machine",
    description: "front loader with control strip; round door revolute about a side hinge, detergent drawer prismatic",
    splits: TEST,
    build,
};

/// Radius of the hinge knuckles, and how far the hinge axis sits out from the door's rim.
const KNUCKLE: (Real, Real) = (0.012, 0.028);

/// The porthole door centred at `(0, cy)` with outer radius `r` in front of the plane
/// `z = back`, `depth` deep, hinged on the left; returns the door, the hinge parts fixed to
/// the body, and the joint. The axis lies on the door's front plane, so the door never
/// swings behind its own back plane into the body.
fn porthole(cy: Real, r: Real, back: Real, depth: Real, max_angle: Real) -> (Mesh, Mesh, Joint) {
    let tube = 0.5 * depth;
    let centre = Point3::new(0.0, cy, back + tube);
    let (kr, offset) = KNUCKLE;
    let pivot = Point3::new(-r - offset, cy, back + depth);
    let span = (cy - 0.1, cy + 0.1);
    let (frame_knuckles, door_knuckle) = knuckles(pivot, span, kr, 3);
    let step = (span.1 - span.0) / 3.0;
    let door = Mesh::union([
        annulus(centre, (r - 2.0 * tube, r), depth, 14),
        annulus(
            centre + Vector3::z() * 0.3 * tube,
            (r - 3.0 * tube, r - 2.0 * tube),
            0.6 * tube,
            14,
        ),
        Mesh::cylinder(
            centre - Vector3::z() * 0.3 * tube,
            centre + Vector3::z() * 0.3 * tube,
            r - 2.5 * tube,
            14,
        ),
        door_knuckle,
        // The arm from the knuckle to the rim, level with the door's knuckle.
        Mesh::cuboid(
            Point3::new(pivot.x, span.0 + step, back + 0.4 * depth),
            Point3::new(-r + tube, span.0 + 2.0 * step, back + depth),
        ),
        // The pull on the free side.
        Mesh::cuboid(
            Point3::new(r - tube, cy - 0.05, back),
            Point3::new(r + 0.025, cy + 0.05, back + depth),
        ),
    ]);
    let mut fixed = frame_knuckles;
    for y in [span.0, span.0 + 2.0 * step] {
        fixed.append(Mesh::cuboid(
            Point3::new(pivot.x - kr, y, back - 0.02),
            Point3::new(pivot.x + kr, y + step, pivot.z),
        ));
    }
    (door, fixed, vertical_hinge(pivot, HingeSide::Left, max_angle))
}

fn build(rng: &mut Rng) -> ArticulatedObject {
    let w = rng.random_range(0.56..0.64);
    let h = rng.random_range(0.82..0.9);
    let d = rng.random_range(0.5..0.62);
    let strip = rng.random_range(0.1..0.13);
    let r = w * rng.random_range(0.31..0.36);
    let depth = rng.random_range(0.05..0.07);
    let drawer_w = w * rng.random_range(0.28..0.38);
    let max_door = rng.random_range(95.0f32..160.0).to_radians();
    let travel = rng.random_range(0.7..0.85);
    let hinge_right = rng.random_bool(0.3);
    let (hw, hd, top, foot, hwall) = (0.5 * w, 0.5 * d, 0.02, 0.02, 0.006);
    let ys = h - top - strip;
    let xd = -hw + drawer_w;
    let mut body = Mesh::union([
        Mesh::cuboid(Point3::new(-hw, foot, -hd), Point3::new(hw, ys, hd)),
        Mesh::cuboid(Point3::new(-hw - 0.005, h - top, -hd), Point3::new(hw + 0.005, h, hd + 0.01)),
        open_box(Point3::new(-hw, ys, -hd), Point3::new(xd, h - top, hd), hwall),
        Mesh::cuboid(Point3::new(xd, ys, -hd), Point3::new(hw, h - top, hd)),
        // Controls: dial, display and buttons on the strip; a service hatch at the bottom.
        knob(Point3::new(hw - 0.3 * (hw - xd), ys + 0.5 * strip, hd), 0.35 * strip, 0.025, 1.0),
        button(xd + 0.3 * (hw - xd), ys + 0.6 * strip, hd, (0.3 * (hw - xd), 0.3 * strip), 0.004),
        button(hw - 0.12 * w, foot + 0.07, hd, (0.16 * w, 0.09), 0.004),
    ]);
    for i in 0..4 {
        let x = xd + (0.18 + 0.08 * i as Real) * (hw - xd);
        body.append(button(x, ys + 0.25 * strip, hd, (0.05 * (hw - xd), 0.12 * strip), 0.006));
    }
    body.append(corner_feet(hw - 0.05, hd - 0.05, foot, 0.02));
    let cy = ys - 0.05 - r;
    let gasket = 0.008;
    body.append(annulus(Point3::new(0.0, cy, hd + gasket), (0.7 * r, 0.85 * r), 2.0 * gasket, 14));
    let (mut door, mut fixed, mut hinge) =
        porthole(cy, r, hd + 2.0 * gasket + 0.002, depth, max_door);
    if hinge_right {
        (door, fixed, hinge) = mirrored_part(door, fixed, &hinge);
    }
    body.append(fixed);
    let (dwall, dd) = (hwall + 0.004, 0.55 * d);
    let (mut tray, slide) = drawer(
        (-hw + 0.003, xd - 0.003),
        (ys + hwall, h - top - 0.003),
        hd,
        dd,
        dwall,
        travel * dd,
    );
    // Dividers part the tray into compartments for powder and liquid side by side, and
    // for softener at the back.
    let (y0, y1) = (ys + hwall + dwall, h - top - 0.003 - 1.5 * dwall);
    let (x0, x1) = (-hw + 0.003 + dwall, xd - 0.003 - dwall);
    let (xm, zm) = (x0 + 0.45 * (x1 - x0), hd - 0.6 * dd);
    tray.append(Mesh::cuboid(Point3::new(xm, y0, zm), Point3::new(xm + 0.004, y1, hd)));
    tray.append(Mesh::cuboid(Point3::new(x0, y0, zm - 0.004), Point3::new(x1, y1, zm)));
    let mut object =
        ArticulatedObject::new("washing_machine", Link { name: "body".into(), mesh: body });
    object.attach(0, Link { name: "door".into(), mesh: door }, hinge);
    object.attach(0, Link { name: "detergent drawer".into(), mesh: tray }, slide);
    object
}
