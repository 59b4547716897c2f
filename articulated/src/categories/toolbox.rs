//! Toolbox: an open box with a carry handle and latches on a lid hinged at the back; inside,
//! one or two trays slide back and forth on ledges under the lid, or else a drawer pulls out
//! of a bay under the main compartment.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, VALIDATION};
use crate::mesh::Mesh;
use crate::objects::container::{front_latch, knuckle_hinges, open_box};
use crate::objects::drawer::drawer;
use crate::objects::handle::bar_handle;
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The toolbox category.
pub const CATEGORY: Category = Category {
    name: "toolbox",
    description: "box with a lid revolute about the back edge and 1-2 prismatic sliding trays or a prismatic drawer below",
    splits: VALIDATION,
    build,
};

fn build(rng: &mut Rng) -> ArticulatedObject {
    let width = rng.random_range(0.4..0.6);
    let (hw, hd) = (0.5 * width, 0.5 * width * rng.random_range(0.4..0.55));
    let h = width * rng.random_range(0.35..0.5);
    let t = rng.random_range(0.006..0.01);
    let lid_t = rng.random_range(0.02..0.035);
    let max_lid = rng.random_range(95.0f32..110.0).to_radians();
    let trays = rng.random_range(0..3);
    let tray_h = h * rng.random_range(0.2..0.3);
    let tray_d = 2.0 * (hd - t) * rng.random_range(0.45..0.6);
    let bay = if trays == 0 { h * rng.random_range(0.3..0.4) } else { 0.0 };
    let travel = rng.random_range(0.5..0.75);
    let mut body = open_box((-hw, hw), (bay, h), (-hd, hd), t);
    let mut lid = Mesh::union([
        Mesh::cuboid(Point3::new(-hw - t, h, -hd), Point3::new(hw + t, h + lid_t, hd + t)),
        bar_handle(
            Point3::new(-0.3 * hw, h + lid_t, 0.0),
            Point3::new(0.3 * hw, h + lid_t, 0.0),
            Vector3::y(),
            0.035,
            0.01,
        ),
    ]);
    let radius = 0.004 * (width + h + 2.0 * hd);
    let centres = [-0.6 * hw, 0.6 * hw];
    let (fixed, moving, hinge) = knuckle_hinges(&centres, 0.25 * hw, (h, -hd), radius, max_lid);
    body.append(fixed);
    lid.append(moving);
    for x in [-0.6 * hw, 0.6 * hw] {
        let (hasp, catch) = front_latch(x, 0.1 * width, h, hd, 0.12 * h, 1.5 * t);
        lid.append(hasp);
        body.append(catch);
    }
    let ledge_y = h - tray_h;
    if trays > 0 {
        // Ledges along the side walls carry the trays with their tops flush with the rim.
        for s in [-1.0, 1.0] {
            let (a, b) = (s * (hw - t), s * (hw - t - 0.012));
            body.append(Mesh::cuboid(
                Point3::new(a.min(b), ledge_y - 0.01, -hd + t),
                Point3::new(a.max(b), ledge_y, hd - t),
            ));
        }
    } else {
        // The drawer's bay: a floor, back and sides under the compartment, open at the front.
        body.append(Mesh::union([
            Mesh::cuboid(Point3::new(-hw, 0.0, -hd), Point3::new(hw, t, hd)),
            Mesh::cuboid(Point3::new(-hw, t, -hd), Point3::new(hw, bay, -hd + t)),
            Mesh::cuboid(Point3::new(-hw, t, -hd + t), Point3::new(-hw + t, bay, hd)),
            Mesh::cuboid(Point3::new(hw - t, t, -hd + t), Point3::new(hw, bay, hd)),
        ]));
    }
    let mut object = ArticulatedObject::new("toolbox", Link { name: "box".into(), mesh: body });
    object.attach(0, Link { name: "lid".into(), mesh: lid }, hinge);
    let inner = hw - t;
    let spans: Vec<(Real, Real)> = match trays {
        1 => vec![(-inner, inner)],
        2 => vec![(-inner, 0.0), (0.0, inner)],
        _ => Vec::new(),
    };
    for (i, &(x0, x1)) in spans.iter().enumerate() {
        // A tray: an open box with a low divider down the middle, resting at the front.
        let (front, wall, mid) = (hd - t, 0.6 * t, 0.5 * (x0 + x1));
        let tray = Mesh::union([
            open_box((x0, x1), (ledge_y, h), (front - tray_d, front), wall),
            Mesh::cuboid(
                Point3::new(mid - 0.5 * wall, ledge_y + wall, front - tray_d + wall),
                Point3::new(mid + 0.5 * wall, h - 0.3 * tray_h, front - wall),
            ),
        ]);
        let joint = Joint::slide(Point3::origin(), -Vector3::z(), 2.0 * front - tray_d);
        object.attach(0, Link { name: format!("tray {}", i + 1), mesh: tray }, joint);
    }
    if trays == 0 {
        let gap = 0.003;
        let (mesh, joint) = drawer(
            (-hw + t + gap, hw - t - gap),
            (t, bay - gap),
            hd - t,
            2.0 * (hd - t),
            0.6 * t,
            travel * 2.0 * (hd - t),
        );
        object.attach(0, Link { name: "drawer".into(), mesh }, joint);
    }
    object
}
