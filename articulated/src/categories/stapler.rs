//! Stapler: a base with an anvil near its front and a hinge post at its back; the top arm
//! (a cover over the staple magazine) turns up about the hinge pin. On front-loading
//! staplers the magazine also slides forwards out of the arm.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TEST};
use crate::mesh::Mesh;
use crate::objects::contact::{contact_pads, pad_thickness};
use crate::objects::profile::prism;
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The stapler category.
pub const CATEGORY: Category = Category {
    name: "stapler",
    description: "base with anvil and hinge post; top arm revolute about the back hinge, with \
                  a prismatic magazine on front-loading staplers",
    splits: TEST,
    build,
};

/// A prism across x in `xs` of a side profile given as (z, y) points.
fn side_prism(profile: &[[Real; 2]], xs: (Real, Real)) -> Mesh {
    prism(profile, xs, |z, y, x| Point3::new(x, y, z))
}

fn build(rng: &mut Rng) -> ArticulatedObject {
    let len = rng.random_range(0.13..0.2);
    let w = rng.random_range(0.035..0.05);
    let base_t = rng.random_range(0.006..0.012);
    let post_len = len * rng.random_range(0.15..0.22);
    let r = rng.random_range(0.004..0.007);
    let post_h = r + rng.random_range(0.004..0.01);
    let arm_h = rng.random_range(0.018..0.03);
    let drop = arm_h * rng.random_range(0.1..0.35);
    let separate_magazine = rng.random_bool(0.5);
    let max_open = rng.random_range(50.0f32..70.0).to_radians();
    let (hw, hl) = (0.5 * w, 0.5 * len);
    let cheek = 0.003;
    let aw = hw - cheek;
    let pivot = Point3::new(0.0, base_t + post_h, -hl + 0.5 * post_len);
    let (y0, y1, zf) = (pivot.y - r, pivot.y - r + arm_h, hl - 0.003);
    let anvil = base_t + 0.0012;
    let (pad_base, pad_arm) =
        contact_pads(Point3::new(aw, pivot.y, pivot.z), -Vector3::x(), 0.8 * r);
    let mut base = vec![
        Mesh::cuboid(Point3::new(-hw, 0.0, -hl), Point3::new(hw, base_t, hl - hw)),
        Mesh::cylinder(Point3::new(0.0, 0.0, hl - hw), Point3::new(0.0, base_t, hl - hw), hw, 16),
        Mesh::cuboid(
            Point3::new(-0.3 * hw, base_t, zf - 0.035),
            Point3::new(0.3 * hw, anvil, zf - 0.008),
        ),
        Mesh::cuboid(Point3::new(-aw, base_t, -hl), Point3::new(aw, y0, -hl + post_len)),
        pad_base,
    ];
    for s in [-1.0, 1.0] {
        let (xa, xb) = (s * aw, s * hw);
        base.push(Mesh::cuboid(
            Point3::new(xa.min(xb), base_t, -hl),
            Point3::new(xa.max(xb), pivot.y, -hl + post_len),
        ));
        base.push(Mesh::cylinder(
            Point3::new(xa, pivot.y, pivot.z),
            Point3::new(xb, pivot.y, pivot.z),
            (1.6 * r).min(0.5 * post_len),
            12,
        ));
        base.push(Mesh::cylinder(
            Point3::new(xb, pivot.y, pivot.z),
            Point3::new(xb + s * 0.0008, pivot.y, pivot.z),
            0.4 * r,
            8,
        ));
    }
    // The cover: a top plate sloping down to the front over two side skirts; the skirts
    // start at the pivot so that their lower corners rise, not dip, as the arm opens.
    let tc = 0.0015;
    let ts = 0.0015;
    let z_back = pivot.z - r;
    let mut arm = vec![
        Mesh::cylinder(
            Point3::new(-aw, pivot.y, pivot.z),
            Point3::new(aw, pivot.y, pivot.z),
            r,
            12,
        ),
        side_prism(
            &[[z_back, y1 - tc], [z_back, y1], [zf, y1 - drop], [zf, y1 - drop - tc]],
            (-aw, aw),
        ),
        pad_arm,
    ];
    let skirt = [[pivot.z, y0], [zf, y0], [zf, y1 - drop], [pivot.z, y1]];
    arm.push(side_prism(&skirt, (-aw, -aw + ts)));
    arm.push(side_prism(&skirt, (aw - ts, aw)));
    // The magazine fills the cover; its nose drops towards the anvil.
    let (mx, my) = (aw - ts, y1 - drop - tc);
    let mz = pivot.z + r + 0.001;
    let nose = (y0 - 0.8 * (y0 - anvil - 0.002)).min(y0);
    let magazine = vec![
        Mesh::cuboid(Point3::new(-mx, y0, mz), Point3::new(mx, my, zf)),
        Mesh::cuboid(Point3::new(-mx, nose, zf - 0.008), Point3::new(mx, my, zf)),
    ];
    let mut object =
        ArticulatedObject::new("stapler", Link { name: "base".into(), mesh: Mesh::union(base) });
    if !separate_magazine {
        arm.extend(magazine);
        // Turning about -x lifts the front of the arm.
        object.attach(
            0,
            Link { name: "arm".into(), mesh: Mesh::union(arm) },
            Joint::hinge(pivot, -Vector3::x(), max_open),
        );
        return object;
    }
    // Thin plates where the magazine's side meets the skirt keep the contact query exact.
    let mag_len = zf - mz;
    let travel = mag_len * rng.random_range(0.45..0.65);
    let (ya, yb) = (y0 + 0.2 * (my - y0), y0 + 0.8 * (my - y0));
    let p = pad_thickness(yb - ya);
    arm.push(Mesh::cuboid(Point3::new(mx, ya, mz), Point3::new(mx + p, yb, zf)));
    let mut magazine = magazine;
    magazine.push(Mesh::cuboid(
        Point3::new(mx - p, ya, mz),
        Point3::new(mx, yb, mz + mag_len - travel),
    ));
    let arm_link = object.attach(
        0,
        Link { name: "arm".into(), mesh: Mesh::union(arm) },
        Joint::hinge(pivot, -Vector3::x(), max_open),
    );
    let joint = Joint::slide(Point3::new(0.0, y0, zf), Vector3::z(), travel);
    object.attach(arm_link, Link { name: "magazine".into(), mesh: Mesh::union(magazine) }, joint);
    object
}
