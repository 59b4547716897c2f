//! Suitcase: an upright shell on wheels with carry handles and a telescopic handle of one or
//! two stages that slides up out of housings on the back; sometimes the front half of the
//! shell is a lid that swings open about a side edge.

use pairs::math::{Isometry3, Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TEST};
use crate::mesh::Mesh;
use crate::objects::container::{box_walls, open_box};
use crate::objects::handle::bar_handle;
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The suitcase category.
pub const CATEGORY: Category = Category {
    name: "suitcase",
    description: "wheeled shell with a telescopic handle of 1 or 2 prismatic stages (chained) and an optional front lid revolute about a side edge",
    splits: TEST,
    build,
};

/// Wall thickness of the handle's tubes and housings.
const TUBE_WALL: Real = 0.0025;

fn build(rng: &mut Rng) -> ArticulatedObject {
    let hw = 0.5 * rng.random_range(0.36..0.5);
    let (h, hd) = (rng.random_range(0.5..0.78), 0.5 * rng.random_range(0.2..0.3));
    let wheel = rng.random_range(0.04..0.07);
    let t = rng.random_range(0.004..0.008);
    let two_stages = rng.random_bool(0.5);
    let with_lid = rng.random_bool(0.5);
    let split = hd - 2.0 * hd * rng.random_range(0.35..0.5);
    let left_hinge = rng.random_bool(0.5);
    let max_lid = rng.random_range(95.0f32..115.0).to_radians();
    let rail_x = hw * rng.random_range(0.55..0.75);
    let tube = rng.random_range(0.022..0.03);
    let travels = [rng.random_range(0.6..0.8), rng.random_range(0.6..0.8)];
    let (bottom, top) = (wheel, wheel + h);
    // The shell's halves are trays, open boxes turned to face the split: the back one opens
    // towards +z, the front one towards -z.
    let turn = |angle: Real| Isometry3::rotation(Vector3::x() * angle);
    let quarter = std::f32::consts::FRAC_PI_2;
    let mut shell =
        open_box((-hw, hw), (-hd, split), (-top, -bottom), t).transformed(&turn(quarter));
    let front = open_box((-hw, hw), (-hd, -split), (bottom, top), t).transformed(&turn(-quarter));
    // Without a lid the front half is fixed and stands on wheels of its own; with one, the
    // side handle goes on the side away from the hinge.
    let (side, wheel_zs) = match with_lid {
        true => (if left_hinge { hw } else { -hw }, vec![-hd + 0.5 * wheel]),
        false => (hw, vec![-hd + 0.5 * wheel, hd - 0.5 * wheel]),
    };
    if !with_lid {
        shell.append(front.clone());
    }
    for (z, x) in wheel_zs.iter().flat_map(|&z| [(z, -hw + 0.04), (z, hw - 0.04)]) {
        let c = Point3::new(x, 0.5 * wheel, z);
        let half = Vector3::x() * 0.012;
        shell.append(Mesh::cylinder(c - half, c + half, 0.5 * wheel, 12));
    }
    let mid_z = 0.5 * (split - hd);
    let (a, b) = (Point3::new(-0.15, top, mid_z), Point3::new(0.15, top, mid_z));
    shell.append(bar_handle(a, b, Vector3::y(), 0.035, 0.01));
    let c = Point3::new(side, bottom + 0.5 * h, mid_z);
    let along = Vector3::z() * 0.05;
    shell.append(bar_handle(c - along, c + along, Vector3::x() * side.signum(), 0.03, 0.009));
    // The handle's housings on the back: square tubes `tube` wide inside.
    let rail_z = -hd - 0.5 * tube - TUBE_WALL;
    let rail_bottom = bottom + 0.15 * h;
    let tubes = |y0: Real, y1: Real, half: Real| {
        Mesh::union([-rail_x, rail_x].map(|x| {
            box_walls((x - half, x + half), (y0, y1), (rail_z - half, rail_z + half), TUBE_WALL)
        }))
    };
    shell.append(tubes(rail_bottom, top, 0.5 * tube + TUBE_WALL));
    let mut object = ArticulatedObject::new("suitcase", Link { name: "shell".into(), mesh: shell });
    // Each stage fits exactly inside the one before and stands a little higher inside it;
    // the last carries the grip on top.
    let stages = if two_stages { 2 } else { 1 };
    let top_end = top + 0.01 * (stages - 1) as Real;
    let mut parent = 0;
    for (stage, travel) in travels.iter().take(stages).enumerate() {
        let half = 0.5 * tube - TUBE_WALL * stage as Real;
        let y0 = rail_bottom + 0.01 * (stage + 1) as Real;
        let mut mesh = tubes(y0, top_end, half);
        let name = if stage + 1 == stages {
            mesh.append(grip(rail_x, half, top_end, rail_z));
            "handle"
        } else {
            "handle tubes"
        };
        let joint = Joint::slide(Point3::origin(), Vector3::y(), travel * (top_end - y0));
        parent = object.attach(parent, Link { name: name.into(), mesh }, joint);
    }
    if with_lid {
        let axis = -Vector3::y() * side.signum();
        let joint = Joint::hinge(Point3::new(-side, bottom, split), axis, max_lid);
        object.attach(0, Link { name: "lid".into(), mesh: front }, joint);
    }
    object
}

/// The grip across the tops of the handle's tubes (`half` their half width) at height `y`:
/// a bar with a rounded hand hold on it.
fn grip(rail_x: Real, half: Real, y: Real, z: Real) -> Mesh {
    Mesh::union([
        Mesh::cuboid(
            Point3::new(-rail_x - half, y, z - 1.4 * half),
            Point3::new(rail_x + half, y + 0.03, z + 1.4 * half),
        ),
        Mesh::cylinder(
            Point3::new(-0.6 * rail_x, y + 0.03, z),
            Point3::new(0.6 * rail_x, y + 0.03, z),
            1.2 * half,
            10,
        ),
    ])
}
