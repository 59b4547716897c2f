//! How well a link's collision hulls fit its visual mesh: volumes, and the symmetric
//! Hausdorff distance between the two surfaces, measured with exact point-to-hull
//! distances.

use pairs::math::{Point3, Real, Vector3};
use parry3d::query::PointQuery;
use parry3d::shape::{TriMesh, Triangle};
use serde::Serialize;

use crate::collision::{Hull, MAX_SAMPLES};
use articulated::mesh::Mesh;

/// A hull ready for point queries: its faces' planes and triangles. Parry's
/// `ConvexPolyhedron` point query misplaces points by millimetres on centimetre-sized hulls
/// (a scissors blade's), which would swamp the fit it measures; this is exact.
pub(crate) struct Solid {
    planes: Vec<(Vector3, Point3)>,
    triangles: Vec<Triangle>,
    tolerance: Real,
}

impl Solid {
    pub(crate) fn new(hull: &Hull) -> Self {
        let triangles: Vec<Triangle> = hull
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| hull.vertices[i as usize]);
                Triangle::new(a, b, c)
            })
            .collect();
        let planes = triangles
            .iter()
            .filter_map(|t| {
                let n = pairs::math::try_unit(&(t.b - t.a).cross(&(t.c - t.a)))?;
                Some((n, t.a))
            })
            .collect();
        let (lo, hi) =
            pairs::math::bounds(&hull.vertices).unwrap_or((Point3::origin(), Point3::origin()));
        Self { planes, triangles, tolerance: 1e-6 * (hi - lo).norm().max(Real::EPSILON) }
    }

    pub(crate) fn distance(&self, p: &Point3) -> Real {
        if self.planes.iter().all(|(n, a)| n.dot(&(p - a)) <= self.tolerance) {
            return 0.0;
        }
        self.triangles
            .iter()
            .map(|t| t.distance_to_local_point(p, false))
            .fold(Real::INFINITY, Real::min)
    }
}

/// How well a link's hulls fit its visual mesh.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Fit {
    /// Volume enclosed by the visual mesh (the sum over its closed pieces).
    pub visual_volume: f64,
    /// Sum of the hulls' volumes.
    pub hull_volume: f64,
    /// Symmetric Hausdorff distance between the visual surface and the hulls' surfaces
    /// (sampled at vertices, edge midpoints and face centres), object units.
    pub hausdorff: f64,
}

/// Points on a surface: vertices, edge midpoints and face centres.
fn surface_samples(vertices: &[Point3], triangles: &[[u32; 3]]) -> Vec<Point3> {
    let mut out = vertices.to_vec();
    for t in triangles {
        let [a, b, c] = t.map(|i| vertices[i as usize]);
        out.push(nalgebra::center(&a, &b));
        out.push(nalgebra::center(&b, &c));
        out.push(nalgebra::center(&c, &a));
        out.push(Point3::from((a.coords + b.coords + c.coords) / 3.0));
    }
    out
}

/// How well `hulls` fit `mesh`, whose closed pieces enclose `visual_volume`.
pub(crate) fn fit(mesh: &Mesh, visual_volume: f64, hulls: &[Hull]) -> Fit {
    let hull_volume = hulls.iter().map(Hull::volume).sum();
    // Visual surface to the hulls (zero inside one). At most MAX_SAMPLES samples, evenly
    // strided, bound the cost on large asset meshes.
    let samples = surface_samples(&mesh.vertices, &mesh.triangles);
    let stride = samples.len().div_ceil(MAX_SAMPLES).max(1);
    let solids: Vec<Solid> = hulls.iter().map(Solid::new).collect();
    let nearest = |p: &Point3| {
        let mut best = Real::INFINITY;
        for solid in &solids {
            best = best.min(solid.distance(p));
            if best == 0.0 {
                break;
            }
        }
        best
    };
    let outside = samples.iter().step_by(stride).map(nearest).fold(0.0, Real::max);
    // Hull surfaces to the visual surface.
    let over = TriMesh::new(mesh.vertices.clone(), mesh.triangles.clone())
        .map(|surface| {
            let samples: Vec<Point3> =
                hulls.iter().flat_map(|h| surface_samples(&h.vertices, &h.triangles)).collect();
            let stride = samples.len().div_ceil(MAX_SAMPLES).max(1);
            samples
                .iter()
                .step_by(stride)
                .map(|p| surface.distance_to_local_point(p, false))
                .fold(0.0, Real::max)
        })
        .unwrap_or(Real::NAN);
    Fit { visual_volume, hull_volume, hausdorff: f64::from(outside.max(over)) }
}
