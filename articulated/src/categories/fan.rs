//! Fan: a desk or standing fan. A base and column (on standing fans maybe telescopic)
//! hold a tilting neck in a fork; the head (motor, guard and rotor, the rotor being
//! symmetric and so no joint) oscillates about the neck.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TEST};
use crate::mesh::Mesh;
use crate::objects::arm::Section;
use crate::objects::rotor::Rotor;
use crate::objects::tube::tube;
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The fan category.
pub const CATEGORY: Category = Category {
    name: "fan",
    description: "base and column (maybe prismatic telescopic); neck revolute tilting; head with guard and rotor revolute oscillating about the neck",
    splits: TEST,
    build,
};

/// The head on a neck whose top is at `top`: guard of radius `r` in front of a motor,
/// the rotor inside the guard. The guard stands off the neck axis by more than the neck's
/// bearing, so oscillating never brings the two together.
fn head(rng: &mut Rng, top: Point3, r: Real, motor: Real) -> Mesh {
    let (back, depth) = (rng.random_range(0.06..0.09), r * rng.random_range(0.35..0.45));
    // The back guard, at the motor's nose, stands `guard` ahead of the neck's axis.
    let guard = 0.07 + 0.1 * r;
    let tube_r = 0.004;
    let centre = Point3::new(0.0, top.y + 0.015 + motor, 0.0);
    let at = |z: Real| Point3::new(0.0, centre.y, z);
    let rotor = Rotor {
        blades: rng.random_range(3..=5),
        hub_radius: 0.5 * motor,
        hub_length: 0.03,
        radius: 0.85 * r,
        root_chord: 0.2 * r,
        tip_chord: 0.38 * r,
        thickness: 0.004,
        pitch: rng.random_range(25.0f32..35.0).to_radians(),
    };
    let spokes = rng.random_range(6..=8);
    let mut mesh = Mesh::union([
        Mesh::cylinder(top, top + Vector3::y() * 0.015, 0.028, 12),
        Mesh::cylinder(at(-back), at(guard), motor, 16),
        Mesh::frustum(at(-back), at(-back - 0.03), motor, 0.6 * motor, 16),
        Mesh::cylinder(at(-0.5 * back), at(-0.5 * back) + Vector3::y() * (motor + 0.02), 0.012, 8),
        Mesh::cylinder(at(guard), at(guard + 0.45 * depth), 0.01, 8),
        rotor.mesh(at(guard + 0.45 * depth)),
        Mesh::ring(at(guard), r, tube_r, 24),
        Mesh::ring(at(guard), 0.55 * r, tube_r, 16),
        Mesh::ring(at(guard + depth), r, tube_r, 24),
        Mesh::ring(at(guard + depth + 0.02), 0.65 * r, tube_r, 16),
        Mesh::ring(at(guard + depth + 0.035), 0.3 * r, tube_r, 12),
        Mesh::cylinder(at(guard + depth + 0.035), at(guard + depth + 0.04), 0.22 * r, 12),
    ]);
    for k in 0..spokes {
        let angle = k as Real * std::f32::consts::TAU / spokes as Real;
        let out = Vector3::new(angle.cos(), angle.sin(), 0.0);
        mesh.append(Mesh::beam(
            at(guard) + out * 0.6 * motor,
            at(guard) + out * r,
            tube_r * 2.0,
            tube_r * 2.0,
            Vector3::z(),
        ));
        mesh.append(Mesh::beam(
            at(guard + depth) + out * r,
            at(guard + depth + 0.035) + out * 0.3 * r,
            tube_r * 2.0,
            tube_r * 2.0,
            Vector3::z(),
        ));
        if k % 2 == 0 {
            mesh.append(Mesh::beam(
                at(guard) + out * r,
                at(guard + depth) + out * r,
                tube_r * 2.0,
                tube_r * 2.0,
                out,
            ));
        }
    }
    mesh
}

