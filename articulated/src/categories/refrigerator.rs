//! Refrigerator: a tall insulated cabinet with glass shelves, closed by one door, by a
//! freezer door stacked above or below the fridge door, or by a side-by-side pair. Doors
//! carry bins on their backs and a bar handle, and swing open about vertical hinges.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TEST};
use crate::mesh::Mesh;
use crate::objects::carcass::open_box;
use crate::objects::container::corner_feet;
use crate::objects::door::HingeSide;
use crate::objects::handle::bar_handle;
use crate::objects::joints::vertical_hinge;
use crate::objects::{ArticulatedObject, Link};
use crate::seed::Rng;

/// The refrigerator category.
pub const CATEGORY: Category = Category {
    name: "refrigerator",
    description: "tall cabinet with shelves; one door, stacked freezer and fridge doors or a side-by-side pair, revolute about vertical hinges",
    splits: TEST,
    build,
};

/// How deep door bins reach into the cabinet; shelves stop short of them.
const BIN_DEPTH: Real = 0.09;
/// Clearance between what a door carries and the cabinet's walls.
const MARGIN: Real = 0.02;

/// One door and the compartment behind it.
struct Opening {
    /// Door outline along x and y.
    x: (Real, Real),
    y: (Real, Real),
    /// Compartment interior along x and y, between walls and dividers.
    inner_x: (Real, Real),
    inner_y: (Real, Real),
    /// Where the door's hinge is.
    side: HingeSide,
    /// Handle span as fractions of the door's height: towards the neighbouring door.
    handle: (Real, Real),
    /// Glass shelves in the compartment.
    shelves: u32,
}

/// A door in front of `z = front` with bins on its back and a handle by its free edge.
fn door(o: &Opening, front: Real, thickness: Real) -> Mesh {
    let (x0, x1) = o.x;
    let (y0, y1) = o.y;
    let mut mesh = Mesh::cuboid(Point3::new(x0, y0, front), Point3::new(x1, y1, front + thickness));
    let (bx0, bx1) = (o.inner_x.0 + MARGIN, o.inner_x.1 - MARGIN);
    let bins = ((o.inner_y.1 - o.inner_y.0) / 0.35).round().max(1.0) as u32;
    for i in 0..bins {
        let yb = o.inner_y.0 + MARGIN + i as Real * (o.inner_y.1 - o.inner_y.0) / bins as Real;
        let zb = front - BIN_DEPTH;
        mesh.append(Mesh::cuboid(Point3::new(bx0, yb, zb), Point3::new(bx1, yb + 0.01, front)));
        mesh.append(Mesh::cuboid(
            Point3::new(bx0, yb, zb),
            Point3::new(bx1, yb + 0.07, zb + 0.008),
        ));
    }
    let width = x1 - x0;
    let hx = match o.side {
        HingeSide::Left => x1 - 0.08 * width.min(0.6),
        HingeSide::Right => x0 + 0.08 * width.min(0.6),
    };
    let at = |f: Real| Point3::new(hx, y0 + f * (y1 - y0), front + thickness);
    mesh.append(bar_handle(at(o.handle.0), at(o.handle.1), Vector3::z(), 0.05, 0.013));
    mesh
}

/// Glass shelves across a compartment, stopping short of the door bins.
fn shelves(o: &Opening, back: Real, front: Real) -> Mesh {
    let step = (o.inner_y.1 - o.inner_y.0) / (o.shelves + 1) as Real;
    Mesh::union((1..=o.shelves).map(|i| {
        let y = o.inner_y.0 + i as Real * step;
        Mesh::cuboid(
            Point3::new(o.inner_x.0, y, back),
            Point3::new(o.inner_x.1, y + 0.006, front - BIN_DEPTH - MARGIN),
        )
    }))
}

