//! Book: a block of pages glued into a rounded spine between two cover boards. The front
//! cover turns open about its joint with the spine; on some books the back cover turns
//! too, about the spine's other edge, the page block then being the static body.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TRAIN};
use crate::mesh::Mesh;
use crate::objects::contact::{contact_pads, pad_thickness};
use crate::objects::profile::prism;
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The book category.
pub const CATEGORY: Category = Category {
    name: "book",
    description: "page block in a rounded spine; front cover revolute about the spine, and \
                  on some books the back cover too",
    splits: TRAIN,
    build,
};

/// A half-round spine of boards `board` thick, from (x, 0) round the back to (x, `thick`),
/// running the full height in z, with `bands` raised bands across it.
fn spine(x: Real, thick: Real, board: Real, height: Real, bands: usize) -> Mesh {
    let radius = 0.5 * (thick - board);
    let n = 8;
    let at = |k: usize, r: Real| {
        let a = (90.0 + 180.0 * k as Real / n as Real).to_radians();
        [x + r * a.cos(), 0.5 * thick + r * a.sin()]
    };
    let (inner, outer) = (radius - 0.5 * board, radius + 0.5 * board);
    // Annular sectors, each one convex piece, end exactly at the covers' edges.
    let mut parts: Vec<Mesh> = (0..n)
        .map(|i| {
            let sector = [at(i, inner), at(i, outer), at(i + 1, outer), at(i + 1, inner)];
            prism(&sector, (-0.5 * height, 0.5 * height), Point3::new)
        })
        .collect();
    for k in 0..bands {
        let z = height * ((k as Real + 1.0) / (bands as Real + 1.0) - 0.5);
        let band = Point3::new(x, 0.5 * thick, z);
        let angles = (120f32.to_radians(), 240f32.to_radians());
        parts.push(Mesh::arc(band, radius + 0.5 * board, 0.0015, angles, 6));
    }
    Mesh::union(parts)
}

fn build(rng: &mut Rng) -> ArticulatedObject {
    let w = rng.random_range(0.12..0.22);
    let h = rng.random_range(0.17..0.3);
    let thick = rng.random_range(0.015..0.06);
    let board = rng.random_range(0.0018..0.0035);
    let square = rng.random_range(0.002..0.005);
    let back_opens = rng.random_bool(0.5);
    let bands = if rng.random_bool(0.4) { rng.random_range(3..6) } else { 0 };
    let max_front = rng.random_range(150.0f32..170.0).to_radians();
    let max_back = rng.random_range(150.0f32..170.0).to_radians();
    let (x0, x1, hh) = (-0.5 * w, 0.5 * w, 0.5 * h);
    let boards = |y: Real| Mesh::cuboid(Point3::new(x0, y, -hh), Point3::new(x1, y + board, hh));
    let pages = Mesh::cuboid(
        Point3::new(x0, board, -hh + square),
        Point3::new(x1 - square, thick - board, hh - square),
    );
    let mut body = vec![spine(x0, thick, board, h, bands), pages];
    // Each cover turns about its outer edge along the spine, so that its end swings clear of
    // the spine; contact pads stacked on the top edge of the book mark where they touch.
    let lift = Vector3::z() * pad_thickness(0.5 * board);
    let front_pivot = Point3::new(x0, thick, hh);
    let (pad_spine, pad_front) = contact_pads(front_pivot + lift, Vector3::z(), 0.5 * board);
    body.push(pad_spine);
    let back_pivot = Point3::new(x0, 0.0, hh);
    let mut back_link = None;
    if back_opens {
        let (pad_spine, pad_back) = contact_pads(back_pivot + lift, Vector3::z(), 0.5 * board);
        body.push(pad_spine);
        back_link = Some(Mesh::union([boards(0.0), pad_back]));
    } else {
        body.push(boards(0.0));
    }
    let name = if back_opens { "page block" } else { "back cover and pages" };
    let mut object =
        ArticulatedObject::new("book", Link { name: name.into(), mesh: Mesh::union(body) });
    // Turning about +z lifts the front cover's fore edge up and over the spine.
    let front = Mesh::union([boards(thick - board), pad_front]);
    object.attach(
        0,
        Link { name: "front cover".into(), mesh: front },
        Joint::hinge(front_pivot, Vector3::z(), max_front),
    );
    if let Some(mesh) = back_link {
        // Turning about -z swings the back cover's fore edge down and under.
        object.attach(
            0,
            Link { name: "back cover".into(), mesh },
            Joint::hinge(back_pivot, -Vector3::z(), max_back),
        );
    }
    object
}
