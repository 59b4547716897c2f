//! Flip phone: a bottom half with a keypad and hinge knuckles at its sides; a top half with
//! a screen on its inner face and a hinge barrel between the knuckles, opening about the
//! hinge from closed (lying on the keypad) to nearly flat behind the bottom half.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TEST};
use crate::mesh::Mesh;
use crate::objects::contact::contact_pads;
use crate::objects::profile::{prism, rounded_rect};
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The flip phone category.
pub const CATEGORY: Category = Category {
    name: "flip_phone",
    description: "bottom half with keypad; top half with screen, revolute about the hinge barrel",
    splits: TEST,
    build,
};

/// Outline in (x, z) of a half from the hinge at `z0` to its rounded far end at `z1`.
fn half_outline(half_w: Real, z0: Real, z1: Real, corner: Real) -> Vec<[Real; 2]> {
    let half_l = 0.5 * (z1 - z0);
    let mut outline: Vec<[Real; 2]> = rounded_rect(half_w, half_l, corner, 3)
        .into_iter()
        .filter(|p| p[1] > 0.0)
        .map(|[u, v]| [u, v + z0 + half_l])
        .collect();
    outline.extend([[-half_w, z0], [half_w, z0]]);
    outline
}

/// A key: a small box standing `height` proud of the face at y = `y`.
fn key(x: Real, z: Real, size: (Real, Real), y: Real, height: Real) -> Mesh {
    let (hx, hz) = (0.5 * size.0, 0.5 * size.1);
    Mesh::cuboid(Point3::new(x - hx, y, z - hz), Point3::new(x + hx, y + height, z + hz))
}

/// The keypad on the face y = `y` over z in `span`: navigation keys nearest the hinge, then
/// `rows` rows of three digit keys.
fn keypad(half_w: Real, span: (Real, Real), y: Real, rows: usize) -> Mesh {
    let key_h = 0.0006;
    let nav = span.0 + 0.16 * (span.1 - span.0);
    let nav_r = 0.35 * half_w;
    let mut keys = vec![
        Mesh::cylinder(Point3::new(0.0, y, nav), Point3::new(0.0, y + key_h, nav), nav_r, 12),
        key(-0.7 * half_w, nav, (0.4 * half_w, 0.5 * nav_r), y, key_h),
        key(0.7 * half_w, nav, (0.4 * half_w, 0.5 * nav_r), y, key_h),
    ];
    let start = nav + 1.4 * nav_r;
    let pitch = (span.1 - start) / rows as Real;
    for r in 0..rows {
        for c in [-1.0, 0.0, 1.0] {
            let z = start + (r as Real + 0.5) * pitch;
            keys.push(key(c * 0.62 * half_w, z, (0.5 * half_w, 0.65 * pitch), y, key_h));
        }
    }
    Mesh::union(keys)
}

fn build(rng: &mut Rng) -> ArticulatedObject {
    let w = rng.random_range(0.045..0.055);
    let len = rng.random_range(0.085..0.105);
    let t1 = rng.random_range(0.009..0.013);
    let t2 = rng.random_range(0.006..0.01);
    let corner = w * rng.random_range(0.1..0.3);
    let rows = if rng.random_bool(0.5) { 4 } else { 5 };
    let knuckle = w * rng.random_range(0.12..0.18);
    let outer_display = rng.random_bool(0.7);
    let max_open = rng.random_range(150.0f32..170.0).to_radians();
    let (hw, hl) = (0.5 * w, 0.5 * len);
    // The halves close with a gap that clears the keys; the hinge axis lies in that gap.
    let gap = 0.0012;
    let r = 0.7 * t1;
    let pivot = Point3::new(0.0, t1 + 0.5 * gap, -hl + r);
    let z_h = -hl + 2.0 * r;
    let outline = half_outline(hw, z_h, hl, corner);
    let plane = |u: Real, v: Real, d: Real| Point3::new(u, d, v);
    let inner = hw - knuckle;
    let knuckles = [-1.0, 1.0].map(|s| {
        Mesh::union([
            Mesh::cuboid(Point3::new(s * inner, 0.0, -hl), Point3::new(s * hw, pivot.y, z_h)),
            Mesh::cylinder(
                Point3::new(s * inner, pivot.y, pivot.z),
                Point3::new(s * hw, pivot.y, pivot.z),
                r,
                12,
            ),
        ])
    });
    let (pad_bottom, pad_top) =
        contact_pads(Point3::new(inner, pivot.y, pivot.z), -Vector3::x(), 0.8 * r);
    let bottom = Mesh::union([
        prism(&outline, (0.0, t1), plane),
        Mesh::cuboid(Point3::new(-inner, 0.0, -hl), Point3::new(inner, pivot.y - r, z_h)),
        Mesh::union(knuckles),
        keypad(hw, (z_h, hl - 0.08 * len), t1, rows),
        pad_bottom,
    ]);
    let y_in = t1 + gap;
    let mut top = vec![
        prism(&outline, (y_in, y_in + t2), plane),
        Mesh::cylinder(
            Point3::new(-inner, pivot.y, pivot.z),
            Point3::new(inner, pivot.y, pivot.z),
            r,
            12,
        ),
        // Screen and earpiece on the inner face, proud of it by less than the keys' clearance.
        Mesh::cuboid(
            Point3::new(-0.8 * hw, y_in - 0.0003, z_h + 0.1 * len),
            Point3::new(0.8 * hw, y_in, hl - 0.18 * len),
        ),
        Mesh::cuboid(
            Point3::new(-0.25 * hw, y_in - 0.0003, hl - 0.12 * len),
            Point3::new(0.25 * hw, y_in, hl - 0.09 * len),
        ),
        pad_top,
    ];
    let y_out = y_in + t2;
    let lens = Point3::new(0.0, y_out, z_h + 0.15 * len);
    top.push(Mesh::cylinder(lens, lens + Vector3::y() * 0.0012, 0.12 * hw, 10));
    if outer_display {
        top.push(Mesh::cuboid(
            Point3::new(-0.5 * hw, y_out, z_h + 0.3 * len),
            Point3::new(0.5 * hw, y_out + 0.0004, z_h + 0.55 * len),
        ));
    }
    let mut object =
        ArticulatedObject::new("flip_phone", Link { name: "bottom half".into(), mesh: bottom });
    // Turning about -x lifts the far end of the top half up and over the hinge.
    let joint = Joint::hinge(pivot, -Vector3::x(), max_open);
    object.attach(0, Link { name: "top half".into(), mesh: Mesh::union(top) }, joint);
    object
}
