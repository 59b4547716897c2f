//! Round and oval shells about a vertical axis: solid tapered bodies and hollow walls, the
//! way bins, toilet bowls and seats are drawn. Radii are half-axes `(x, z)`.

use pairs::math::{Point3, Real};

use crate::mesh::Mesh;

/// A point of the oval with half-axes `radii` around `centre`, at `angle` from +x towards
/// +z, raised by `y`.
fn on_oval(centre: Point3, radii: (Real, Real), angle: Real, y: Real) -> Point3 {
    Point3::new(centre.x + radii.0 * angle.cos(), centre.y + y, centre.z + radii.1 * angle.sin())
}

/// A solid oval frustum `height` tall standing on `centre`, with half-axes `bottom` at its
/// base and `top` at its top.
pub fn oval_frustum(
    centre: Point3,
    height: Real,
    bottom: (Real, Real),
    top: (Real, Real),
    segments: u32,
) -> Mesh {
    let step = std::f32::consts::TAU / segments as Real;
    let points: Vec<Point3> = (0..segments)
        .flat_map(|i| {
            let a = i as Real * step;
            [on_oval(centre, bottom, a, 0.0), on_oval(centre, top, a, height)]
        })
        .collect();
    Mesh::hull(&points)
}

/// A hollow oval wall `height` tall standing on `centre`: the outer surface has half-axes
/// `bottom` at the base and `top` at the top, and the wall is `wall` thick. Made of
/// `segments` convex sectors.
pub fn oval_wall(
    centre: Point3,
    height: Real,
    bottom: (Real, Real),
    top: (Real, Real),
    wall: Real,
    segments: u32,
) -> Mesh {
    let step = std::f32::consts::TAU / segments as Real;
    let inset = |r: (Real, Real)| (r.0 - wall, r.1 - wall);
    Mesh::union((0..segments).map(|i| {
        let ends = [i as Real * step, (i + 1) as Real * step];
        let points: Vec<Point3> = ends
            .iter()
            .flat_map(|&a| {
                [
                    on_oval(centre, bottom, a, 0.0),
                    on_oval(centre, inset(bottom), a, 0.0),
                    on_oval(centre, top, a, height),
                    on_oval(centre, inset(top), a, height),
                ]
            })
            .collect();
        Mesh::hull(&points)
    }))
}
