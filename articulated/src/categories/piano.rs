//! Piano: an upright (a tall case with a top lid hinged at the back) or a grand (a wing-shaped
//! case on three legs with a lid hinged along its straight side); both have a keyboard whose
//! fallboard folds up against the case.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TRAIN};
use crate::mesh::Mesh;
use crate::objects::container::back_hinge;
use crate::objects::keyboard::{Keyboard, KEYBED_DROP};
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The piano category.
pub const CATEGORY: Category = Category {
    name: "piano",
    description: "upright or grand piano: fallboard revolute over the keys, top lid revolute (back edge or straight side)",
    splits: TRAIN,
    build,
};

fn build(rng: &mut Rng) -> ArticulatedObject {
    let grand = rng.random_bool(0.5);
    let keyboard = Keyboard {
        half: 0.5 * rng.random_range(1.2..1.24),
        keys: rng.random_range(0.7..0.74),
        depth: rng.random_range(0.14..0.16),
        cheek: rng.random_range(0.05..0.1),
    };
    let thickness = rng.random_range(0.012..0.02);
    let fold = rng.random_range(80.0f32..90.0).to_radians();
    let half_w = keyboard.half + keyboard.cheek;
    let (mut case, lid, lid_joint) =
        if grand { grand_case(rng, half_w) } else { upright_case(rng, half_w, keyboard.keys) };
    case.append(keyboard.mesh());
    let mut object = ArticulatedObject::new("piano", Link { name: "case".into(), mesh: case });
    let (board, joint) = keyboard.fallboard(thickness, fold);
    object.attach(0, Link { name: "fallboard".into(), mesh: board }, joint);
    object.attach(0, Link { name: "lid".into(), mesh: lid }, lid_joint);
    object
}

/// An upright's case `half_w` half wide behind z = 0, with toe blocks and columns under a
/// keybed whose keys are at height `keys`, pedals, a music ledge above where the fallboard
/// folds, and its top lid hinged along the back edge.
fn upright_case(rng: &mut Rng, half_w: Real, keys: Real) -> (Mesh, Mesh, Joint) {
    let (h, depth) = (rng.random_range(1.05..1.35), rng.random_range(0.3..0.4));
    let (lid_t, max_lid) =
        (rng.random_range(0.015..0.025), rng.random_range(70.0f32..90.0).to_radians());
    let mut case = Mesh::union([
        Mesh::cuboid(Point3::new(-half_w, 0.0, -depth), Point3::new(half_w, h, 0.0)),
        // The folded fallboard reaches at most 0.24 above the keys.
        Mesh::cuboid(
            Point3::new(-half_w + 0.05, keys + 0.27, 0.0),
            Point3::new(half_w - 0.05, keys + 0.29, 0.03),
        ),
        Mesh::cuboid(
            Point3::new(-half_w - 0.01, h - 0.04, -depth - 0.01),
            Point3::new(half_w + 0.01, h, 0.01),
        ),
    ]);
    for side in [-1.0, 1.0] {
        let x = side * (half_w - 0.04);
        case.append(Mesh::cuboid(
            Point3::new(x - 0.04, 0.0, 0.0),
            Point3::new(x + 0.04, 0.06, 0.2),
        ));
        case.append(Mesh::beam(
            Point3::new(x, 0.06, 0.15),
            Point3::new(x, keys - KEYBED_DROP, 0.15),
            0.05,
            0.05,
            Vector3::z(),
        ));
    }
    case.append(pedals(0.0));
    let lid = Mesh::cuboid(
        Point3::new(-half_w - 0.01, h, -depth - 0.01),
        Point3::new(half_w + 0.01, h + lid_t, 0.02),
    );
    (case, lid, back_hinge(Point3::new(0.0, h, -depth - 0.01), max_lid))
}

/// Three pedals on a block at the floor, centred at z.
fn pedals(z: Real) -> Mesh {
    Mesh::union([-0.06, 0.0, 0.06].map(|x| {
        Mesh::cuboid(Point3::new(x - 0.015, 0.04, z), Point3::new(x + 0.015, 0.055, z + 0.1))
    }))
}

/// A grand's case: a wing-shaped outline `half_w` half wide behind z = 0 (convex pieces with
/// a bend in the curved side), a solid body with a rim around the strings, three legs and a
/// pedal lyre; and its lid hinged along the straight (left) side.
fn grand_case(rng: &mut Rng, half_w: Real) -> (Mesh, Mesh, Joint) {
    let length = rng.random_range(1.5..1.9);
    let (bottom, top) = (rng.random_range(0.6..0.64), rng.random_range(0.95..1.02));
    let (rim, inset) = (rng.random_range(0.03..0.05), rng.random_range(0.04..0.08));
    let (lid_t, max_lid) =
        (rng.random_range(0.015..0.025), rng.random_range(40.0f32..55.0).to_radians());
    let (w, a, bend_z) = (2.0 * half_w, 0.35 * length, -0.7 * length);
    let tail = -half_w + 0.18 * w;
    let outline = [
        (-half_w, 0.0),
        (half_w, 0.0),
        (half_w, -a),
        (0.0, bend_z),
        (tail, -length),
        (-half_w, -length),
    ];
    let pieces: [&[(Real, Real)]; 3] = [
        &[(-half_w, 0.0), (half_w, 0.0), (half_w, -a), (-half_w, -a)],
        &[(-half_w, -a), (half_w, -a), (0.0, bend_z), (-half_w, bend_z)],
        &[(-half_w, bend_z), (0.0, bend_z), (tail, -length), (-half_w, -length)],
    ];
    let prism = |y0: Real, y1: Real| {
        Mesh::union(pieces.iter().map(|p| {
            let points: Vec<Point3> = p
                .iter()
                .flat_map(|&(x, z)| [Point3::new(x, y0, z), Point3::new(x, y1, z)])
                .collect();
            Mesh::hull(&points)
        }))
    };
    let mut case = prism(bottom, top - inset);
    let centre = Point3::new(-0.2 * half_w, 0.0, -0.45 * length);
    for (i, &(x0, z0)) in outline.iter().enumerate() {
        let (x1, z1) = outline[(i + 1) % outline.len()];
        let (p, q) = (Point3::new(x0, 0.0, z0), Point3::new(x1, 0.0, z1));
        // A repeated outline point (none is) has no edge normal: x, flipped inward below.
        let inward = pairs::math::unit_or(&Vector3::y().cross(&(q - p)), Vector3::x());
        let inward = if inward.dot(&(centre - p)) < 0.0 { -inward } else { inward };
        let lift = Vector3::y() * (top - 0.5 * inset) + inward * 0.5 * rim;
        case.append(Mesh::beam(p + lift, q + lift, rim, inset, Vector3::y()));
    }
    for (x, z) in
        [(-half_w + 0.12, -0.15), (half_w - 0.12, -0.15), (-half_w + 0.12, -length + 0.15)]
    {
        case.append(Mesh::frustum(
            Point3::new(x, 0.0, z),
            Point3::new(x, bottom, z),
            0.035,
            0.05,
            10,
        ));
    }
    case.append(Mesh::beam(
        Point3::new(0.0, 0.04, -0.3),
        Point3::new(0.0, bottom, -0.3),
        0.16,
        0.04,
        Vector3::z(),
    ));
    case.append(pedals(-0.28));
    let lid = prism(top, top + lid_t);
    // Turning about +z lifts the curved side up off the rim.
    (case, lid, Joint::hinge(Point3::new(-half_w, top, 0.0), Vector3::z(), max_lid))
}
