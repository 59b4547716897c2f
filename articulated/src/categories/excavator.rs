//! Excavator: tracks and undercarriage, maybe with a dozer blade; an upper structure (cab,
//! engine hood, counterweight) slewing about the vertical, or fixed on some machines; a
//! bent boom, a stick and a bucket hinged in a chain about horizontal axes.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TRAIN};
use crate::mesh::Mesh;
use crate::objects::arm::{heading, Section};
use crate::objects::bucket::bucket;
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The excavator category.
pub const CATEGORY: Category = Category {
    name: "excavator",
    description: "tracks; upper structure revolute about the vertical (or fixed); boom, stick and bucket revolute in a chain",
    splits: TRAIN,
    build,
};

/// The undercarriage, `length` long: two tracks, the car body, the slewing ring up to
/// height `ring`, and maybe a dozer blade in front.
fn undercarriage(rng: &mut Rng, length: Real, gauge: Real, ring: Real) -> Mesh {
    let (width, height) =
        (rng.random_range(0.45..0.7), rng.random_range(0.7..0.9f32).min(ring - 0.05));
    let (x0, x1) = (0.5 * gauge - 0.5 * width, 0.5 * gauge + 0.5 * width);
    let wheel =
        |z: Real, r: Real| Mesh::cylinder(Point3::new(x0, r, z), Point3::new(x1, r, z), r, 12);
    let (sprocket, idler) = (
        wheel(0.5 * height - 0.5 * length, 0.5 * height),
        wheel(0.5 * length - 0.45 * height, 0.45 * height),
    );
    let points: Vec<Point3> = sprocket.vertices.iter().chain(&idler.vertices).copied().collect();
    let track = Mesh::hull(&points);
    let mut mesh = Mesh::union([
        track.clone().mirrored_x(),
        track,
        Mesh::cuboid(
            Point3::new(-x0, 0.3 * height, -0.35 * length),
            Point3::new(x0, 0.85 * height, 0.35 * length),
        ),
        Mesh::cylinder(
            Point3::new(0.0, 0.85 * height, 0.0),
            Point3::new(0.0, ring, 0.0),
            0.3 * gauge,
            16,
        ),
    ]);
    if rng.random_bool(0.5) {
        let (z0, z1) = (0.5 * length + 0.2, 0.5 * length + 0.3);
        mesh.append(Mesh::cuboid(Point3::new(-x1, 0.05, z0), Point3::new(x1, 0.6 * height, z1)));
        let arm = Mesh::beam(
            Point3::new(0.3 * gauge, 0.5 * height, 0.3 * length),
            Point3::new(0.3 * gauge, 0.35 * height, z0),
            0.12,
            0.15,
            Vector3::y(),
        );
        mesh.append(arm.clone().mirrored_x());
        mesh.append(arm);
    }
    mesh
}

/// The upper structure on the slewing ring at height `floor`: platform, counterweight,
/// hood, and the cab beside the boom's fork (cheeks outside `|x| = half`); returns it and
/// the boom's foot pivot.
fn upper(rng: &mut Rng, floor: Real, width: Real, boom: &Section) -> (Mesh, Point3) {
    let (tail, nose) = (rng.random_range(1.4..1.9), rng.random_range(0.9..1.2));
    let hw = 0.5 * width;
    let deck = floor + 0.2;
    let cab_x = boom.outer() + 0.1;
    let foot = Point3::new(0.0, deck + 0.5, nose - 0.35);
    let mesh = Mesh::union([
        Mesh::cuboid(Point3::new(-hw, floor, -tail), Point3::new(hw, deck, nose)),
        Mesh::cuboid(Point3::new(-hw, deck, -tail), Point3::new(hw, deck + 0.8, 0.5 - tail)),
        Mesh::cuboid(Point3::new(-hw, deck, 0.5 - tail), Point3::new(hw, deck + 0.7, -0.4)),
        Mesh::cuboid(Point3::new(cab_x, deck, -0.4), Point3::new(hw, deck + 1.6, nose - 0.05)),
        Mesh::cuboid(
            Point3::new(cab_x + 0.08, deck + 0.7, nose - 0.05),
            Point3::new(hw - 0.08, deck + 1.5, nose - 0.03),
        ),
        Mesh::cuboid(
            Point3::new(hw, deck + 0.7, -0.3),
            Point3::new(hw + 0.02, deck + 1.5, nose - 0.15),
        ),
        boom.fork(Point3::new(0.0, deck, foot.z), foot),
    ]);
    (mesh, foot)
}

