//! Wardrobe: a tall carcass on a plinth with a cornice, a hanging rail and a hat shelf,
//! closed by a pair of panelled doors hinged at its sides, above none, one or two drawers.

use pairs::math::{Point3, Real};
use rand::Rng as _;

use super::catalog::{Category, TRAIN};
use crate::mesh::Mesh;
use crate::objects::carcass::open_box;
use crate::objects::door::{front_door, HingeSide};
use crate::objects::drawer::drawer;
use crate::objects::{ArticulatedObject, Link};
use crate::seed::Rng;

/// The wardrobe category.
pub const CATEGORY: Category = Category {
    name: "wardrobe",
    description: "tall carcass with a hanging rail; two doors revolute about side hinges, zero to two prismatic drawers below",
    splits: TRAIN,
    build,
};

/// Raised panels on a door's front `z = z` over `x`, `y`: one tall panel, or a short one
/// under a tall one.
fn raised_panels((x0, x1): (Real, Real), (y0, y1): (Real, Real), z: Real, count: u32) -> Mesh {
    let m = 0.07;
    let split = if count == 1 { y0 + m } else { y0 + 0.3 * (y1 - y0) };
    let panel = |ya: Real, yb: Real| {
        Mesh::cuboid(Point3::new(x0 + m, ya, z), Point3::new(x1 - m, yb, z + 0.01))
    };
    let mut mesh = panel(split, y1 - m);
    if count > 1 {
        mesh.append(panel(y0 + m, split - m));
    }
    mesh
}

fn build(rng: &mut Rng) -> ArticulatedObject {
    let w = rng.random_range(0.8..1.4);
    let h = rng.random_range(1.7..2.1);
    let d = rng.random_range(0.5..0.62);
    let t = rng.random_range(0.018..0.025);
    let plinth = rng.random_range(0.05..0.1);
    let drawers = rng.random_range(0..3u32);
    let drawer_h = rng.random_range(0.16..0.22);
    let max_open = [rng.random_range(100.0f32..125.0), rng.random_range(100.0f32..125.0)];
    let travel = rng.random_range(0.6..0.8);
    let panels = rng.random_range(1..3u32);
    let (hw, hd, g) = (0.5 * w, 0.5 * d, 0.004);
    let (ix0, ix1) = (-hw + t, hw - t);
    // The doors close the carcass above a shelf (centred here) that tops the drawers.
    let shelf = plinth + t + drawers as Real * drawer_h;
    let mut body = Mesh::union([
        open_box(Point3::new(-hw, plinth, -hd), Point3::new(hw, h, hd), t),
        // The sides run down to the floor either side of a recessed kick board.
        Mesh::cuboid(Point3::new(-hw, 0.0, -hd), Point3::new(-hw + t, plinth, hd)),
        Mesh::cuboid(Point3::new(hw - t, 0.0, -hd), Point3::new(hw, plinth, hd)),
        Mesh::cuboid(Point3::new(ix0, 0.0, hd - 0.04), Point3::new(ix1, plinth, hd - 0.04 + t)),
        Mesh::cuboid(
            Point3::new(-hw - 0.015, h, -hd - 0.015),
            Point3::new(hw + 0.015, h + 0.035, hd + t + 0.015),
        ),
        // Hat shelf and hanging rail.
        Mesh::cuboid(Point3::new(ix0, h - 0.3, -hd + t), Point3::new(ix1, h - 0.3 + t, hd - 0.02)),
        Mesh::cylinder(Point3::new(ix0, h - 0.38, 0.0), Point3::new(ix1, h - 0.38, 0.0), 0.013, 10),
    ]);
    let mut parts = Vec::new();
    for i in 0..drawers {
        let y0 = plinth + t + i as Real * drawer_h;
        // Each drawer runs on a rail across the carcass; the lowest on the bottom panel.
        let rail = if i == 0 { y0 } else { y0 + 0.5 * t };
        if i > 0 {
            body.append(Mesh::cuboid(
                Point3::new(ix0, y0 - 0.5 * t, -hd + t),
                Point3::new(ix1, rail, hd),
            ));
        }
        let (mesh, slide) = drawer(
            (ix0 + g, ix1 - g),
            (rail, y0 + drawer_h - 0.5 * t - g),
            hd - t,
            d - 2.0 * t,
            0.6 * t,
            travel * (d - 2.0 * t),
        );
        parts.push((format!("drawer {i}"), mesh, slide));
    }
    if drawers > 0 {
        body.append(Mesh::cuboid(
            Point3::new(ix0, shelf - 0.5 * t, -hd + t),
            Point3::new(ix1, shelf + 0.5 * t, hd),
        ));
    }
    let y0 = if drawers > 0 { shelf - 0.5 * t + g } else { plinth };
    let (mut left, left_hinge) =
        front_door((-hw, -g), (y0, h), hd, t, HingeSide::Left, max_open[0].to_radians());
    let (mut right, right_hinge) =
        front_door((g, hw), (y0, h), hd, t, HingeSide::Right, max_open[1].to_radians());
    left.append(raised_panels((-hw, -g), (y0, h), hd + t, panels));
    right.append(raised_panels((g, hw), (y0, h), hd + t, panels));
    let mut object =
        ArticulatedObject::new("wardrobe", Link { name: "carcass".into(), mesh: body });
    object.attach(0, Link { name: "left door".into(), mesh: left }, left_hinge);
    object.attach(0, Link { name: "right door".into(), mesh: right }, right_hinge);
    for (name, mesh, slide) in parts {
        object.attach(0, Link { name, mesh }, slide);
    }
    object
}
