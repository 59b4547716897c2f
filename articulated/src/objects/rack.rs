//! Racks and baskets that slide in appliance cavities: oven shelves and dishwasher baskets.

use pairs::math::{Point3, Real, Vector3};

use crate::mesh::Mesh;

/// A rack over `x0..x1` and `z0..z1` with its floor at height `y`: a rim of four flat bars
/// `bar` wide and `bars` bars running along z inside it; with `wall > 0`, a basket whose low
/// walls are `wall` high and whose floor carries rows of tines.
pub fn rack(
    (x0, x1): (Real, Real),
    y: Real,
    (z0, z1): (Real, Real),
    bars: u32,
    bar: Real,
    wall: Real,
) -> Mesh {
    let y1 = y + bar;
    let mut mesh = Mesh::union([
        Mesh::cuboid(Point3::new(x0, y, z0), Point3::new(x1, y1, z0 + bar)),
        Mesh::cuboid(Point3::new(x0, y, z1 - bar), Point3::new(x1, y1, z1)),
        Mesh::cuboid(Point3::new(x0, y, z0 + bar), Point3::new(x0 + bar, y1, z1 - bar)),
        Mesh::cuboid(Point3::new(x1 - bar, y, z0 + bar), Point3::new(x1, y1, z1 - bar)),
    ]);
    let step = (x1 - x0) / (bars + 1) as Real;
    let xs: Vec<Real> = (1..=bars).map(|i| x0 + i as Real * step).collect();
    for &x in &xs {
        let (a, b) = (Point3::new(x, y, z0 + bar), Point3::new(x, y, z1 - bar));
        mesh.append(Mesh::beam(a, b, 0.6 * bar, 0.6 * bar, Vector3::y()));
    }
    if wall > 0.0 {
        let yw = y + wall;
        let t = 0.5 * bar;
        mesh.append(Mesh::union([
            Mesh::cuboid(Point3::new(x0, y1, z0), Point3::new(x1, yw, z0 + t)),
            Mesh::cuboid(Point3::new(x0, y1, z1 - t), Point3::new(x1, yw, z1)),
            Mesh::cuboid(Point3::new(x0, y1, z0 + t), Point3::new(x0 + t, yw, z1 - t)),
            Mesh::cuboid(Point3::new(x1 - t, y1, z0 + t), Point3::new(x1, yw, z1 - t)),
        ]));
        // Two rows of tines across the basket hold dishes upright. They stand across the
        // slide and far apart, so that a slide shows; a fine regular comb slid by its pitch
        // would look unmoved.
        for f in [0.3, 0.68] {
            let z = z0 + f * (z1 - z0);
            let a = Point3::new(x0 + 2.0 * bar, y1, z - 0.2 * bar);
            mesh.append(Mesh::cuboid(
                a,
                Point3::new(x1 - 2.0 * bar, y1 + 0.7 * wall, z + 0.2 * bar),
            ));
        }
    }
    mesh
}