fn build(rng: &mut Rng) -> ArticulatedObject {
    let length = rng.random_range(3.0..4.5);
    let gauge: Real = rng.random_range(1.9..2.5);
    let ring = rng.random_range(0.8..0.95);
    let section = Section {
        half: rng.random_range(0.18..0.25),
        cheek: rng.random_range(0.06..0.1),
        depth: rng.random_range(0.4..0.55),
    };
    let width = (gauge + 0.6).max(2.0 * (section.outer() + 0.95));
    let tracks = undercarriage(rng, length, gauge, ring);
    let (upper_mesh, foot) = upper(rng, ring, width, &section);
    let mut object;
    let parent = if rng.random_bool(0.75) {
        object = ArticulatedObject::new(
            "excavator",
            Link { name: "undercarriage".into(), mesh: tracks },
        );
        let slew = rng.random_range(100.0f32..170.0).to_radians();
        let turn = Joint::revolute(Point3::origin(), Vector3::y(), (-slew, slew));
        object.attach(0, Link { name: "upper structure".into(), mesh: upper_mesh }, turn)
    } else {
        object = ArticulatedObject::new(
            "excavator",
            Link { name: "body".into(), mesh: Mesh::union([tracks, upper_mesh]) },
        );
        0
    };
    // The boom rises steeply, then bends to reach forward.
    let boom = length * rng.random_range(1.0..1.25);
    let (rise, reach) = (
        rng.random_range(40.0f32..55.0).to_radians(),
        rng.random_range(-15.0f32..5.0).to_radians(),
    );
    let knee = foot + Vector3::new(0.0, rise.sin(), rise.cos()) * (0.55 * boom);
    let head = knee + Vector3::new(0.0, reach.sin(), reach.cos()) * (0.45 * boom);
    let boom_mesh = Mesh::union([section.bar(foot, knee), section.bar(knee, head)]);
    // Raising the boom turns it about -x; curling the stick and the bucket in, about +x.
    // The boom dips little and the stick crowds in little, so the bucket never reaches
    // back into the tracks or the blade.
    let lift =
        (rng.random_range(5.0f32..12.0).to_radians(), rng.random_range(35.0f32..50.0).to_radians());
    let boom_link = object.attach(
        parent,
        Link { name: "boom".into(), mesh: boom_mesh },
        Joint::revolute(foot, -Vector3::x(), (-lift.0, lift.1)),
    );
    let down = heading((180.0 - rng.random_range(10.0f32..30.0)).to_radians());
    let tip = head + down * (boom * rng.random_range(0.45..0.6));
    let stick_section = Section { depth: 0.9 * section.depth, ..section };
    let stick = stick_section.fork_to_bar(head, tip);
    let crowd = (
        rng.random_range(40.0f32..60.0).to_radians(),
        rng.random_range(10.0f32..25.0).to_radians(),
    );
    let stick_link = object.attach(
        boom_link,
        Link { name: "stick".into(), mesh: stick },
        Joint::revolute(head, Vector3::x(), (-crowd.0, crowd.1)),
    );
    let scoop = bucket(
        tip,
        down,
        length * rng.random_range(0.15..0.18),
        length * rng.random_range(0.28..0.35),
        &stick_section,
    );
    let curl = (
        rng.random_range(55.0f32..75.0).to_radians(),
        rng.random_range(75.0f32..100.0).to_radians(),
    );
    object.attach(
        stick_link,
        Link { name: "bucket".into(), mesh: scoop },
        Joint::revolute(tip, Vector3::x(), (-curl.0, curl.1)),
    );
    object
}
