//! Windmill: a tower carrying a head that turns into the wind (a turbine's nacelle or a
//! mill's cap), and a rotor of 3 to 5 blades or lattice sails turning on the head.
//!
//! The rotor turns through less than the angle between blades, so no two states are
//! copies of each other by the rotor's symmetry.

use pairs::math::{Isometry3, Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TEST};
use crate::mesh::Mesh;
use crate::objects::rotor::Rotor;
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The windmill category.
pub const CATEGORY: Category = Category {
    name: "windmill",
    description: "tower; nacelle or cap revolute about the vertical; rotor of 3-5 blades revolute about its axis through less than the blade spacing",
    splits: TEST,
    build,
};

/// What turns on the tower: the head, and the rotor with its hub and number of blades.
struct Top {
    head: Mesh,
    hub: Point3,
    rotor: Mesh,
    blades: u32,
}

/// A wind turbine's nacelle on a tower of height `h`, base radius `base` and top radius
/// `top`, with its three-bladed rotor.
fn turbine(rng: &mut Rng, h: Real, base: Real, top: Real) -> Top {
    let rotor = Rotor {
        blades: 3,
        hub_radius: h * rng.random_range(0.03..0.04),
        hub_length: 0.06 * h,
        radius: h * rng.random_range(0.45..0.6),
        root_chord: h * rng.random_range(0.06..0.08),
        tip_chord: h * rng.random_range(0.015..0.025),
        thickness: 0.012 * h,
        pitch: rng.random_range(10.0f32..20.0).to_radians(),
    };
    let (width, height, length) = (
        h * rng.random_range(0.05..0.07),
        h * rng.random_range(0.05..0.07),
        h * rng.random_range(0.15..0.2),
    );
    let floor = h + 0.01 * h;
    // The rotor spins in front of the tower, clear of its widest part.
    let front = (0.35 * length).max(base + rotor.root_chord + 0.02 * h - 0.5 * rotor.hub_length);
    let hub = Point3::new(0.0, floor + 0.5 * height, front + 0.5 * rotor.hub_length);
    // The nacelle reaches back from the yaw bearing, with a cooler and a wind mast on top.
    let (back, roof) = (-length, floor + height);
    let mesh = Mesh::union([
        Mesh::cylinder(Point3::new(0.0, h, 0.0), Point3::new(0.0, floor, 0.0), top, 12),
        Mesh::cuboid(Point3::new(-0.5 * width, floor, back), Point3::new(0.5 * width, roof, front)),
        Mesh::cuboid(
            Point3::new(-0.4 * width, roof, back),
            Point3::new(0.4 * width, roof + 0.3 * height, back + 0.25 * length),
        ),
        Mesh::cylinder(
            Point3::new(0.0, roof, back + 0.35 * length),
            Point3::new(0.0, roof + 0.6 * height, back + 0.35 * length),
            0.004 * h,
            6,
        ),
    ]);
    Top { head: mesh, hub, rotor: rotor.mesh(hub), blades: 3 }
}

/// A mill's cap, with its windshaft and a fantail, on a tower of height `h`, and its
/// lattice sails.
fn mill(rng: &mut Rng, h: Real, base: Real, top: Real) -> Top {
    let sails = rng.random_range(4..=5);
    let radius = h * rng.random_range(0.6..0.75);
    let cap = h * rng.random_range(0.2..0.3);
    let floor = h + 0.03 * h;
    let corner = |x: Real, y: Real, z: Real| Point3::new(x, y, z);
    let hull: Vec<Point3> = [-1.0, 1.0]
        .into_iter()
        .flat_map(|s| {
            [
                corner(s * top, floor, -1.1 * top),
                corner(s * top, floor, 1.1 * top),
                corner(s * 0.15 * top, floor + cap, -0.8 * top),
                corner(s * 0.15 * top, floor + cap, 0.9 * top),
            ]
        })
        .collect();
    let shaft_y = floor + 0.45 * cap;
    let hub = Point3::new(0.0, shaft_y, base + 0.08 * h);
    let tail = Point3::new(0.0, floor + cap, -1.1 * top - 0.15 * h);
    let fantail = Rotor {
        blades: 6,
        hub_radius: 0.015 * h,
        hub_length: 0.02 * h,
        radius: 0.1 * h,
        root_chord: 0.02 * h,
        tip_chord: 0.04 * h,
        thickness: 0.004 * h,
        pitch: 0.4,
    };
    let mesh = Mesh::union([
        Mesh::cylinder(Point3::new(0.0, h, 0.0), Point3::new(0.0, floor, 0.0), top, 8),
        Mesh::hull(&hull),
        Mesh::cylinder(Point3::new(0.0, shaft_y, 0.0), hub - Vector3::z() * 0.02 * h, 0.03 * h, 10),
        Mesh::beam(
            Point3::new(0.0, floor + 0.5 * cap, -0.6 * top),
            tail,
            0.02 * h,
            0.02 * h,
            Vector3::y(),
        ),
        fantail
            .mesh(Point3::origin())
            .transformed(&Isometry3::new(tail.coords, Vector3::y() * std::f32::consts::FRAC_PI_2)),
    ]);
    let rotor =
        lattice(sails, radius, 0.04 * h).transformed(&Isometry3::translation(hub.x, hub.y, hub.z));
    Top { head: mesh, hub, rotor, blades: sails }
}

