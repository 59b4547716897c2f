//! Pliers: two halves riveted together in a lap joint, each a short thick jaw on one side
//! of the pivot and a long curved, sleeved handle on the other; one half turns about the
//! rivet, opening the jaws as the handles spread.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TEST};
use crate::mesh::Mesh;
use crate::objects::contact::contact_pads;
use crate::objects::profile::prism;
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The pliers category.
pub const CATEGORY: Category = Category {
    name: "pliers",
    description: "two jaw-and-handle halves crossing at a rivet; one half is revolute about it",
    splits: TEST,
    build,
};

/// Proportions shared by both halves, in metres and radians.
struct Shape {
    /// Radius of the lap-joint disc around the rivet.
    disc: Real,
    /// Half the thickness of a half (the disc of each half is this thick).
    half_t: Real,
    jaw_len: Real,
    jaw_root: Real,
    jaw_tip: Real,
    handle_len: Real,
    handle_w: Real,
    /// Handle direction at the rivet and at the end, below the jaw line.
    spread: (Real, Real),
    /// Fraction of the handle covered by the grip sleeve.
    sleeve: Real,
}

/// One half in the xy plane, its jaw on the `s` side of y = 0 (+1 or -1) and its handle on
/// the other; its lap-joint disc fills z in `layer`, the rest the full thickness.
fn half(k: &Shape, s: Real, layer: (Real, Real)) -> Mesh {
    let t = k.half_t;
    let p = |x: Real, y: Real, z: Real| Point3::new(x, s * y, z);
    // The jaw starts on the disc's rim, so that turning keeps it clear of the other disc.
    let root: Vec<(Real, Real)> = [0.0f32, 25.0, 50.0]
        .iter()
        .map(|a| (k.disc * a.to_radians().cos(), k.disc * a.to_radians().sin()))
        .collect();
    let (x1, x2) = (k.disc + 0.45 * k.jaw_len, k.disc + k.jaw_len);
    let mut jaw: Vec<Point3> = root.iter().flat_map(|&(x, y)| [p(x, y, -t), p(x, y, t)]).collect();
    jaw.extend(
        [(x1, k.jaw_root, 1.0), (x2, k.jaw_tip, 0.6), (x2, 0.0, 0.6)]
            .iter()
            .flat_map(|&(x, y, f)| [p(x, y, -f * t), p(x, y, f * t)]),
    );
    let mut parts = vec![Mesh::hull(&jaw)];
    let outer = if layer.0 < 0.0 { -t } else { t };
    parts.push(Mesh::cylinder(
        Point3::new(0.0, 0.0, outer),
        Point3::new(0.0, 0.0, outer * 1.2),
        0.45 * k.disc,
        10,
    ));
    // The handle's neck stays in the lap layer, one piece with the disc, until it is clear
    // of the other half's handle; from there on the handle has the full thickness.
    let dir = |a: Real| Vector3::new(-a.cos(), -a.sin(), 0.0);
    let neck = 0.6 * k.handle_w / k.spread.0.sin();
    let mut at = Point3::origin() + dir(k.spread.0) * neck;
    let side = dir(k.spread.0).cross(&Vector3::z()) * 0.5 * k.handle_w;
    let mut lap: Vec<[Real; 2]> = (0..16)
        .map(|i| {
            let a = i as Real * std::f32::consts::TAU / 16.0;
            [k.disc * a.cos(), k.disc * a.sin()]
        })
        .collect();
    lap.extend([at + side, at - side].map(|v| [v.x, v.y]));
    parts.push(prism(&lap, layer, p));
    let n = 5;
    let step = (k.handle_len - neck) / n as Real;
    for i in 0..n {
        let f = i as Real / (n - 1) as Real;
        let d = dir(k.spread.0 + (k.spread.1 - k.spread.0) * f);
        let (a, b) = (at - d * 0.3 * k.handle_w, at + d * (step + 0.3 * k.handle_w));
        let (a, b) = (p(a.x, a.y, 0.0), p(b.x, b.y, 0.0));
        parts.push(Mesh::beam(a, b, k.handle_w, 2.0 * t, Vector3::z()));
        if f >= 1.0 - k.sleeve {
            parts.push(Mesh::beam(a, b, 1.4 * k.handle_w, 2.6 * t, Vector3::z()));
        }
        at += d * step;
    }
    parts.push(Mesh::sphere(p(at.x, at.y, 0.0), 0.75 * k.handle_w, 12));
    Mesh::union(parts)
}

fn build(rng: &mut Rng) -> ArticulatedObject {
    let length = rng.random_range(0.15..0.24);
    let needle = rng.random_bool(0.35);
    let disc = length * rng.random_range(0.055..0.07);
    let jaw_len =
        length * if needle { rng.random_range(0.32..0.42) } else { rng.random_range(0.2..0.28) };
    let jaw_tip =
        disc * if needle { rng.random_range(0.15..0.3) } else { rng.random_range(0.45..0.7) };
    let shape = Shape {
        disc,
        half_t: length * rng.random_range(0.022..0.03),
        jaw_len,
        jaw_root: disc * rng.random_range(0.9..1.2),
        jaw_tip,
        handle_len: length - jaw_len - disc,
        handle_w: disc * rng.random_range(0.7..0.9),
        spread: (
            rng.random_range(11.0f32..16.0).to_radians(),
            rng.random_range(2.0f32..6.0).to_radians(),
        ),
        sleeve: rng.random_range(0.5..0.75),
    };
    let max_open = rng.random_range(28.0f32..40.0).to_radians();
    let t = shape.half_t;
    let (pad_fixed, pad_moving) = contact_pads(Point3::origin(), Vector3::z(), 0.8 * shape.disc);
    let fixed = Mesh::union([half(&shape, -1.0, (-t, 0.0)), pad_fixed]);
    let moving = Mesh::union([half(&shape, 1.0, (0.0, t)), pad_moving]);
    let mut object =
        ArticulatedObject::new("pliers", Link { name: "fixed half".into(), mesh: fixed });
    // Turning about +z lifts the upper jaw off the lower one and spreads the handles.
    object.attach(
        0,
        Link { name: "moving half".into(), mesh: moving },
        Joint::hinge(Point3::origin(), Vector3::z(), max_open),
    );
    object
}
