//! Oven (a free-standing range): a body with a cooktop, knobs on a backguard or on a strip
//! above the door, and a glazed door hinged at the bottom that falls open. Some have a rack
//! with a baking tray that slides forward in the cavity (only as far as the shut door: no
//! joint depends on another), or a storage drawer that pulls out under the door.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TEST};
use crate::mesh::Mesh;
use crate::objects::carcass::open_box;
use crate::objects::controls::knob_row;
use crate::objects::drawer::drawer;
use crate::objects::handle::bar_handle;
use crate::objects::joints::drop_hinge;
use crate::objects::panel::framed_panel;
use crate::objects::rack::rack;
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The oven category.
pub const CATEGORY: Category = Category {
    name: "oven",
    description: "range with cooktop and knobs; glazed door revolute about its bottom edge, optionally a prismatic rack or storage drawer",
    splits: TEST,
    build,
};

/// How far the door handle stands off the door, and its radius.
const HANDLE: (Real, Real) = (0.045, 0.012);

/// Four burners of different sizes on the cooktop `y = top` of a body `2 hw` wide and
/// `2 hd` deep.
fn burners(hw: Real, hd: Real, top: Real) -> Mesh {
    Mesh::union([(-1.0, -1.0, 0.09), (1.0, -1.0, 0.07), (-1.0, 1.0, 0.065), (1.0, 1.0, 0.08)].map(
        |(sx, sz, r): (Real, Real, Real)| {
            let c = Point3::new(sx * 0.5 * hw, top, sz * 0.45 * hd);
            Mesh::union([
                Mesh::cylinder(c, c + Vector3::y() * 0.012, r, 12),
                Mesh::cylinder(c, c + Vector3::y() * 0.022, 0.35 * r, 10),
            ])
        },
    ))
}

/// A rack near the cavity floor with a baking tray on it, `depth` deep from the cavity's
/// back `z0`, sliding along +z on ledges fixed to the side walls (returned second).
fn rack_and_ledges((x0, x1): (Real, Real), y: Real, z0: Real, depth: Real) -> (Mesh, Mesh) {
    let z1 = z0 + depth;
    let mut tray = rack((x0, x1), y, (z0, z1), 11, 0.008, 0.0);
    let (tx0, tx1, tz0, tz1) = (x0 + 0.02, x1 - 0.02, z0 + 0.02, z1 - 0.02);
    let (y0, y1) = (y + 0.012, y + 0.06);
    tray.append(Mesh::union([
        Mesh::cuboid(Point3::new(tx0, y + 0.008, tz0), Point3::new(tx1, y0, tz1)),
        Mesh::cuboid(Point3::new(tx0, y0, tz0), Point3::new(tx1, y1, tz0 + 0.004)),
        Mesh::cuboid(Point3::new(tx0, y0, tz1 - 0.004), Point3::new(tx1, y1, tz1)),
        Mesh::cuboid(Point3::new(tx0, y0, tz0), Point3::new(tx0 + 0.004, y1, tz1)),
        Mesh::cuboid(Point3::new(tx1 - 0.004, y0, tz0), Point3::new(tx1, y1, tz1)),
    ]));
    let ledges = Mesh::union(
        [x0, x1 - 0.012]
            .map(|x| Mesh::cuboid(Point3::new(x, y - 0.008, z0), Point3::new(x + 0.012, y, z1))),
    );
    (tray, ledges)
}

fn build(rng: &mut Rng) -> ArticulatedObject {
    let w = rng.random_range(0.5..0.76);
    let h = rng.random_range(0.85..0.95);
    let d = rng.random_range(0.55..0.65);
    let wall = rng.random_range(0.02..0.03);
    let t = rng.random_range(0.04..0.06);
    let extra = rng.random_range(0..3u32);
    let backguard = rng.random_bool(0.5);
    let bottom = rng.random_range(0.14..0.2);
    let knobs = rng.random_range(4..7u32);
    let max_open = rng.random_range(80.0f32..90.0).to_radians();
    let travel = rng.random_range(0.55..0.75);
    let (hw, hd, g) = (0.5 * w, 0.5 * d, 0.004);
    let strip = if backguard { 0.0 } else { 0.1 };
    let (ya, yb) = (bottom, h - strip);
    let mut body = Mesh::union([
        open_box(Point3::new(-hw, 0.0, -hd), Point3::new(hw, h, hd), wall),
        // The cavity's floor, with a drawer compartment or a closed plinth under it.
        Mesh::cuboid(
            Point3::new(-hw + wall, ya - wall, -hd + wall),
            Point3::new(hw - wall, ya, hd),
        ),
        Mesh::cuboid(Point3::new(-hw, h, -hd), Point3::new(hw, h + 0.006, hd)),
        burners(hw, hd, h + 0.006),
    ]);
    if backguard {
        let (top, face) = (h + 0.15, -hd + 0.06);
        body.append(Mesh::cuboid(Point3::new(-hw, h, -hd), Point3::new(hw, top, face)));
        body.append(knob_row((-0.85 * hw, 0.85 * hw), h + 0.08, face, knobs, 0.022));
    } else {
        body.append(Mesh::cuboid(
            Point3::new(-hw + wall, yb - wall, -hd + wall),
            Point3::new(hw - wall, yb, hd),
        ));
        body.append(Mesh::cuboid(Point3::new(-hw, yb + g, hd), Point3::new(hw, h, hd + t)));
        body.append(knob_row((-0.85 * hw, 0.85 * hw), 0.5 * (yb + h), hd + t, knobs, 0.022));
    }
    if extra != 2 {
        body.append(Mesh::cuboid(Point3::new(-hw, 0.0, hd), Point3::new(hw, ya - g, hd + 0.5 * t)));
    }
    // The door: a frame round the window, its handle along the top.
    let door_top = yb - g;
    let mut door =
        framed_panel((-hw, hw), (ya + g, door_top), hd, t, [0.12 * w, 0.12 * w, 0.1, 0.14], 0.008);
    let hy = door_top - 0.06;
    let at = |x: Real| Point3::new(x, hy, hd + t);
    door.append(bar_handle(at(-0.75 * hw), at(0.75 * hw), Vector3::z(), HANDLE.0, HANDLE.1));
    // Falling open, the handle must not dip below the hinge into a pulled-out drawer.
    let safe = (hy - ya).atan2(HANDLE.0 + HANDLE.1);
    let (brackets, hinge) = drop_hinge((-hw, hw), ya + g, hd, t, max_open.min(safe));
    body.append(brackets);
    let mut parts = vec![("door", door, hinge)];
    let (x0, x1) = (-hw + wall, hw - wall);
    if extra == 1 {
        let depth = 0.5 * (d - wall);
        let (tray, ledges) = rack_and_ledges((x0, x1), ya + 0.05, -hd + wall, depth);
        body.append(ledges);
        let slide = Joint::slide(Point3::origin(), Vector3::z(), d - wall - depth - 0.02);
        parts.push(("rack", tray, slide));
    } else if extra == 2 {
        let depth = d - 2.0 * wall;
        let (mesh, slide) =
            drawer((-hw, hw), (wall, ya - wall - g), hd, depth, wall + 0.002, travel * depth);
        parts.push(("drawer", mesh, slide));
    }
    let mut object = ArticulatedObject::new("oven", Link { name: "body".into(), mesh: body });
    for (name, mesh, joint) in parts {
        object.attach(0, Link { name: name.into(), mesh }, joint);
    }
    object
}
