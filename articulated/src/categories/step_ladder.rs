//! Step ladder: a front frame of two rails and treads under a top cap (the static part);
//! a rear frame of two rails and braces hinged under the cap, swinging back to stand the
//! ladder; on some ladders a shelf hinged under the top tread folds down and back.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TRAIN};
use crate::mesh::Mesh;
use crate::objects::bracket::bracket_hinge;
use crate::objects::profile::block;
use crate::objects::{ArticulatedObject, Link};
use crate::seed::Rng;

/// The step ladder category.
pub const CATEGORY: Category = Category {
    name: "step_ladder",
    description: "front frame with treads; rear frame revolute about the top hinge, and an \
                  optional shelf revolute under the top tread",
    splits: TRAIN,
    build,
};

fn build(rng: &mut Rng) -> ArticulatedObject {
    let height: Real = rng.random_range(0.9..1.6);
    let steps = ((height / 0.27).round() as usize).saturating_sub(1).max(2);
    let w = rng.random_range(0.4..0.52);
    let (rail_w, rail_d) = (rng.random_range(0.025..0.035), rng.random_range(0.065..0.085));
    let (rear_w, rear_d) = (rng.random_range(0.02..0.025), rng.random_range(0.03..0.04));
    let tread_t = rng.random_range(0.02..0.03);
    let max_spread = rng.random_range(25.0f32..35.0).to_radians();
    let shelf = rng.random_bool(0.5);
    let hw = 0.5 * w;
    let pitch = height / (steps + 1) as Real;
    let mut front = Vec::new();
    for s in [-1.0, 1.0] {
        front.push(block(
            Point3::new(s * hw, 0.0, -rail_d),
            Point3::new(s * (hw - rail_w), height, 0.0),
        ));
        front.push(block(
            Point3::new(s * hw, 0.0, -rail_d),
            Point3::new(s * (hw - rail_w), 0.03, 0.01),
        ));
    }
    for k in 1..=steps {
        let y = k as Real * pitch;
        front.push(block(
            Point3::new(-hw + rail_w, y - tread_t, -rail_d),
            Point3::new(hw - rail_w, y, 0.0),
        ));
        front.push(block(
            Point3::new(-hw + rail_w, y - 0.4 * tread_t, 0.0),
            Point3::new(hw - rail_w, y, 0.01),
        ));
    }
    // The top cap spans both frames; the rear rails' knuckles hang under it.
    let r = 0.5 * rear_d;
    let back = -rail_d - rear_d;
    front.push(block(
        Point3::new(-hw - 0.02, height, back - 0.015),
        Point3::new(hw + 0.02, height + 0.04, 0.02),
    ));
    let mut rear = Vec::new();
    let mut spread = None;
    for s in [-1.0, 1.0] {
        let pivot = Point3::new(s * (hw - 0.5 * rear_w), height - r, -rail_d - r);
        let (bracket, knuckle, joint) =
            bracket_hinge(pivot, Vector3::x(), 0.5 * rear_w, r, Vector3::y() * r, max_spread);
        front.push(bracket);
        rear.push(knuckle);
        rear.push(block(
            Point3::new(s * hw, 0.0, -rail_d),
            Point3::new(s * (hw - rear_w), pivot.y, back),
        ));
        spread = Some(joint);
    }
    for y in [0.1 * height, 0.3 * height] {
        rear.push(block(
            Point3::new(-hw + rear_w, y - 0.015, back + 0.2 * rear_d),
            Point3::new(hw - rear_w, y + 0.015, back + 0.8 * rear_d),
        ));
    }
    let mut shelf_link = None;
    if shelf {
        // Hung under the top tread, the shelf folds down inside the front frame and swings
        // back between the rear rails to lie level.
        let rs = 0.008;
        let under = steps as Real * pitch - tread_t;
        let pivot = Point3::new(0.0, under - rs, -rail_d + rs);
        let half = hw - rear_w - 0.02;
        let (bracket, knuckle, joint) = bracket_hinge(
            pivot,
            Vector3::x(),
            half,
            rs,
            Vector3::y() * rs,
            rng.random_range(85.0f32..92.0).to_radians(),
        );
        front.push(bracket);
        let depth = 0.75 * (pitch - tread_t - 2.0 * rs);
        let (z0, z1) = (pivot.z - 0.8 * rs, pivot.z + 0.8 * rs);
        // Rims on the back face turn up when the shelf lies level; the side rims stop short
        // of the hinge so that they swing up behind the tread, not into it.
        let tray = Mesh::union([
            knuckle,
            block(Point3::new(-half, pivot.y - depth, z0), Point3::new(half, pivot.y, z1)),
            block(
                Point3::new(-half, pivot.y - depth, z0 - 0.015),
                Point3::new(half, pivot.y - depth + 0.01, z0),
            ),
            block(
                Point3::new(-half, pivot.y - depth, z0 - 0.015),
                Point3::new(-half + 0.01, pivot.y - 0.03, z0),
            ),
            block(
                Point3::new(half - 0.01, pivot.y - depth, z0 - 0.015),
                Point3::new(half, pivot.y - 0.03, z0),
            ),
        ]);
        shelf_link = Some((tray, joint));
    }
    let mut object = ArticulatedObject::new(
        "step_ladder",
        Link { name: "front frame".into(), mesh: Mesh::union(front) },
    );
    if let Some(joint) = spread {
        // Turning about +x swings the rear frame's feet backwards (-z).
        object.attach(0, Link { name: "rear frame".into(), mesh: Mesh::union(rear) }, joint);
    }
    if let Some((mesh, joint)) = shelf_link {
        object.attach(0, Link { name: "shelf".into(), mesh }, joint);
    }
    object
}
