//! USB stick: a flat body with a rounded back, a metal USB-A plug and sometimes a lanyard
//! loop; a U-shaped swivel bracket clasps the body's faces and turns up to half a turn about
//! a pin through the body near its back, uncovering the plug.

use pairs::math::{Isometry3, Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TEST};
use crate::mesh::Mesh;
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The usb_stick category.
pub const CATEGORY: Category = Category {
    name: "usb_stick",
    description:
        "flat body with a USB plug; a U-shaped swivel bracket revolute about a pin near the back",
    splits: TEST,
    build,
};

fn build(rng: &mut Rng) -> ArticulatedObject {
    let length = rng.random_range(0.03..0.055);
    let (hw, ht) = (0.5 * rng.random_range(0.016..0.024), 0.5 * rng.random_range(0.007..0.011));
    let plug = rng.random_range(0.011..0.013);
    let bracket_hw = hw * rng.random_range(0.8..1.0);
    let bracket_t = rng.random_range(0.0006..0.001);
    let gap = rng.random_range(0.0015..0.003);
    let loop_r = if rng.random_bool(0.5) { rng.random_range(0.003..0.005) } else { 0.0 };
    let max_swivel = rng.random_range(160.0f32..180.0).to_radians();
    // The pin runs through the centre of the rounded back, so the bracket's round end turns
    // in place over it.
    let pin = hw;
    let mut body = Mesh::union([
        Mesh::cuboid(Point3::new(pin, -ht, -hw), Point3::new(length, ht, hw)),
        Mesh::cylinder(Point3::new(pin, -ht, 0.0), Point3::new(pin, ht, 0.0), hw, 16),
        usb_plug(length, plug),
    ]);
    for side in [-1.0, 1.0] {
        body.append(Mesh::union((0..3).map(|i| {
            let x = pin + (length - pin) * (0.25 + 0.2 * i as Real);
            let z = side * hw;
            Mesh::cuboid(
                Point3::new(x, -0.6 * ht, z - 0.0005),
                Point3::new(x + 0.002, 0.6 * ht, z + 0.0005),
            )
        })));
    }
    if loop_r > 0.0 {
        let ring = Mesh::ring(Point3::origin(), loop_r, 0.0012, 10);
        let pose = Isometry3::new(
            Vector3::new(0.2 * hw - loop_r, 0.0, 0.0),
            Vector3::x() * std::f32::consts::FRAC_PI_2,
        );
        body.append(ring.transformed(&pose));
    }
    let bracket = swivel_bracket(pin, length + plug + gap, ht, bracket_t, bracket_hw);
    let mut object = ArticulatedObject::new("usb_stick", Link { name: "body".into(), mesh: body });
    let joint = Joint::hinge(Point3::new(pin, 0.0, 0.0), Vector3::y(), max_swivel);
    object.attach(0, Link { name: "swivel bracket".into(), mesh: bracket }, joint);
    object
}

/// The swivel bracket: two plates `t` thick on the body's faces (at heights +-`ht`), round
/// around the pin at x = `pin` and `hw` half wide, joined by a bridge at x = `end` beyond the
/// plug. Everything of the body lies closer to the pin than the bridge, so it swings clear.
fn swivel_bracket(pin: Real, end: Real, ht: Real, t: Real, hw: Real) -> Mesh {
    let plates = [(ht, ht + t), (-ht - t, -ht)].into_iter().flat_map(|(lo, hi)| {
        [
            Mesh::cylinder(Point3::new(pin, lo, 0.0), Point3::new(pin, hi, 0.0), hw, 16),
            Mesh::cuboid(Point3::new(pin, lo, -hw), Point3::new(end, hi, hw)),
        ]
    });
    let bridge = Mesh::cuboid(Point3::new(end, -ht - t, -hw), Point3::new(end + t, ht + t, hw));
    Mesh::union(plates.chain([bridge]))
}

/// A USB-A plug `length` long from `x0`: a 12 by 4.5 mm metal shell around a plastic tongue.
fn usb_plug(x0: Real, length: Real) -> Mesh {
    let (hw, ht, w) = (0.006, 0.00225, 0.0003);
    let x1 = x0 + length;
    Mesh::union([
        Mesh::cuboid(Point3::new(x0, ht - w, -hw), Point3::new(x1, ht, hw)),
        Mesh::cuboid(Point3::new(x0, -ht, -hw), Point3::new(x1, -ht + w, hw)),
        Mesh::cuboid(Point3::new(x0, -ht + w, -hw), Point3::new(x1, ht - w, -hw + w)),
        Mesh::cuboid(Point3::new(x0, -ht + w, hw - w), Point3::new(x1, ht - w, hw)),
        Mesh::cuboid(Point3::new(x0, 0.0, -hw + w), Point3::new(x1 - 0.001, ht - w, hw - w)),
    ])
}
