//! Printer: a body with a control panel sloping at its front and a scanner on top; the
//! scanner lid (some with a document feeder on it) turns up about a hinge rod along
//! the back. Below the panel, an output tray slides out of a slot in the front, or a front
//! flap folds down about its lower edge, or both.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, VALIDATION};
use crate::mesh::Mesh;
use crate::objects::bracket::bracket_hinge;
use crate::objects::contact::pad_thickness;
use crate::objects::profile::block;
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The printer category.
pub const CATEGORY: Category = Category {
    name: "printer",
    description: "body with control panel; scanner lid revolute at the back; a prismatic \
                  output tray, a revolute front flap, or both",
    splits: VALIDATION,
    build,
};

/// The output tray in a slot over x in ±`half_x`, y from `y0` to `y1`, reaching `depth`
/// back from the front face at z = `front`: the tray for the moving part, the slot's walls
/// for the body, and the joint that pulls the tray out.
fn tray(
    half_x: Real,
    (y0, y1): (Real, Real),
    front: Real,
    depth: Real,
    travel: Real,
) -> (Mesh, Mesh, Joint) {
    let back = front - depth + 0.003;
    let (hx, t) = (half_x - 0.002, 0.004);
    // Thin plates where the tray rests on the slot's floor keep the contact query exact;
    // the tray's plate stays inside the slot at full travel.
    let p = pad_thickness(half_x);
    let tray = Mesh::union([
        block(Point3::new(-hx, y0, back), Point3::new(hx, y0 + t, front)),
        block(Point3::new(-hx, y0, back), Point3::new(-hx + t, y0 + 0.3 * (y1 - y0), front)),
        block(Point3::new(hx - t, y0, back), Point3::new(hx, y0 + 0.3 * (y1 - y0), front)),
        block(Point3::new(-hx, y0, front - t), Point3::new(hx, y1 - 0.002, front)),
        block(
            Point3::new(-0.2 * hx, y0 + 0.5 * (y1 - y0), front),
            Point3::new(0.2 * hx, y0 + 0.7 * (y1 - y0), front + 0.006),
        ),
        block(Point3::new(-0.5 * hx, y0, back), Point3::new(0.5 * hx, y0 + p, front - travel)),
    ]);
    let floor =
        block(Point3::new(-0.5 * hx, y0 - p, front - depth), Point3::new(0.5 * hx, y0, front));
    (tray, floor, Joint::slide(Point3::new(0.0, y0, front), Vector3::z(), travel))
}

