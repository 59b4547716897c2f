//! Round parts built from convex wedges: flat rings (annuli) for portholes, gaskets and
//! rims, which fit together without the gaps and corners of a ring of boxes.

use pairs::math::{Point3, Real, Vector3};

use crate::mesh::Mesh;

/// A flat ring around `centre` in the plane normal to z, from radius `radii.0` to
/// `radii.1`, `depth` thick (centred on `centre.z`), as `segments` convex wedges.
pub fn annulus(centre: Point3, (inner, outer): (Real, Real), depth: Real, segments: u32) -> Mesh {
    let step = std::f32::consts::TAU / segments as Real;
    Mesh::union((0..segments).map(|i| {
        let corners: Vec<Point3> = [i, i + 1]
            .into_iter()
            .flat_map(|k| {
                let (s, c) = (k as Real * step).sin_cos();
                [inner, outer].into_iter().flat_map(move |r| {
                    [-0.5, 0.5].map(|f| centre + Vector3::new(r * c, r * s, f * depth))
                })
            })
            .collect();
        Mesh::hull(&corners)
    }))
}
