//! Folding knife: a handle of two side scales with a slot between them, closed at the back
//! by a spacer; the blade turns about the pivot from closed (edge inside the slot) through
//! the open side of the slot to straight ahead. Pen knives carry a second, small blade at
//! the butt, in a slot of its own above a centre liner.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TEST};
use crate::mesh::Mesh;
use crate::objects::contact::contact_pads;
use crate::objects::profile::prism;
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The folding knife category.
pub const CATEGORY: Category = Category {
    name: "folding_knife",
    description: "handle of two scales around a slot; the blade is revolute about the pivot, \
                  folding into the slot; pen knives add a small blade at the butt",
    splits: TEST,
    build,
};

/// A blade lying in the slot at height `y` (its mid-plane), turning about (`pivot_x`, 0),
/// closed along `dir` (-1 or +1 in x) with its spine at z = `spine`; `tip` is the tip's
/// height above the edge as a fraction of the blade's width (0: sheepsfoot, 1: spear).
struct Blade {
    pivot_x: Real,
    dir: Real,
    y: Real,
    length: Real,
    width: Real,
    thickness: Real,
    spine: Real,
    tip: Real,
    /// Where the spine starts to drop to the tip, as a fraction of the length.
    drop: Real,
}

impl Blade {
    fn mesh(&self, tang: Real, flipper: Option<Real>) -> Mesh {
        let b = self;
        let place = |u: Real, v: Real, d: Real| Point3::new(b.pivot_x + b.dir * u, b.y + d, v);
        let (half, edge) = (0.5 * b.thickness, b.spine - b.width);
        // Spine and tip keep the full thickness; the edge is ground thin.
        let body: Vec<Point3> = [
            (0.3 * tang, b.spine, 1.0),
            (b.drop * b.length, b.spine, 1.0),
            (b.length, edge + b.tip * b.width, 0.6),
            (0.94 * b.length, edge + 0.3 * b.tip * b.width, 0.2),
            (0.75 * b.length, edge, 0.2),
            (0.3 * tang, edge, 0.2),
        ]
        .iter()
        .flat_map(|&(u, v, f)| [place(u, v, -f * half), place(u, v, f * half)])
        .collect();
        let mut parts = vec![
            Mesh::hull(&body),
            Mesh::cylinder(place(0.0, 0.0, -half), place(0.0, 0.0, half), tang, 12),
        ];
        // A flipper tab behind the pivot sticks out of the handle's open side when closed.
        if let Some(reach) = flipper {
            let tab = [(0.0, 0.5 * tang), (-0.7 * tang, 0.5 * tang), (-0.35 * tang, reach)];
            parts.push(prism(&tab.map(|(u, v)| [u, v]), (-half, half), place));
        }
        Mesh::union(parts)
    }
}

/// Outline of a scale in (x, z): round about the pivot at the front; at the butt, round
/// about the pen blade's pivot or squared with cut corners.
fn scale_outline(length: Real, half_w: Real, round_butt: bool) -> Vec<[Real; 2]> {
    let arc = |cx: Real, from: Real| {
        (0..=6).map(move |i| {
            let a = (from + 30.0 * i as Real).to_radians();
            [cx + half_w * a.cos(), half_w * a.sin()]
        })
    };
    let mut outline: Vec<[Real; 2]> = arc(0.0, -90.0).collect();
    if round_butt {
        outline.extend(arc(-length + half_w, 90.0));
    } else {
        let c = 0.3 * half_w;
        outline.extend([
            [-length + c, half_w],
            [-length, half_w - c],
            [-length, -half_w + c],
            [-length + c, -half_w],
        ]);
    }
    outline
}

