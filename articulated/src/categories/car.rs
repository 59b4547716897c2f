//! Car: a body of three convex blocks (nose, cabin, tail) on four wheels (fixed: a wheel
//! turning about its axle is a symmetry); two or four side doors with windows swing out
//! about vertical axes at their front edges, and a two-door car may also open its bonnet
//! or boot lid.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TEST};
use crate::mesh::Mesh;
use crate::objects::car_body::{running_gear, CarShape, LID};
use crate::objects::joints::mirrored_x;
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The car category.
pub const CATEGORY: Category = Category {
    name: "car",
    description: "car body with fixed wheels; two or four doors revolute about vertical front-edge axes, maybe a bonnet or boot lid",
    splits: TEST,
    build,
};

fn build(rng: &mut Rng) -> ArticulatedObject {
    let l = rng.random_range(3.8..4.7);
    let w = rng.random_range(1.65..1.85);
    let r = rng.random_range(0.29..0.33);
    let wheelbase = l * rng.random_range(0.6..0.64);
    let front_overhang = (l - wheelbase) * rng.random_range(0.5..0.58);
    let bottom = rng.random_range(0.16..0.2);
    let belt = rng.random_range(0.85f32..0.98).max(2.0 * r + 0.2);
    let roof = belt + rng.random_range(0.42..0.55);
    let t = rng.random_range(0.09..0.11);
    let tumble = rng.random_range(0.1..0.16);
    let four_doors = rng.random_bool(0.5);
    let lid = rng.random_range(0..3u32);
    let door_front = rng.random_range(0.03..0.12);
    let rake = rng.random_range(0.25..0.4);
    let rear_slope = rng.random_range(0.15..0.3);
    let quarter = rng.random_range(0.35..0.6);
    let two_door_length = rng.random_range(1.05f32..1.25);
    let max_door = [(); 4].map(|_| rng.random_range(60.0f32..72.0).to_radians());
    let (max_bonnet, max_boot) = (rng.random_range(45.0f32..60.0), rng.random_range(60.0f32..80.0));
    let (hl, hw, m, pillar) = (0.5 * l, 0.5 * w, 0.04, 0.08);
    let fa = hl - front_overhang;
    let ra = fa - wheelbase;
    let d1 = fa - r - m - door_front;
    let rear_limit = ra + r + m;
    let d0 = if four_doors { rear_limit } else { d1 - two_door_length.min(d1 - rear_limit) };
    let spans = if four_doors {
        let front = 0.5 * (d1 - d0 - pillar);
        vec![(d1 - front, d1), (d0, d1 - front - pillar)]
    } else {
        vec![(d0, d1)]
    };
    // A two-door car's cabin reaches on behind the doors, over the rear seats.
    let c0 = if four_doors { d0 } else { d0 - quarter };
    let span = d1 - c0;
    let car = CarShape {
        hl,
        hw,
        ys: [bottom, belt, roof],
        t,
        tumble,
        base: (c0, d1),
        roof: (c0 + rear_slope * span, d1 - rake * (spans[0].1 - spans[0].0)),
    };
    // Which lid opens: none on a four-door car, else none, the bonnet or the boot lid.
    let opens = if four_doors { 0 } else { lid };
    let (nose, tail) = ((belt, belt - 0.12), (belt, belt - 0.06));
    let lowered = |(a, b): (Real, Real)| (a - LID, b - LID);
    let nose_top = if opens == 1 { lowered(nose) } else { nose };
    let tail_top = if opens == 2 { lowered(tail) } else { tail };
    let mut body = Mesh::union([
        car.end_block(d1, hl, nose_top),
        car.cabin(),
        car.end_block(c0, -hl, tail_top),
        running_gear(&car, r, [fa, ra]),
    ]);
    // Side panels fill the cabin's sides outside the doors: B pillars, rear quarters.
    let panels = if four_doors { (spans[0].0 - pillar, spans[0].0) } else { (c0, d0) };
    let post = car.on_cabin_side(panels, roof, 0.0);
    let skin = Mesh::cuboid(Point3::new(hw - t, bottom, panels.0), Point3::new(hw, belt, panels.1));
    body.append(Mesh::union([skin.clone().mirrored_x(), skin]));
    if four_doors {
        body.append(Mesh::union([post.clone().mirrored_x(), post]));
    }
    let mut object = ArticulatedObject::new("car", Link { name: "body".into(), mesh: body });
    for (i, &span) in spans.iter().enumerate() {
        let (door, joint) = car.door(span, i == 0, max_door[2 * i]);
        let place = if i == 0 { "front" } else { "rear" };
        let other = Joint { limits: (0.0, max_door[2 * i + 1]), ..mirrored_x(&joint) };
        object.attach(0, Link { name: format!("{place} right door"), mesh: door.clone() }, joint);
        object.attach(
            0,
            Link { name: format!("{place} left door"), mesh: door.mirrored_x() },
            other,
        );
    }
    // Lids hinge at the top of their cabin-side edge, so that they rise away from the cabin.
    let belt_line = |z: Real| Point3::new(0.0, belt, z);
    if opens == 1 {
        let hinge = Joint::hinge(belt_line(d1), -Vector3::x(), max_bonnet.to_radians());
        object.attach(0, Link { name: "bonnet".into(), mesh: car.lid(d1, hl, nose) }, hinge);
    } else if opens == 2 {
        let hinge = Joint::hinge(belt_line(c0), Vector3::x(), max_boot.to_radians());
        object.attach(0, Link { name: "boot lid".into(), mesh: car.lid(c0, -hl, tail) }, hinge);
    }
    object
}
