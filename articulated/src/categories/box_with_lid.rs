//! Box with a lid: an open box (shoe box, chest or jewellery box) whose lid swings up about
//! the back edge. Shoe-box lids hang over the walls; chests stand on feet with side handles,
//! hinge knuckles, an optional domed lid and front latch; jewellery boxes have a knob,
//! dividers and sometimes a latch.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TEST};
use crate::mesh::Mesh;
use crate::objects::container::{back_hinge, corner_feet, front_latch, knuckle_hinges, open_box};
use crate::objects::handle::bar_handle;
use crate::objects::{ArticulatedObject, Link};
use crate::seed::Rng;

/// The box_with_lid category.
pub const CATEGORY: Category = Category {
    name: "box_with_lid",
    description:
        "open box (shoe box, chest or jewellery box) with a lid revolute about its back edge",
    splits: TEST,
    build,
};

/// The kinds of box, which set the proportions and the fittings.
#[derive(Clone, Copy, PartialEq)]
enum Style {
    ShoeBox,
    Chest,
    Jewellery,
}

fn build(rng: &mut Rng) -> ArticulatedObject {
    let style = [Style::ShoeBox, Style::Chest, Style::Jewellery][rng.random_range(0..3)];
    let (width, walls) = match style {
        Style::ShoeBox => (rng.random_range(0.28..0.4), (0.003, 0.005)),
        Style::Chest => (rng.random_range(0.55..1.0), (0.015, 0.025)),
        Style::Jewellery => (rng.random_range(0.12..0.26), (0.005, 0.009)),
    };
    let (hw, hd) = (0.5 * width, 0.5 * width * rng.random_range(0.5..0.8));
    let h = width * rng.random_range(0.3..0.6);
    let t = rng.random_range(walls.0..walls.1);
    let lid_t = t * rng.random_range(1.2..2.0);
    let max_open = rng.random_range(100.0f32..115.0).to_radians();
    let domed = style == Style::Chest && rng.random_bool(0.5);
    let latch = style != Style::ShoeBox && rng.random_bool(0.6);
    let feet = if style == Style::ShoeBox { 0.0 } else { h * rng.random_range(0.04..0.1) };
    let mut body = open_box((-hw, hw), (feet, h), (-hd, hd), t);
    // A shoe box's lid folds about its back edge; the others turn on knuckled hinges.
    let mut joint = back_hinge(Point3::new(0.0, h, -hd), max_open);
    let mut lid = match style {
        Style::ShoeBox => shoe_box_lid(hw, hd, h, lid_t, h * rng.random_range(0.2..0.35)),
        _ if domed => domed_lid(hw + t, hd, h, lid_t, hd * rng.random_range(0.3..0.6)),
        _ => Mesh::cuboid(Point3::new(-hw - t, h, -hd), Point3::new(hw + t, h + lid_t, hd + t)),
    };
    if style != Style::ShoeBox {
        body.append(corner_feet(hw - 2.0 * t, hd - 2.0 * t, feet, 1.5 * t));
        let radius = 0.004 * (width + h + 2.0 * hd);
        let centres = [-0.6 * hw, 0.6 * hw];
        let (fixed, moving, knuckled) =
            knuckle_hinges(&centres, 0.2 * hw, (h, -hd), radius, max_open);
        body.append(fixed);
        lid.append(moving);
        joint = knuckled;
    }
    if style == Style::Chest {
        body.append(Mesh::union([-1.0, 1.0].map(|s| {
            let (y, x) = (feet + 0.6 * (h - feet), s * hw);
            let (a, b) = (Point3::new(x, y, -0.25 * hd), Point3::new(x, y, 0.25 * hd));
            bar_handle(a, b, Vector3::x() * s, 0.04, 0.008)
        })));
    }
    if style == Style::Jewellery {
        body.append(Mesh::cuboid(
            Point3::new(-hw + t, feet + t, -0.5 * t),
            Point3::new(hw - t, feet + 0.6 * (h - feet), 0.5 * t),
        ));
        let knob = 0.12 * hd;
        lid.append(Mesh::sphere(Point3::new(0.0, h + lid_t + 0.6 * knob, 0.0), knob, 12));
    }
    if latch {
        let (hasp, catch) = front_latch(0.0, 0.12 * width, h, hd, 0.12 * (h - feet), 0.8 * t);
        lid.append(hasp);
        body.append(catch);
    }
    let mut object =
        ArticulatedObject::new("box_with_lid", Link { name: "box".into(), mesh: body });
    object.attach(0, Link { name: "lid".into(), mesh: lid }, joint);
    object
}

/// A shoe-box lid: a slab whose front and side skirts hang `skirt` down outside the walls.
fn shoe_box_lid(hw: Real, hd: Real, h: Real, t: Real, skirt: Real) -> Mesh {
    let o = t + 0.002;
    let (x0, x1, z1) = (-hw - o, hw + o, hd + o);
    Mesh::union([
        Mesh::cuboid(Point3::new(x0, h, -hd), Point3::new(x1, h + t, z1)),
        Mesh::cuboid(Point3::new(x0, h - skirt, z1 - t), Point3::new(x1, h, z1)),
        Mesh::cuboid(Point3::new(x0, h - skirt, -hd), Point3::new(x0 + t, h, z1 - t)),
        Mesh::cuboid(Point3::new(x1 - t, h - skirt, -hd), Point3::new(x1, h, z1 - t)),
    ])
}

/// A chest's domed lid: one convex hull over a `hw` by `hd` top, `t` thick at its edges and
/// rising `bulge` higher in the middle.
fn domed_lid(hw: Real, hd: Real, h: Real, t: Real, bulge: Real) -> Mesh {
    let points: Vec<Point3> = (0..=8)
        .flat_map(|k| {
            let phi = std::f32::consts::PI * k as Real / 8.0;
            let (y, z) = (h + t + bulge * phi.sin(), -hd * phi.cos());
            [Point3::new(-hw, y, z), Point3::new(hw, y, z)]
        })
        .chain([-hw, hw].into_iter().flat_map(|x| [Point3::new(x, h, -hd), Point3::new(x, h, hd)]))
        .collect();
    Mesh::hull(&points)
}
