//! Seesaw: a stand (two A-frame plates, or two pairs of splayed legs) holding an axle; the
//! plank, with a seat and a handle at each end, rocks about the axle.

use pairs::math::{Isometry3, Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TEST};
use crate::mesh::Mesh;
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The seesaw category.
pub const CATEGORY: Category = Category {
    name: "seesaw",
    description:
        "A-frame or leg stand; plank with seats and handles revolute about the central axle",
    splits: TEST,
    build,
};

/// One side of the stand in the slab `x0..x1`, its apex holding the axle at height `pivot`,
/// its feet `spread` apart along z.
fn stand_side(
    rng: &mut Rng,
    (x0, x1): (Real, Real),
    pivot: Real,
    axle: Real,
    spread: Real,
) -> Mesh {
    let apex = pivot + 2.0 * axle;
    let xm = 0.5 * (x0 + x1);
    let mut mesh = Mesh::union([
        Mesh::cylinder(
            Point3::new(x1, pivot, 0.0),
            Point3::new(x1 + 0.02, pivot, 0.0),
            1.6 * axle,
            12,
        ),
        Mesh::cuboid(
            Point3::new(x0 - 0.02, 0.0, -0.55 * spread),
            Point3::new(x1 + 0.02, 0.04, 0.55 * spread),
        ),
    ]);
    if rng.random_bool(0.5) {
        let corner = |x: Real, y: Real, z: Real| Point3::new(x, y, z);
        let (top, foot) = (2.0 * axle, 0.5 * spread);
        let points: Vec<Point3> = [x0, x1]
            .into_iter()
            .flat_map(|x| {
                [
                    corner(x, 0.0, -foot),
                    corner(x, 0.0, foot),
                    corner(x, apex, -top),
                    corner(x, apex, top),
                ]
            })
            .collect();
        mesh.append(Mesh::hull(&points));
    } else {
        let width = x1 - x0;
        for z in [-0.5 * spread, 0.5 * spread] {
            mesh.append(Mesh::beam(
                Point3::new(xm, apex, 0.0),
                Point3::new(xm, 0.0, z),
                width,
                width,
                Vector3::x(),
            ));
        }
        mesh.append(Mesh::cuboid(
            Point3::new(x0, pivot - 1.5 * axle, -2.0 * axle),
            Point3::new(x1, apex, 2.0 * axle),
        ));
    }
    mesh
}

/// A seat, maybe with a backrest, and a handle at the +z end of a plank whose top is at
/// `top` and whose half length is `half`.
fn plank_end(rng: &mut Rng, top: Real, half: Real, width: Real) -> Mesh {
    let seat = 0.5 * width.max(rng.random_range(0.28..0.38));
    let handle_z = half - rng.random_range(0.5..0.6);
    let (rise, grip) = (rng.random_range(0.25..0.35), rng.random_range(0.14..0.2));
    let handle_top = Point3::new(0.0, top + rise, handle_z);
    let mut mesh = Mesh::union([
        Mesh::cuboid(
            Point3::new(-seat, top, half - 0.45),
            Point3::new(seat, top + 0.05, half - 0.04),
        ),
        Mesh::cylinder(Point3::new(0.0, top, handle_z), handle_top, 0.02, 10),
        Mesh::cylinder(
            handle_top - Vector3::x() * grip,
            handle_top + Vector3::x() * grip,
            0.018,
            10,
        ),
    ]);
    if rng.random_bool(0.5) {
        mesh.append(Mesh::cuboid(
            Point3::new(-seat, top + 0.05, half - 0.07),
            Point3::new(seat, top + 0.3, half - 0.04),
        ));
    }
    mesh
}

fn build(rng: &mut Rng) -> ArticulatedObject {
    let length = rng.random_range(2.2..3.6);
    let (width, thick) = (rng.random_range(0.2..0.32), rng.random_range(0.04..0.07));
    let pivot = rng.random_range(0.45..0.7);
    let axle = rng.random_range(0.03..0.045);
    let slab = (0.5 * width + rng.random_range(0.01..0.02), rng.random_range(0.04..0.06));
    let spread = rng.random_range(0.6..1.0f32).min(0.3 * length);
    // The plank's ends stop short of the ground.
    let rock =
        rng.random_range(12.0f32..20.0).to_radians().min(((pivot - 0.1) / (0.5 * length)).asin());
    let side = stand_side(rng, (slab.0, slab.0 + slab.1), pivot, axle, spread);
    let stand = Mesh::union([
        side.clone().mirrored_x(),
        side,
        Mesh::beam(
            Point3::new(-slab.0, 0.1, 0.0),
            Point3::new(slab.0, 0.1, 0.0),
            0.05,
            0.05,
            Vector3::y(),
        ),
    ]);
    let (half, top) = (0.5 * length, pivot + axle + thick);
    let hw = 0.5 * width;
    let end = plank_end(rng, top, half, width);
    let plank = Mesh::union([
        Mesh::cylinder(Point3::new(-slab.0, pivot, 0.0), Point3::new(slab.0, pivot, 0.0), axle, 12),
        Mesh::cuboid(
            Point3::new(-0.8 * hw, pivot, -1.5 * axle),
            Point3::new(0.8 * hw, pivot + axle, 1.5 * axle),
        ),
        Mesh::cuboid(Point3::new(-hw, pivot + axle, -half), Point3::new(hw, top, half)),
        end.clone().transformed(&Isometry3::rotation(Vector3::y() * std::f32::consts::PI)),
        end,
    ]);
    let mut object = ArticulatedObject::new("seesaw", Link { name: "stand".into(), mesh: stand });
    let rocker = Joint::revolute(Point3::new(0.0, pivot, 0.0), Vector3::x(), (-rock, rock));
    object.attach(0, Link { name: "plank".into(), mesh: plank }, rocker);
    object
}
