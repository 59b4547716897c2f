//! Sliding window: a frame whose stops and parting bead form two tracks, with two sashes
//! (framed panes) that slide past each other sideways, or a double- or single-hung pair
//! that slides up and down; where only one sash moves the other is fixed in the frame.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TEST};
use crate::mesh::Mesh;
use crate::objects::panel::framed_panel;
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The sliding window category.
pub const CATEGORY: Category = Category {
    name: "sliding_window",
    description:
        "frame with two tracks; one or two sashes prismatic, sliding sideways or up and down",
    splits: TEST,
    build,
};

/// A bead of four bars `b` wide just inside the opening `x`, `y`, over `z`.
fn bead((x0, x1): (Real, Real), (y0, y1): (Real, Real), (z0, z1): (Real, Real), b: Real) -> Mesh {
    Mesh::union([
        Mesh::cuboid(Point3::new(x0, y0, z0), Point3::new(x1, y0 + b, z1)),
        Mesh::cuboid(Point3::new(x0, y1 - b, z0), Point3::new(x1, y1, z1)),
        Mesh::cuboid(Point3::new(x0, y0 + b, z0), Point3::new(x0 + b, y1 - b, z1)),
        Mesh::cuboid(Point3::new(x1 - b, y0 + b, z0), Point3::new(x1, y1 - b, z1)),
    ])
}

/// A sash over `x`, `y`, `z`: a framed pane with a glazing bar across the sliding `axis`
/// (x or y), which shows its motion, and maybe one along it.
fn sash(
    x: (Real, Real),
    y: (Real, Real),
    z: (Real, Real),
    rail: Real,
    bars: u32,
    axis: Vector3,
) -> Mesh {
    let thickness = z.1 - z.0;
    let mut mesh = framed_panel(x, y, z.0, thickness, [rail; 4], 0.006);
    let (xm, ym, zm) = (0.5 * (x.0 + x.1), 0.5 * (y.0 + y.1), 0.5 * (z.0 + z.1));
    let across = (Point3::new(xm, y.0 + rail, zm), Point3::new(xm, y.1 - rail, zm));
    let along = (Point3::new(x.0 + rail, ym, zm), Point3::new(x.1 - rail, ym, zm));
    let (first, second) = if axis.x > 0.5 { (across, along) } else { (along, across) };
    for (a, b) in [first, second].into_iter().take(bars as usize) {
        mesh.append(Mesh::beam(a, b, 0.4 * rail, 0.5 * thickness, Vector3::z()));
    }
    mesh
}

/// A latch on a sash's outer face (`z` facing `out`) at `centre`, long across the sliding
/// `axis`; set in from the meeting edge, it clears the beads when the sash is fully open.
fn latch(centre: Point3, axis: Vector3, out: Real) -> Mesh {
    let across = Vector3::new(axis.y.abs(), axis.x.abs(), 0.0);
    let half = axis.abs() * 0.012 + across * 0.03;
    let (a, b) = (centre - half, centre + half + Vector3::z() * 0.015 * out);
    Mesh::cuboid(Point3::new(a.x, a.y, a.z.min(b.z)), Point3::new(b.x, b.y, a.z.max(b.z)))
}

