//! Dishwasher: a tub on a recessed toe kick with a spray arm, one or two baskets on ledges,
//! and a door with a control strip and handle, hinged at its bottom edge to fall open.
//! Baskets slide forward only as far as the door lets them: no joint depends on another,
//! so a state may have the door shut while a basket is pulled.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TRAIN};
use crate::mesh::Mesh;
use crate::objects::carcass::{cavity, open_box};
use crate::objects::container::corner_feet;
use crate::objects::controls::button;
use crate::objects::handle::bar_handle;
use crate::objects::joints::drop_hinge;
use crate::objects::rack::rack;
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The dishwasher category.
pub const CATEGORY: Category = Category {
    name: "dishwasher",
    description:
        "tub with baskets; door revolute about its bottom edge, one or two baskets prismatic",
    splits: TRAIN,
    build,
};

/// The door, `2 hw` wide over `y0..y1`, `t` thick in front of `z = front`: a panel, a
/// control strip with buttons along its top and a bar handle under it.
fn door(hw: Real, (y0, y1): (Real, Real), front: Real, t: Real, buttons: u32) -> Mesh {
    let z = front + t;
    let mut mesh = Mesh::union([
        Mesh::cuboid(Point3::new(-hw, y0, front), Point3::new(hw, y1, z)),
        Mesh::cuboid(Point3::new(-hw, y1 - 0.07, z), Point3::new(hw, y1, z + 0.004)),
        bar_handle(
            Point3::new(-0.3 * hw, y1 - 0.12, z),
            Point3::new(0.3 * hw, y1 - 0.12, z),
            Vector3::z(),
            0.03,
            0.01,
        ),
    ]);
    for i in 0..buttons {
        let x = 0.3 * hw + 0.1 * hw * i as Real;
        mesh.append(button(x, y1 - 0.035, z + 0.004, (0.035, 0.02), 0.005));
    }
    mesh
}

fn build(rng: &mut Rng) -> ArticulatedObject {
    let w = if rng.random_bool(0.2) { 0.45 } else { rng.random_range(0.57..0.6) };
    let h = rng.random_range(0.82..0.88);
    let d = rng.random_range(0.55..0.62);
    let wall = rng.random_range(0.015..0.02);
    let kick = rng.random_range(0.08..0.11);
    let t = rng.random_range(0.04..0.05);
    let baskets = if rng.random_bool(0.7) { 2 } else { 1 };
    let deep = rng.random_range(0.55..0.65);
    let upper_at = rng.random_range(0.5..0.58);
    let buttons = rng.random_range(3..6u32);
    let max_open = rng.random_range(80.0f32..90.0).to_radians();
    let (hw, hd, g) = (0.5 * w, 0.5 * d, 0.004);
    let (lo, hi) = (Point3::new(-hw, kick, -hd), Point3::new(hw, h, hd));
    let (inner_lo, inner_hi) = cavity(lo, hi, wall);
    let (ix, floor) = ((inner_lo.x, inner_hi.x), inner_lo.y);
    let mut body = Mesh::union([
        open_box(lo, hi, wall),
        Mesh::cuboid(
            Point3::new(-hw + 0.01, 0.0, hd - 0.06),
            Point3::new(hw - 0.01, kick, hd - 0.045),
        ),
        // The spray arm under the lower basket.
        Mesh::cylinder(Point3::new(0.0, floor, 0.0), Point3::new(0.0, floor + 0.03, 0.0), 0.03, 10),
        Mesh::beam(
            Point3::new(-0.35 * (ix.1 - ix.0), floor + 0.02, 0.0),
            Point3::new(0.35 * (ix.1 - ix.0), floor + 0.02, 0.0),
            0.035,
            0.015,
            Vector3::y(),
        ),
    ]);
    let (brackets, hinge) = drop_hinge((-hw, hw), kick + g, hd, t, max_open);
    body.append(Mesh::union([corner_feet(hw - 0.06, hd - 0.06, kick, 0.015), brackets]));
    let mut object = ArticulatedObject::new("dishwasher", Link { name: "tub".into(), mesh: body });
    object.attach(
        0,
        Link { name: "door".into(), mesh: door(hw, (kick + g, h), hd, t, buttons) },
        hinge,
    );
    // Baskets rest at the back of the tub and stop just behind the shut door.
    let depth = deep * (inner_hi.z - inner_lo.z);
    let z0 = inner_lo.z + 0.01;
    let travel = hd - 0.015 - (z0 + depth);
    let tub_h = inner_hi.y - floor;
    let levels = [(floor + 0.04, 0.15), (floor + upper_at * tub_h, 0.09)];
    for (i, &(y, wall_h)) in levels.iter().take(baskets).enumerate() {
        let basket = rack(ix, y, (z0, z0 + depth), 9, 0.008, wall_h);
        let ledges = Mesh::union([ix.0, ix.1 - 0.012].map(|x| {
            Mesh::cuboid(
                Point3::new(x, y - 0.008, inner_lo.z),
                Point3::new(x + 0.012, y, hd - 0.01),
            )
        }));
        object.links[0].mesh.append(ledges);
        let name = if i == 0 { "lower basket" } else { "upper basket" };
        object.attach(
            0,
            Link { name: name.into(), mesh: basket },
            Joint::slide(Point3::origin(), Vector3::z(), travel),
        );
    }
    object
}
