//! Digger buckets: a scoop hinged under a stick, with ears clasping the stick's end.

use pairs::math::{Point3, Real, Vector3};

use super::arm::Section;
use crate::mesh::Mesh;

/// A bucket hinged at `pivot`, hanging along `down` (a unit vector in the yz plane) under
/// a stick of cross-section `stick`: ears (a fork) clasping the stick, a curved back plate,
/// two side plates and five teeth, `radius` deep and `width` wide, its mouth facing the
/// machine (turning `down` towards -z).
pub fn bucket(pivot: Point3, down: Vector3, radius: Real, width: Real, stick: &Section) -> Mesh {
    // Profile coordinates: `u` along the stick, `v` towards the machine, in radii.
    let inward = Vector3::new(0.0, -down.z, down.y);
    let at = |u: Real, v: Real, x: Real| {
        pivot + down * (u * radius) + inward * (v * radius) + Vector3::x() * x
    };
    // The back plate follows an arc round (1, 0.25) from above the pivot to the lip.
    let arc: Vec<(Real, Real)> = (0..=7)
        .map(|k| {
            let angle = (-150.0 + 30.0 * k as Real).to_radians();
            (1.0 + 0.75 * angle.cos(), 0.25 + 0.75 * angle.sin())
        })
        .collect();
    let (hw, plate) = (0.5 * width, 0.04);
    let mut mesh = stick.fork(pivot, at(0.4, 0.0, 0.0));
    for pair in arc.windows(2) {
        let (a, b) = (at(pair[0].0, pair[0].1, 0.0), at(pair[1].0, pair[1].1, 0.0));
        mesh.append(Mesh::beam(a, b, 0.05 * radius, width, Vector3::x()));
    }
    for x in [-hw, hw - plate] {
        let side: Vec<Point3> =
            arc.iter().flat_map(|&(u, v)| [at(u, v, x), at(u, v, x + plate)]).collect();
        mesh.append(Mesh::hull(&side));
    }
    let (lip_u, lip_v) = arc[arc.len() - 1];
    for k in 0..5 {
        let x = -hw + width * (0.1 + 0.2 * k as Real);
        mesh.append(Mesh::hull(&[
            at(lip_u, lip_v, x - 0.04),
            at(lip_u, lip_v, x + 0.04),
            at(lip_u + 0.05, lip_v + 0.03, x),
            at(lip_u - 0.13, lip_v + 0.08, x),
        ]));
    }
    mesh
}
