//! Area-weighted uniform sampling of an object's surface.

use pairs::math::{Isometry3, Point3};
use pairs::sampling::{point_on_triangle, triangle_area, AreaSampler};

use crate::objects::ArticulatedObject;
use crate::seed::Rng;

/// A sampled surface point: its link and its position in the rest frame, so that it can be
/// placed in any articulation state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    /// Index of the link it lies on.
    pub link: usize,
    /// Position in the object's rest frame.
    pub rest: Point3,
}

impl SurfacePoint {
    /// The point's position for the given link poses.
    pub fn posed(&self, poses: &[Isometry3]) -> Point3 {
        poses[self.link] * self.rest
    }
}

/// Draws points uniformly by area over all links of an object ([`AreaSampler`] over every
/// triangle of every link). Areas do not change with the articulation, so one sampler
/// serves every state.
#[derive(Debug, Clone)]
pub struct SurfaceSampler {
    /// (link, triangle) of each triangle of the object, in link order.
    triangles: Vec<(usize, usize)>,
    /// Draws an index into `triangles` by area.
    areas: AreaSampler,
}

impl SurfaceSampler {
    /// Builds the area table of an object.
    pub fn new(object: &ArticulatedObject) -> Self {
        let triangles: Vec<(usize, usize)> = object
            .links
            .iter()
            .enumerate()
            .flat_map(|(link, l)| (0..l.mesh.triangles.len()).map(move |t| (link, t)))
            .collect();
        let areas = AreaSampler::new(
            triangles.iter().map(|&(link, t)| triangle_area(&object.links[link].mesh.corners(t))),
        );
        Self { triangles, areas }
    }

    /// Total surface area, rest frame units squared.
    pub fn total_area(&self) -> f64 {
        self.areas.total_area()
    }

    /// Draws `n` points; empty if the object has no area (no draw is then made).
    pub fn sample(&self, object: &ArticulatedObject, n: usize, rng: &mut Rng) -> Vec<SurfacePoint> {
        (0..n)
            .filter_map(|_| {
                let (link, t) = self.triangles[self.areas.draw(rng)?];
                let rest = point_on_triangle(rng, object.links[link].mesh.corners(t));
                Some(SurfacePoint { link, rest })
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Mesh;
    use crate::objects::Link;
    use crate::seed::{rng_for, Stream};

    #[test]
    fn samples_split_by_area_and_lie_on_the_surface() {
        let small = Mesh::cuboid(Point3::origin(), Point3::new(1.0, 1.0, 1.0));
        let big = Mesh::cuboid(Point3::new(2.0, 0.0, 0.0), Point3::new(4.0, 2.0, 2.0));
        let mut obj = ArticulatedObject::new("t", Link { name: "small".into(), mesh: small });
        obj.links.push(Link { name: "big".into(), mesh: big });
        let sampler = SurfaceSampler::new(&obj);
        assert!((sampler.total_area() - 30.0).abs() < 1e-4);
        let pts = sampler.sample(&obj, 6000, &mut rng_for(1, 0, Stream::Pair(0)));
        let on_big = pts.iter().filter(|p| p.link == 1).count() as f64 / 6000.0;
        assert!((on_big - 0.8).abs() < 0.03, "{on_big}");
        for p in &pts {
            let q = if p.link == 0 {
                p.rest.coords
            } else {
                (p.rest.coords - pairs::math::Vector3::new(2.0, 0.0, 0.0)) / 2.0
            };
            let on_face = q.iter().any(|c| c.abs() < 1e-5 || (c - 1.0).abs() < 1e-5);
            assert!(on_face && q.iter().all(|c| (-1e-5..=1.0 + 1e-5).contains(c)), "{q:?}");
        }
    }
}