fn build(rng: &mut Rng) -> ArticulatedObject {
    let standing = rng.random_bool(0.5);
    let r: Real =
        if standing { rng.random_range(0.18..0.25) } else { rng.random_range(0.12..0.18) };
    let (base_r, base_h) = if standing {
        (rng.random_range(0.16..0.2), 0.035)
    } else {
        (rng.random_range(0.09..0.13), 0.04)
    };
    let column =
        if standing { rng.random_range(0.014..0.018) } else { rng.random_range(0.015..0.022) };
    let motor = r * rng.random_range(0.3..0.38);
    let telescopic = standing && rng.random_bool(0.7);
    let travel = rng.random_range(0.25..0.4);
    let tilt_section = Section { half: 0.8 * column, cheek: 0.007, depth: 2.0 * column };
    let (half, depth) = (tilt_section.half, tilt_section.depth);
    let stem =
        base_h + if standing { rng.random_range(0.6..0.8) } else { rng.random_range(0.03..0.08) };
    let pivot = Point3::new(0.0, stem + 0.5 * depth + 0.008, 0.0);
    // The neck lifts the guard clear of the fork and column below the tilt axis.
    // Standing fans' necks are longer, so that tilting them shows at their size.
    let extra = if standing { rng.random_range(0.06..0.12) } else { rng.random_range(0.0..0.04) };
    let neck = (r - 0.015 - motor + 0.03).max(0.1) + extra;
    let top = pivot + Vector3::y() * neck;
    let foot = Point3::new(0.0, stem, 0.0);
    let tilt_fork = Mesh::union([
        tilt_section.fork(foot, pivot),
        Mesh::cylinder(
            pivot + Vector3::x() * tilt_section.outer(),
            pivot + Vector3::x() * (tilt_section.outer() + 0.012),
            0.7 * depth,
            12,
        ),
    ]);
    let mut root = Mesh::union([
        Mesh::cylinder(Point3::origin(), Point3::new(0.0, base_h, 0.0), base_r, 20),
        Mesh::cuboid(
            Point3::new(-0.03, base_h, 0.5 * base_r),
            Point3::new(0.03, base_h + 0.015, 0.8 * base_r),
        ),
    ]);
    let mut object;
    let parent = if telescopic {
        // Collapsed at rest, the lock collar sits on the sleeve; the piston reaches deep
        // enough to stay in the sleeve at full travel.
        let sleeve = stem - 0.09;
        root.append(tube(
            Point3::new(0.0, base_h, 0.0),
            Point3::new(0.0, sleeve, 0.0),
            column,
            0.006,
            10,
        ));
        object = ArticulatedObject::new("fan", Link { name: "base".into(), mesh: root });
        let collar = Point3::new(0.0, sleeve + 0.04, 0.0);
        let inner = Mesh::union([
            Mesh::cylinder(Point3::new(0.0, sleeve - travel - 0.04, 0.0), foot, column, 12),
            Mesh::cylinder(
                Point3::new(0.0, sleeve, 0.0),
                Point3::new(0.0, sleeve + 0.08, 0.0),
                0.055,
                16,
            ),
            Mesh::cylinder(collar, collar + Vector3::x() * 0.085, 0.012, 8),
            tilt_fork,
        ]);
        let slide = Joint::prismatic(foot, Vector3::y(), (0.0, travel));
        object.attach(0, Link { name: "inner column".into(), mesh: inner }, slide)
    } else {
        root.append(Mesh::cylinder(Point3::new(0.0, base_h, 0.0), foot, column, 12));
        root.append(tilt_fork);
        object = ArticulatedObject::new("fan", Link { name: "base".into(), mesh: root });
        0
    };
    // The neck stays within the fork's inner slab, so it clears the cheeks at any tilt.
    // Its housing, the bearing the head oscillates on, is wide and shallow: its broad
    // faces face the way it tilts, which shows the tilt best.
    let (housing, under) = (if standing { 0.065 } else { 0.055 }, top - Vector3::y() * 0.08);
    let neck_mesh = Mesh::union([
        tilt_section.bar(pivot, pivot + Vector3::y() * depth),
        Mesh::cylinder(pivot, under, half, 12),
        Mesh::cuboid(Point3::new(-housing, under.y, -0.03), Point3::new(housing, top.y, 0.03)),
    ]);
    let (down, up) =
        (rng.random_range(5.0f32..10.0).to_radians(), rng.random_range(34.0f32..42.0).to_radians());
    // Turning about -x lifts the head's front.
    let tilt = Joint::revolute(pivot, -Vector3::x(), (-down, up));
    let neck_link = object.attach(parent, Link { name: "neck".into(), mesh: neck_mesh }, tilt);
    let sweep = rng.random_range(40.0f32..50.0).to_radians();
    let head_mesh = head(rng, top, r, motor);
    let oscillate = Joint::revolute(top, Vector3::y(), (-sweep, sweep));
    object.attach(neck_link, Link { name: "head".into(), mesh: head_mesh }, oscillate);
    object
}