fn build(rng: &mut Rng) -> ArticulatedObject {
    // Sashes slide along the window's longer side: sideways in wide windows, up and down
    // in tall ones.
    let long = rng.random_range(0.9..1.6);
    let short = long * rng.random_range(0.55..0.95);
    let fw = rng.random_range(0.04..0.07);
    let depth = rng.random_range(0.08..0.12);
    let rail = rng.random_range(0.035..0.055);
    let vertical = rng.random_bool(0.5);
    let (w, h) = if vertical { (short, long) } else { (long, short) };
    let both_move = rng.random_bool(0.6);
    let bars = rng.random_range(1..3u32);
    let split = rng.random_range(0.45..0.55);
    // Where only one sash moves: the lower one of a hung window, else either.
    let move_b = vertical || rng.random_bool(0.5);
    let (hw, hd) = (0.5 * w, 0.5 * depth);
    let (ox, oy) = ((-hw + fw, hw - fw), (fw, h - fw));
    // Tracks: an outer and an inner stop, a parting bead between the two sash planes.
    let (e, b) = (0.12 * depth, 0.012);
    let st = 0.5 * (depth - 3.0 * e);
    let back = (-hd + e, -hd + e + st);
    let front = (hd - e - st, hd - e);
    let mut frame = Mesh::union([
        Mesh::cuboid(Point3::new(-hw, 0.0, -hd), Point3::new(hw, fw, hd + 0.03)),
        Mesh::cuboid(Point3::new(-hw, h - fw, -hd), Point3::new(hw, h, hd)),
        Mesh::cuboid(Point3::new(-hw, fw, -hd), Point3::new(-hw + fw, h - fw, hd)),
        Mesh::cuboid(Point3::new(hw - fw, fw, -hd), Point3::new(hw, h - fw, hd)),
        bead(ox, oy, (-hd, back.0), b),
        bead(ox, oy, (back.1, front.0), b),
        bead(ox, oy, (front.1, hd), b),
    ]);
    let overlap = 0.5 * rail;
    // Sash A runs in the back track, sash B in the front one; they overlap at the middle.
    // Latches sit on the meeting rail or stile, set in from its edge past the beads.
    let inset = b + 0.016;
    let (mut a, mut bs, axis, travel_a, travel_b, meet_a, meet_b) = if vertical {
        let ym = oy.0 + split * (oy.1 - oy.0);
        let (ya, yb) = ((ym - overlap, oy.1), (oy.0, ym + overlap));
        let meet_a = Point3::new(0.0, ya.0 + inset, back.0);
        let meet_b = Point3::new(0.0, yb.1 - inset, front.1);
        let (a, bs) = (
            sash(ox, ya, back, rail, bars, Vector3::y()),
            sash(ox, yb, front, rail, bars, Vector3::y()),
        );
        (a, bs, Vector3::y(), ya.0 - oy.0, oy.1 - yb.1, meet_a, meet_b)
    } else {
        let xm = ox.0 + split * (ox.1 - ox.0);
        let (xa, xb) = ((ox.0, xm + overlap), (xm - overlap, ox.1));
        let ym = 0.5 * (oy.0 + oy.1);
        let meet_a = Point3::new(xa.1 - inset, ym, back.0);
        let meet_b = Point3::new(xb.0 + inset, ym, front.1);
        let (a, bs) = (
            sash(xa, oy, back, rail, bars, Vector3::x()),
            sash(xb, oy, front, rail, bars, Vector3::x()),
        );
        (a, bs, Vector3::x(), ox.1 - xa.1, xb.0 - ox.0, meet_a, meet_b)
    };
    a.append(latch(meet_a, axis, -1.0));
    bs.append(latch(meet_b, axis, 1.0));
    // Sash A is the upper one of a hung window and slides down, or the left one of a
    // sideways window and slides right; sash B slides the other way.
    let axis_a = if vertical { -axis } else { axis };
    let axis_b = -axis_a;
    let sashes = if both_move {
        vec![
            ("sash a", a, Joint::slide(Point3::origin(), axis_a, travel_a)),
            ("sash b", bs, Joint::slide(Point3::origin(), axis_b, travel_b)),
        ]
    } else {
        let (fixed, moving, joint) = if move_b {
            (a, bs, Joint::slide(Point3::origin(), axis_b, travel_b))
        } else {
            (bs, a, Joint::slide(Point3::origin(), axis_a, travel_a))
        };
        frame.append(fixed);
        vec![("sash", moving, joint)]
    };
    let mut object =
        ArticulatedObject::new("sliding_window", Link { name: "frame".into(), mesh: frame });
    for (name, mesh, joint) in sashes {
        object.attach(0, Link { name: name.into(), mesh }, joint);
    }
    object
}