fn build(rng: &mut Rng) -> ArticulatedObject {
    let length = rng.random_range(0.08..0.13);
    let width = length * rng.random_range(0.2..0.27);
    let scale_t = rng.random_range(0.0025..0.0045);
    let blade_t = rng.random_range(0.0022..0.0035);
    let pen = rng.random_bool(0.35);
    let flipper = !pen && rng.random_bool(0.5);
    let hw = 0.5 * width;
    let spacer = 0.15 * width;
    let main = Blade {
        pivot_x: 0.0,
        dir: -1.0,
        y: 0.0,
        length: length * rng.random_range(0.72..0.85),
        width: width * rng.random_range(0.6..0.72),
        thickness: blade_t,
        spine: 0.45 * width,
        tip: rng.random_range(0.0..0.7),
        drop: rng.random_range(0.5..0.8),
    };
    let max_open = rng.random_range(165.0f32..180.0).to_radians();
    let y0 = -0.5 * blade_t;
    let liner = 0.0012;
    let pen_blade = pen.then(|| Blade {
        pivot_x: -length + hw,
        dir: 1.0,
        y: 0.5 * blade_t + liner + 0.4 * blade_t,
        length: length * rng.random_range(0.4..0.5),
        width: width * rng.random_range(0.45..0.55),
        thickness: 0.8 * blade_t,
        spine: 0.45 * width,
        tip: rng.random_range(0.2..0.6),
        drop: rng.random_range(0.5..0.7),
    });
    let top_of_slots = pen_blade.as_ref().map_or(-y0, |b| b.y + 0.5 * b.thickness);
    let outline = scale_outline(length, hw, pen);
    let plane = |u: Real, v: Real, d: Real| Point3::new(u, d, v);
    let slot_spacer = |x0: Real, x1: Real, ys: (Real, Real)| {
        Mesh::cuboid(Point3::new(x0, ys.0, -hw), Point3::new(x1, ys.1, -hw + spacer))
    };
    let mut handle = vec![
        prism(&outline, (y0 - scale_t, y0), plane),
        prism(&outline, (top_of_slots, top_of_slots + scale_t), plane),
        slot_spacer(-length + if pen { hw } else { 0.003 }, -0.45 * length, (y0, -y0)),
    ];
    let screw = |x: Real| {
        [(y0 - scale_t, -1.0), (top_of_slots + scale_t, 1.0)].map(|(y, s)| {
            Mesh::cylinder(
                Point3::new(x, y, 0.0),
                Point3::new(x, y + s * 0.0008, 0.0),
                0.22 * width,
                10,
            )
        })
    };
    handle.extend(screw(0.0));
    handle.extend(screw(-length + hw));
    let tang = 0.4 * width;
    let (pad_h, pad_b) = contact_pads(Point3::new(0.0, -y0, 0.0), -Vector3::y(), 0.7 * tang);
    handle.push(pad_h);
    let blade = Mesh::union([main.mesh(tang, flipper.then_some(hw + 0.006)), pad_b]);
    let mut pen_link = None;
    if let Some(b) = &pen_blade {
        let ys = (-y0 + liner, top_of_slots);
        handle.push(prism(&outline, (-y0, ys.0), plane));
        handle.push(slot_spacer(-0.5 * length, -0.05 * length, ys));
        let pivot = Point3::new(b.pivot_x, ys.0, 0.0);
        let (pad_l, pad_p) = contact_pads(pivot, Vector3::y(), 0.7 * tang);
        handle.push(pad_l);
        let joint =
            Joint::hinge(pivot, -Vector3::y(), rng.random_range(165.0f32..180.0).to_radians());
        pen_link = Some((Mesh::union([b.mesh(tang, None), pad_p]), joint));
    }
    let mut object = ArticulatedObject::new(
        "folding_knife",
        Link { name: "handle".into(), mesh: Mesh::union(handle) },
    );
    // Turning about +y swings the tip out through the open (+z) side of the slot.
    let pivot = Joint::hinge(Point3::origin(), Vector3::y(), max_open);
    object.attach(0, Link { name: "blade".into(), mesh: blade }, pivot);
    if let Some((mesh, joint)) = pen_link {
        object.attach(0, Link { name: "pen blade".into(), mesh }, joint);
    }
    object
}