fn build(rng: &mut Rng) -> ArticulatedObject {
    let layout = rng.random_range(0..4u32);
    let w = rng.random_range(0.6..0.8) + if layout == 3 { 0.15 } else { 0.0 };
    let h = rng.random_range(1.5..1.9);
    let d = rng.random_range(0.6..0.75);
    let wall = rng.random_range(0.035..0.05);
    let t = rng.random_range(0.05..0.07);
    let foot = rng.random_range(0.02..0.05);
    let split = rng.random_range(0.28..0.38);
    let side = if rng.random_bool(0.5) { HingeSide::Left } else { HingeSide::Right };
    let main_shelves = rng.random_range(1..4u32);
    let max_open = [rng.random_range(100.0f32..125.0), rng.random_range(100.0f32..125.0)];
    let (hw, hd, g) = (0.5 * w, 0.5 * d, 0.003);
    let (ix, iy) = ((-hw + wall, hw - wall), (foot + wall, h - wall));
    let opening = |x, y, inner_x, inner_y, side, handle, shelves| Opening {
        x,
        y,
        inner_x,
        inner_y,
        side,
        handle,
        shelves,
    };
    let mut body = open_box(Point3::new(-hw, foot, -hd), Point3::new(hw, h, hd), wall);
    let openings = if layout == 3 {
        let xs = -hw + w * (split + 0.12);
        body.append(Mesh::cuboid(
            Point3::new(xs - 0.5 * wall, iy.0, -hd + wall),
            Point3::new(xs + 0.5 * wall, iy.1, hd),
        ));
        vec![
            opening(
                (-hw, xs - g),
                (foot, h),
                (ix.0, xs - 0.5 * wall),
                iy,
                HingeSide::Left,
                (0.3, 0.7),
                3,
            ),
            opening(
                (xs + g, hw),
                (foot, h),
                (xs + 0.5 * wall, ix.1),
                iy,
                HingeSide::Right,
                (0.3, 0.7),
                main_shelves,
            ),
        ]
    } else if layout == 0 {
        vec![opening((-hw, hw), (foot, h), ix, iy, side, (0.45, 0.8), main_shelves + 1)]
    } else {
        // The freezer takes `split` of the height, on top (layout 1) or at the bottom.
        let ys = if layout == 1 { h - split * (h - foot) } else { foot + split * (h - foot) };
        body.append(Mesh::cuboid(
            Point3::new(ix.0, ys - 0.5 * wall, -hd + wall),
            Point3::new(ix.1, ys + 0.5 * wall, hd),
        ));
        let (upper_shelves, lower_shelves) =
            if layout == 1 { (1, main_shelves) } else { (main_shelves, 1) };
        vec![
            opening(
                (-hw, hw),
                (ys + g, h),
                ix,
                (ys + 0.5 * wall, iy.1),
                side,
                (0.08, 0.45),
                upper_shelves,
            ),
            opening(
                (-hw, hw),
                (foot, ys - g),
                ix,
                (iy.0, ys - 0.5 * wall),
                side,
                (0.6, 0.92),
                lower_shelves,
            ),
        ]
    };
    for o in &openings {
        body.append(shelves(o, -hd + wall, hd));
    }
    body.append(corner_feet(hw - 0.05, hd - 0.05, foot, 0.025));
    let mut object =
        ArticulatedObject::new("refrigerator", Link { name: "cabinet".into(), mesh: body });
    for (i, o) in openings.iter().enumerate() {
        let hinge_x = if o.side == HingeSide::Left { o.x.0 } else { o.x.1 };
        let joint =
            vertical_hinge(Point3::new(hinge_x, o.y.0, hd), o.side, max_open[i].to_radians());
        let name = match (openings.len(), layout, i) {
            (1, _, _) => "door",
            (_, 3, 0) => "left door",
            (_, 3, _) => "right door",
            (_, _, 0) => "upper door",
            _ => "lower door",
        };
        object.attach(0, Link { name: name.into(), mesh: door(o, hd, t) }, joint);
    }
    object
}