/// `count` lattice sails of `radius` round a hub of radius `hub` turning about z: each a
/// stock from the hub and, beside it, two rails joined by bars.
fn lattice(count: u32, radius: Real, hub: Real) -> Mesh {
    let bar = 0.02 * radius;
    let step = std::f32::consts::TAU / count as Real;
    let sail = Mesh::union(
        [
            Mesh::cuboid(Point3::new(0.0, -bar, -bar), Point3::new(radius, bar, bar)),
            Mesh::cuboid(
                Point3::new(0.2 * radius, 0.12 * radius, -0.5 * bar),
                Point3::new(radius, 0.12 * radius + bar, 0.5 * bar),
            ),
            Mesh::cuboid(
                Point3::new(0.2 * radius, -0.06 * radius - bar, -0.5 * bar),
                Point3::new(radius, -0.06 * radius, 0.5 * bar),
            ),
        ]
        .into_iter()
        .chain((0..8).map(|k| {
            let x = (0.22 + 0.11 * k as Real) * radius;
            Mesh::cuboid(
                Point3::new(x, -0.06 * radius, -0.5 * bar),
                Point3::new(x + bar, 0.12 * radius, 0.5 * bar),
            )
        })),
    );
    let boss = Mesh::cylinder(
        Point3::new(0.0, 0.0, -0.5 * hub),
        Point3::new(0.0, 0.0, 0.5 * hub),
        hub,
        10,
    );
    Mesh::union([boss].into_iter().chain((0..count).map(|k| {
        sail.clone().transformed(&Isometry3::rotation(Vector3::z() * (k as Real * step)))
    })))
}

fn build(rng: &mut Rng) -> ArticulatedObject {
    let modern = rng.random_bool(0.5);
    let h = if modern { rng.random_range(40.0..80.0) } else { rng.random_range(8.0..14.0) };
    let base = h * if modern { rng.random_range(0.045..0.06) } else { rng.random_range(0.3..0.38) };
    let top = base * rng.random_range(0.55..0.7);
    // Heads turn to face the wind; the stops keep cables from winding up, and keep the
    // head short of a half turn, which would nearly map a nacelle onto itself.
    let yaw = (
        rng.random_range(30.0f32..90.0).to_radians(),
        rng.random_range(100.0f32..125.0).to_radians(),
    );
    let segments = if modern { 12 } else { 8 };
    let mut tower = Mesh::frustum(Point3::origin(), Point3::new(0.0, h, 0.0), base, top, segments);
    if !modern {
        // The door stands out less than the sails' clearance from the tower.
        tower.append(Mesh::cuboid(
            Point3::new(-0.06 * h, 0.0, 0.5 * base),
            Point3::new(0.06 * h, 0.18 * h, 1.02 * base),
        ));
    }
    let parts = if modern { turbine(rng, h, base, top) } else { mill(rng, h, base, top) };
    let spacing = std::f32::consts::TAU / parts.blades as Real;
    let mut object = ArticulatedObject::new("windmill", Link { name: "tower".into(), mesh: tower });
    let turn = Joint::revolute(Point3::origin(), Vector3::y(), (-yaw.0, yaw.1));
    let head = object.attach(0, Link { name: "head".into(), mesh: parts.head }, turn);
    // The rotor stops 20 degrees short of the blade spacing.
    let spin = Joint::revolute(parts.hub, Vector3::z(), (0.0, spacing - 20f32.to_radians()));
    object.attach(head, Link { name: "rotor".into(), mesh: parts.rotor }, spin);
    object
}