fn build(rng: &mut Rng) -> ArticulatedObject {
    let w = rng.random_range(0.38..0.5);
    let h = rng.random_range(0.16..0.26);
    let d = rng.random_range(0.3..0.42);
    let panel = d * rng.random_range(0.18..0.26);
    let kind = rng.random_range(0..3);
    let (has_tray, has_flap) = (kind != 1, kind != 0);
    let feeder = rng.random_bool(0.4);
    let max_lid = rng.random_range(60.0f32..85.0).to_radians();
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let top = h - 0.03;
    let slot = (0.58 * h, 0.7 * h);
    let slot_x = 0.35 * w;
    // One convex piece for the body above the slot, its top and the sloping panel.
    let base = if has_tray { slot.1 } else { 0.012 };
    let crown = [(-hd, h), (hd - panel, h), (hd, top), (hd, base), (-hd, base)]
        .iter()
        .flat_map(|&(z, y)| [Point3::new(-hw, y, z), Point3::new(hw, y, z)])
        .collect::<Vec<_>>();
    let mut body = vec![Mesh::hull(&crown)];
    let slope = |f: Real, x: Real| Point3::new(x, h - f * (h - top), hd - panel + f * panel);
    let display = [slope(0.3, -0.3 * w), slope(0.3, 0.0), slope(0.7, -0.3 * w), slope(0.7, 0.0)];
    body.push(Mesh::hull(&[display, display.map(|p| p + Vector3::y() * 0.003)].concat()));
    for k in 0..3 {
        let c = slope(0.5, 0.1 * w + 0.05 * w * k as Real);
        body.push(Mesh::cylinder(c - Vector3::y() * 0.004, c + Vector3::y() * 0.004, 0.008, 10));
    }
    for (x, z) in [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)] {
        body.push(block(
            Point3::new(x * (hw - 0.02), 0.0, z * (hd - 0.02)),
            Point3::new(x * (hw - 0.05), 0.012, z * (hd - 0.05)),
        ));
    }
    let mut moving: Vec<(&str, Mesh, Joint)> = Vec::new();
    // The lid rests on the scanner; a hinge rod along its back turns in cheeks on the body.
    let (lid_t, r) = (rng.random_range(0.015..0.025), 0.008);
    let lid_y = h;
    let pivot = Point3::new(0.0, lid_y + r, -hd - r);
    let span = hw - 0.008;
    let (cheeks, rod, lid_joint) =
        bracket_hinge(pivot, -Vector3::x(), span, r, Vector3::z() * r, max_lid);
    body.push(cheeks);
    let mut lid = vec![
        rod,
        block(Point3::new(-span, lid_y, -hd), Point3::new(span, lid_y + lid_t, hd - panel - 0.004)),
        block(
            Point3::new(-0.2 * w, lid_y + 0.3 * lid_t, hd - panel - 0.004),
            Point3::new(0.2 * w, lid_y + 0.7 * lid_t, hd - panel),
        ),
    ];
    if feeder {
        let fy = lid_y + lid_t;
        lid.push(Mesh::hull(
            &[
                (-span, 0.0, -hd),
                (-span, 0.05, -hd),
                (-span, 0.0, -hd + 0.25 * d),
                (-span, 0.02, -hd + 0.25 * d),
                (0.3 * span, 0.0, -hd),
                (0.3 * span, 0.05, -hd),
                (0.3 * span, 0.0, -hd + 0.25 * d),
                (0.3 * span, 0.02, -hd + 0.25 * d),
            ]
            .map(|(x, y, z)| Point3::new(x, fy + y, z)),
        ));
    }
    moving.push(("scanner lid", Mesh::union(lid), lid_joint));
    if has_tray {
        let depth = d * rng.random_range(0.4..0.55);
        let travel = depth * rng.random_range(0.75..0.92);
        let (mesh, floor, joint) = tray(slot_x, slot, hd, depth, travel);
        body.extend([
            block(Point3::new(-hw, 0.012, -hd), Point3::new(hw, slot.0, hd)),
            block(Point3::new(-hw, slot.0, -hd), Point3::new(-slot_x, slot.1, hd)),
            block(Point3::new(slot_x, slot.0, -hd), Point3::new(hw, slot.1, hd)),
            block(Point3::new(-slot_x, slot.0, -hd), Point3::new(slot_x, slot.1, hd - depth)),
            floor,
        ]);
        moving.push(("output tray", mesh, joint));
    }
    if has_flap {
        // The flap closes the front below the slot; a hinge along its lower edge lets it
        // fold down to a level shelf.
        let rf = 0.006;
        let fy1 = if has_tray { slot.0 - 0.01 } else { slot.1 };
        let (fy0, fx) = (0.05 * h, 0.45 * w);
        let pivot = Point3::new(0.0, fy0, hd + rf);
        let max = rng.random_range(80.0f32..92.0).to_radians();
        let (cheeks, knuckle, joint) =
            bracket_hinge(pivot, Vector3::x(), fx, rf, -Vector3::z() * rf, max);
        body.push(cheeks);
        let flap = Mesh::union([
            knuckle,
            block(Point3::new(-fx, fy0, hd), Point3::new(fx, fy1, hd + 2.0 * rf)),
            block(
                Point3::new(-0.3 * fx, fy1 - 0.015, hd + 2.0 * rf),
                Point3::new(0.3 * fx, fy1 - 0.005, hd + 2.0 * rf + 0.006),
            ),
        ]);
        moving.push(("front flap", flap, joint));
    }
    let mut object =
        ArticulatedObject::new("printer", Link { name: "body".into(), mesh: Mesh::union(body) });
    for (name, mesh, joint) in moving {
        object.attach(0, Link { name: name.into(), mesh }, joint);
    }
    object
}
