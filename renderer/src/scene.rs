//! The renderer's posed object: every link's triangles in one compressed 8-wide BVH
//! (`obvhs`, triangles stored in leaf order), cast against one primary ray per pixel after
//! a bounding-box test. The scanner keeps parry's
//! ([`scanner::scene::PosedScene`]) so that datasets stay byte-identical; the two agree
//! on which rays hit (generator/benches/open3d_raycast.py counts the same hits for both and
//! for Open3D).

use glam::Vec3A;
use obvhs::cwbvh::builder::build_cwbvh_from_tris;
use obvhs::cwbvh::CwBvh;
use obvhs::ray::{Ray, RayHit};
use obvhs::triangle::Triangle;
use obvhs::BvhBuildParams;
use pairs::math::{Isometry3, Point3, Real, Vector3};

use articulated::objects::ArticulatedObject;
use scanner::scene::{Hit, SceneError};

/// All links of an object in one articulation state, for ray casting.
pub struct RenderScene {
    bvh: CwBvh,
    triangles: Vec<Triangle>,
    link_of_triangle: Vec<u32>,
    poses: Vec<Isometry3>,
    min: Point3,
    max: Point3,
}

fn glam(p: &Point3) -> Vec3A {
    Vec3A::new(p.x, p.y, p.z)
}

impl RenderScene {
    /// The object's links placed by `poses` (rest frame to object frame).
    pub fn new(object: &ArticulatedObject, poses: &[Isometry3]) -> Result<Self, SceneError> {
        let mut triangles = Vec::new();
        let mut link_of_triangle = Vec::new();
        let mut placed_all = Vec::new();
        for (link, (l, pose)) in object.links.iter().zip(poses).enumerate() {
            let placed: Vec<Point3> = l.mesh.vertices.iter().map(|v| pose * v).collect();
            for p in &placed {
                if !p.coords.iter().all(|c| c.is_finite()) {
                    return Err(SceneError::Mesh(format!(
                        "link {} has a non-finite vertex",
                        l.name
                    )));
                }
            }
            for t in &l.mesh.triangles {
                let [a, b, c] = t.map(|i| glam(&placed[i as usize]));
                triangles.push(Triangle { v0: a, v1: b, v2: c });
                link_of_triangle.push(link as u32);
            }
            placed_all.extend(placed);
        }
        let (min, max) =
            pairs::math::bounds(&placed_all).unwrap_or((Point3::origin(), Point3::origin()));
        if triangles.is_empty() {
            return Err(SceneError::Mesh("the object has no triangles".into()));
        }
        let bvh = build_cwbvh_from_tris(
            &triangles,
            BvhBuildParams::medium_build(),
            &mut Default::default(),
        );
        // Triangles in the BVH's primitive order, so a leaf's primitive index is the
        // triangle's (one indirection less per test).
        let order = &bvh.primitive_indices;
        let triangles: Vec<Triangle> = order.iter().map(|&i| triangles[i as usize]).collect();
        let link_of_triangle: Vec<u32> =
            order.iter().map(|&i| link_of_triangle[i as usize]).collect();
        Ok(Self { bvh, triangles, link_of_triangle, poses: poses.to_vec(), min, max })
    }

    /// Centre of the posed object's bounding box.
    pub fn centre(&self) -> Point3 {
        nalgebra::center(&self.min, &self.max)
    }

    /// Diagonal of the posed object's bounding box.
    pub fn diagonal(&self) -> Real {
        (self.max - self.min).norm()
    }

    /// The eight corners of the bounding box.
    pub fn corners(&self) -> [Point3; 8] {
        scanner::scene::box_corners(&self.min, &self.max)
    }

    /// Whether the ray can meet the bounding box within `max_distance` (slab test; a ray
    /// that misses the box, as most of an image's rays do, skips the BVH).
    fn box_hit(&self, origin: &Point3, direction: &Vector3, max_distance: Real) -> bool {
        let (mut near, mut far) = (0.0 as Real, max_distance);
        for a in 0..3 {
            let inverse = 1.0 / direction[a];
            let (t0, t1) =
                ((self.min[a] - origin[a]) * inverse, (self.max[a] - origin[a]) * inverse);
            // A NaN (a ray in the slab's plane) leaves the interval as it was.
            near = near.max(t0.min(t1));
            far = far.min(t0.max(t1));
        }
        // A little slack for rounding at the box's faces, where triangles lie.
        near <= far + 1e-5 * (1.0 + far.abs())
    }

    /// Pose of every link in this state.
    pub fn poses(&self) -> &[Isometry3] {
        &self.poses
    }

    /// The first surface the ray from `origin` along the unit `direction` meets within
    /// `max_distance`.
    pub fn cast(&self, origin: &Point3, direction: &Vector3, max_distance: Real) -> Option<Hit> {
        if !self.box_hit(origin, direction, max_distance) {
            return None;
        }
        let ray = Ray::new(
            glam(origin),
            Vec3A::new(direction.x, direction.y, direction.z),
            0.0,
            max_distance,
        );
        let mut hit = RayHit::none();
        let found =
            self.bvh.ray_traverse(ray, &mut hit, |ray, id| self.triangles[id].intersect(ray));
        if !found {
            return None;
        }
        let triangle = hit.primitive_id as usize;
        let n = self.triangles[triangle].compute_normal();
        let normal = Vector3::new(n.x, n.y, n.z);
        let facing = -normal.dot(direction);
        Some(Hit {
            distance: hit.t,
            link: self.link_of_triangle[triangle] as usize,
            facing,
            back: facing < 0.0,
            normal: if facing < 0.0 { -normal } else { normal },
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use articulated::mesh::Mesh;
    use articulated::objects::Link;
    use scanner::scene::PosedScene;

    #[test]
    fn hits_agree_with_the_scanners_ray_caster() {
        let cube = |x: Real| Mesh::cuboid(Point3::new(x, 0.0, 0.0), Point3::new(x + 1.0, 1.0, 1.0));
        let mut object = ArticulatedObject::new("test", Link { name: "a".into(), mesh: cube(0.0) });
        object.links.push(Link { name: "b".into(), mesh: cube(2.0) });
        let poses = [Isometry3::identity(), Isometry3::translation(0.0, 0.0, 1.0)];
        let ours = RenderScene::new(&object, &poses).expect("scene");
        let parry = PosedScene::new(&object, &poses).expect("scene");
        let origin = Point3::new(1.3, 0.4, 6.0);
        for i in 0..400 {
            let (a, b) = ((i % 20) as Real / 19.0, (i / 20) as Real / 19.0);
            // Offsets that keep every ray off the cubes' edges, where either face is right.
            let d = pairs::math::unit_or(
                &Vector3::new(-0.4871 + 2.0 * a, -0.3913 + 1.2 * b, -4.0),
                Vector3::z(),
            );
            match (ours.cast(&origin, &d, 20.0), parry.cast(&origin, &d, 20.0)) {
                (Some(x), Some(y)) => {
                    assert_eq!(x.link, y.link);
                    assert!((x.distance - y.distance).abs() < 1e-4);
                    assert!(
                        (x.normal - y.normal).norm() < 1e-4 && (x.facing - y.facing).abs() < 1e-4,
                        "ray {i}: {x:?} vs {y:?}"
                    );
                }
                (None, None) => {}
                (x, y) => panic!("ray {i}: {x:?} vs {y:?}"),
            }
        }
        assert_eq!(ours.corners(), parry.corners());
    }
}
