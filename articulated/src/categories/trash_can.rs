//! Trash can: a pedal bin, round or square, raised on feet, with a lid hinged at the back
//! that swings up; most have a foot pedal, a lever under the bin turning about its back end.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TEST};
use crate::mesh::Mesh;
use crate::objects::container::{back_hinge, box_walls, corner_feet};
use crate::objects::shell::{oval_frustum, oval_wall};
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The trash_can category.
pub const CATEGORY: Category = Category {
    name: "trash_can",
    description: "round or square pedal bin: lid revolute about the back edge, optional foot pedal revolute under the front",
    splits: TEST,
    build,
};

/// Fewest share of the surface a pedal must have to be sampled well; smaller ones are left
/// out.
const MIN_PEDAL_SHARE: Real = 0.05;

fn build(rng: &mut Rng) -> ArticulatedObject {
    let round = rng.random_bool(0.6);
    let r = rng.random_range(0.1..0.17);
    let h = rng.random_range(0.28..0.65);
    let feet = rng.random_range(0.08..0.11);
    let recess = (h - feet) * rng.random_range(0.15..0.3);
    let wall = rng.random_range(0.006..0.012);
    let lid_t = rng.random_range(0.02..0.04);
    let overhang = rng.random_range(0.004..0.01);
    let max_lid = rng.random_range(70.0f32..85.0).to_radians();
    let max_press = rng.random_range(12.0f32..18.0).to_radians();
    let pedal_width = 2.0 * r * rng.random_range(0.5..0.8);
    let pedal_length = rng.random_range(0.06..0.1);
    let with_pedal = rng.random_bool(0.8);
    let rb = r * if round { rng.random_range(0.85..0.95) } else { 1.0 };
    let liner = h - recess;
    let radius_at = |y: Real| rb + (r - rb) * (y - feet) / (h - feet);
    let mut body = if round {
        let (lo, hi) = ((rb, rb), (radius_at(liner), radius_at(liner)));
        Mesh::union([
            oval_frustum(Point3::new(0.0, feet, 0.0), liner - feet, lo, hi, 16),
            oval_wall(Point3::new(0.0, liner, 0.0), recess, hi, (r, r), wall, 16),
        ])
    } else {
        Mesh::union([
            Mesh::cuboid(Point3::new(-r, feet, -r), Point3::new(r, liner, r)),
            box_walls((-r, r), (liner, h), (-r, r), wall),
        ])
    };
    body.append(corner_feet(0.6 * rb, 0.6 * rb, feet, 0.1 * rb));
    // The hinge housing reaches back under the lid's back edge, where the hinge axis runs.
    let back = -r - overhang;
    body.append(Mesh::cuboid(
        Point3::new(-0.3 * r, h - 3.0 * lid_t, back - 0.5 * lid_t),
        Point3::new(0.3 * r, h, -r + wall),
    ));
    let lid = lid_mesh(round, r + overhang, h, lid_t);
    let mut object = ArticulatedObject::new("trash_can", Link { name: "bin".into(), mesh: body });
    let (pedal, press) = pedal(pedal_width, pedal_length, feet, rb, max_press);
    let total = object.links[0].mesh.area() + lid.area() + pedal.area();
    object.attach(
        0,
        Link { name: "lid".into(), mesh: lid },
        back_hinge(Point3::new(0.0, h, back), max_lid),
    );
    if with_pedal && pedal.area() >= MIN_PEDAL_SHARE * total {
        object.attach(0, Link { name: "pedal".into(), mesh: pedal }, press);
    }
    object
}

/// The lid: a round or square slab `half` wide, `t` thick, bevelled to its top, with a
/// lifting tab at the front.
fn lid_mesh(round: bool, half: Real, h: Real, t: Real) -> Mesh {
    let top = 0.85 * half;
    let slab = if round {
        oval_frustum(Point3::new(0.0, h, 0.0), t, (half, half), (top, top), 16)
    } else {
        let corners = |y: Real, s: Real| {
            [(-1.0, -1.0), (-1.0, 1.0), (1.0, -1.0), (1.0, 1.0)]
                .map(|(a, b)| Point3::new(a * s, y, b * s))
        };
        Mesh::hull(&[corners(h, half), corners(h + t, top)].concat())
    };
    let tab = Mesh::cuboid(
        Point3::new(-0.15 * half, h + 0.2 * t, half - 0.01),
        Point3::new(0.15 * half, h + 0.6 * t, half + 0.025),
    );
    Mesh::union([slab, tab])
}

/// The pedal: a lever under the bin, from its pivot on the bin's bottom behind the centre to a
/// ribbed step in front of the bin, and the joint that presses the step down.
fn pedal(width: Real, length: Real, feet: Real, rb: Real, max_press: Real) -> (Mesh, Joint) {
    let (lt, lw) = (0.02, 0.03);
    let (back, front) = (-0.3 * rb, rb + 0.01);
    let (y0, y1) = (feet - 0.5 * lt - 0.02, feet - 0.5 * lt);
    // The step's front edge stops 5 mm above the floor.
    let max_press = max_press.min(((y0 - 0.005) / (front + length - back)).asin());
    let lever =
        Mesh::cuboid(Point3::new(-0.5 * lw, feet - lt, back), Point3::new(0.5 * lw, feet, front));
    let step = Mesh::cuboid(
        Point3::new(-0.5 * width, y0, front),
        Point3::new(0.5 * width, y1, front + length),
    );
    let ribs = (0..4).map(|i| {
        let z = front + length * (0.15 + 0.23 * i as Real);
        Mesh::cuboid(
            Point3::new(-0.45 * width, y1, z),
            Point3::new(0.45 * width, y1 + 0.005, z + 0.2 * length),
        )
    });
    let mesh = Mesh::union([lever, step].into_iter().chain(ribs));
    // Turning about +x lowers everything in front of the pivot.
    (mesh, Joint::hinge(Point3::new(0.0, feet, back), Vector3::x(), max_press))
}
