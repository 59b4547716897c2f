//! Folding table: a top with an apron, and legs that fold flat under it on hinges. Card
//! tables have four single legs, each folding along its own side; banquet tables have two
//! leg frames, one at each end, folding in towards the middle.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TRAIN};
use crate::mesh::Mesh;
use crate::objects::bracket::bracket_hinge;
use crate::objects::profile::{block, prism, rounded_rect};
use crate::objects::{ArticulatedObject, Link};
use crate::seed::Rng;

/// The folding table category.
pub const CATEGORY: Category = Category {
    name: "folding_table",
    description: "top with apron; four legs or two leg frames revolute about hinges under the \
                  top, folding flat beneath it",
    splits: TRAIN,
    build,
};

/// A square leg of width `w` from `pivot` along `dir` for `length`, with a rubber foot.
fn leg(pivot: Point3, dir: Vector3, length: Real, w: Real) -> Mesh {
    let end = pivot + dir * length;
    Mesh::union([
        Mesh::beam(pivot, end, w, w, Vector3::y()),
        Mesh::cylinder(end - dir * 0.025, end, 0.6 * w, 10),
    ])
}

fn build(rng: &mut Rng) -> ArticulatedObject {
    let card = rng.random_bool(0.5);
    let height = rng.random_range(0.68..0.76);
    let top_t = rng.random_range(0.018..0.03);
    // Card tables have chunky wooden legs, banquet tables steel tube frames.
    let w = if card { rng.random_range(0.05..0.06) } else { rng.random_range(0.032..0.04) };
    let corner = rng.random_range(0.0..0.08);
    let (apron_t, apron_in) = (0.015, 0.01);
    let r = 0.55 * w;
    let underside = height - top_t;
    let pivot_y = underside - 0.01 - r;
    let apron_h = underside - pivot_y + 0.5 * w + 0.005;
    // Legs stand inside the apron; folded, each must stop short of the next hinge.
    let inset = apron_in + apron_t + 0.5 * w + 0.012;
    let len = pivot_y;
    let (half_x, half_z) = if card {
        let side = rng.random_range(0.78..0.92f32).max(len + 2.0 * inset + w + 0.04);
        (0.5 * side, 0.5 * side)
    } else {
        let long = rng.random_range(1.2..1.9f32).max(2.0 * (len + inset + r) + 0.06);
        (0.5 * long, 0.5 * rng.random_range(0.6..0.8))
    };
    let outline = rounded_rect(half_x, half_z, corner, 4);
    let mut top = vec![prism(&outline, (underside, height), |u, v, d| Point3::new(u, d, v))];
    let (ax, az) = (half_x - apron_in, half_z - apron_in);
    let apron_y = (underside - apron_h, underside);
    for s in [-1.0, 1.0] {
        top.push(block(
            Point3::new(-ax, apron_y.0, s * az),
            Point3::new(ax, apron_y.1, s * (az - apron_t)),
        ));
        top.push(block(
            Point3::new(s * ax, apron_y.0, -az + apron_t),
            Point3::new(s * (ax - apron_t), apron_y.1, az - apron_t),
        ));
    }
    let mut moving = Vec::new();
    // Turning about y x fold swings a folded leg down; its brackets hang from the underside.
    let mount = Vector3::y() * (underside - pivot_y);
    let (px, pz) = (half_x - inset, half_z - inset);
    if card {
        // A pinwheel: each corner's leg folds along the side towards the next corner.
        for (cx, cz, fold) in [
            (-1.0, -1.0, Vector3::x()),
            (1.0, -1.0, Vector3::z()),
            (1.0, 1.0, -Vector3::x()),
            (-1.0, 1.0, -Vector3::z()),
        ] {
            let pivot = Point3::new(cx * px, pivot_y, cz * pz);
            let (bracket, knuckle, joint) = bracket_hinge(
                pivot,
                Vector3::y().cross(&fold),
                0.55 * w,
                r,
                mount,
                rng.random_range(88.0f32..95.0).to_radians(),
            );
            top.push(bracket);
            moving.push(("leg", Mesh::union([knuckle, leg(pivot, fold, len, w)]), joint));
        }
    } else {
        let px = half_x - inset - r;
        for s in [-1.0, 1.0] {
            let pivot = Point3::new(s * px, pivot_y, 0.0);
            let fold = -s * Vector3::x();
            let (bracket, knuckle, joint) = bracket_hinge(
                pivot,
                Vector3::y().cross(&fold),
                pz + 0.55 * w,
                r,
                mount,
                rng.random_range(88.0f32..95.0).to_radians(),
            );
            top.push(bracket);
            let at = |z: Real, along: Real| Point3::new(pivot.x + fold.x * along, pivot_y, z);
            let frame = Mesh::union([
                knuckle,
                leg(at(-pz, 0.0), fold, len, w),
                leg(at(pz, 0.0), fold, len, w),
                Mesh::beam(at(-pz, 0.8 * len), at(pz, 0.8 * len), 0.8 * w, 0.6 * w, Vector3::y()),
            ]);
            moving.push(("leg frame", frame, joint));
        }
    }
    let mut object = ArticulatedObject::new(
        "folding_table",
        Link { name: "top".into(), mesh: Mesh::union(top) },
    );
    for (name, mesh, joint) in moving {
        object.attach(0, Link { name: name.into(), mesh }, joint);
    }
    object
}
