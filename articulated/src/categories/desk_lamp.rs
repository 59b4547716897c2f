//! Desk lamp: a weighted base with a yoke, two or three arm segments in a chain, each
//! hinged to the previous about a horizontal axis, and a shade hinged to the last one.

use pairs::math::{Point3, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TEST};
use crate::mesh::Mesh;
use crate::objects::arm::{heading, Section};
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The desk lamp category.
pub const CATEGORY: Category = Category {
    name: "desk_lamp",
    description:
        "base with a yoke; 2 or 3 arm segments revolute in a chain; shade revolute at the arm's tip",
    splits: TEST,
    build,
};

/// The shade hanging from `pivot` along `dir`: a bracket, a neck and a flared shade.
fn head(rng: &mut Rng, section: &Section, pivot: Point3, dir: Vector3, forked: bool) -> Mesh {
    let neck = pivot + dir * rng.random_range(0.045..0.06);
    let length = rng.random_range(0.09..0.15);
    let (top, mouth) = (rng.random_range(0.022..0.03), rng.random_range(0.05..0.075));
    Mesh::union([
        section.segment(pivot, neck, forked),
        Mesh::frustum(neck - dir * 0.015, neck, 0.5 * top, top, 12),
        Mesh::frustum(neck, neck + dir * length, top, mouth, 16),
        Mesh::sphere(neck + dir * (length - 0.3 * mouth), 0.45 * mouth, 12),
    ])
}

fn build(rng: &mut Rng) -> ArticulatedObject {
    let (radius, thick) = (rng.random_range(0.07..0.11), rng.random_range(0.02..0.035));
    let section = Section {
        half: rng.random_range(0.009..0.012),
        cheek: rng.random_range(0.007..0.01),
        depth: rng.random_range(0.018..0.026),
    };
    let segments = if rng.random_bool(0.5) { 3 } else { 2 };
    let foot = Point3::new(0.0, thick, 0.0);
    let mut pivot = foot + Vector3::y() * (section.depth + rng.random_range(0.01..0.03));
    let base = Mesh::union([
        Mesh::cylinder(Point3::origin(), foot, radius, 16),
        Mesh::cuboid(
            Point3::new(-0.015, thick, 0.5 * radius),
            Point3::new(0.015, thick + 0.012, 0.75 * radius),
        ),
        section.segment(foot, pivot, true),
    ]);
    let mut object = ArticulatedObject::new("desk_lamp", Link { name: "base".into(), mesh: base });
    // Rest pose: up and slightly forward, then out over the desk, then (third) down.
    let rests = [
        rng.random_range(5.0f32..15.0),
        rng.random_range(60.0..85.0),
        rng.random_range(100.0..125.0),
    ];
    // Turning forward, each segment stops short of `reach` from straight up (degrees), so
    // that the arm stretched out keeps the shade above the desk.
    let reach = [25.0f32, 100.0, 140.0];
    let short = if segments == 3 { 0.75 } else { 1.0 };
    let (mut parent, mut forward) = (0, 0.0);
    for (i, rest) in rests.iter().take(segments).enumerate() {
        let tip = pivot + heading(rest.to_radians()) * (short * rng.random_range(0.26..0.36));
        let range = rng.random_range(30.0f32..40.0);
        let high = range.min(reach[i] - rest - forward).max(8.0);
        forward += high;
        let limits = (-range.to_radians(), high.to_radians());
        let link =
            Link { name: format!("arm {}", i + 1), mesh: section.segment(pivot, tip, i % 2 == 1) };
        parent = object.attach(parent, link, Joint::revolute(pivot, Vector3::x(), limits));
        pivot = tip;
    }
    let hang = heading(rng.random_range(150.0f32..175.0).to_radians());
    let shade = head(rng, &section, pivot, hang, segments % 2 == 1);
    let tilt = rng.random_range(25.0f32..35.0).to_radians();
    object.attach(
        parent,
        Link { name: "shade".into(), mesh: shade },
        Joint::revolute(pivot, Vector3::x(), (-tilt, tilt)),
    );
    object
}
