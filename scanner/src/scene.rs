//! A posed object as one triangle mesh with parry3d's BVH, for ray casting: which link a
//! ray hits first, how far along it, and from which side.

use pairs::math::{Isometry3, Point3, Real, Vector3};
use parry3d::query::{Ray, RayCast};
use parry3d::shape::{FeatureId, TriMesh};

use articulated::objects::ArticulatedObject;

/// Why a scene cannot be built.
#[derive(Debug, thiserror::Error, PartialEq)]
#[non_exhaustive]
pub enum SceneError {
    /// The object has no triangles, or parry refused its mesh.
    #[error("cannot build the ray-casting mesh: {0}")]
    Mesh(String),
}

/// The first surface a ray meets.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// Distance along the (unit) ray, object units.
    pub distance: Real,
    /// Link of the triangle hit.
    pub link: usize,
    /// Cosine between the surface normal and the direction back to the ray's origin; near 1
    /// facing the ray, near 0 at grazing angles.
    pub facing: Real,
    /// Whether the ray met the triangle's back (inside a link's surface).
    pub back: bool,
    /// Unit normal of the triangle hit (object frame), turned towards the ray's origin.
    pub normal: Vector3,
}

/// All links of an object in one articulation state and pose.
pub struct PosedScene {
    mesh: TriMesh,
    poses: Vec<Isometry3>,
    link_of_triangle: Vec<u32>,
    min: Point3,
    max: Point3,
}

impl PosedScene {
    /// The object's links placed by `poses` (rest frame to object frame), one link per pose.
    pub fn new(object: &ArticulatedObject, poses: &[Isometry3]) -> Result<Self, SceneError> {
        let mut vertices = Vec::new();
        let mut triangles = Vec::new();
        let mut link_of_triangle = Vec::new();
        for (link, (l, pose)) in object.links.iter().zip(poses).enumerate() {
            let first = vertices.len() as u32;
            vertices.extend(l.mesh.vertices.iter().map(|v| pose * v));
            triangles.extend(l.mesh.triangles.iter().map(|t| t.map(|i| i + first)));
            link_of_triangle.extend(std::iter::repeat_n(link as u32, l.mesh.triangles.len()));
        }
        let (min, max) =
            pairs::math::bounds(&vertices).unwrap_or((Point3::origin(), Point3::origin()));
        let mesh =
            TriMesh::new(vertices, triangles).map_err(|e| SceneError::Mesh(e.to_string()))?;
        Ok(Self { mesh, poses: poses.to_vec(), link_of_triangle, min, max })
    }

    /// Centre of the posed object's bounding box.
    pub fn centre(&self) -> Point3 {
        nalgebra::center(&self.min, &self.max)
    }

    /// Diagonal of the posed object's bounding box, object units.
    pub fn diagonal(&self) -> Real {
        (self.max - self.min).norm()
    }

    /// Pose of every link (rest frame to object frame) in this state.
    pub fn poses(&self) -> &[Isometry3] {
        &self.poses
    }

    /// The eight corners of the bounding box.
    pub fn corners(&self) -> [Point3; 8] {
        box_corners(&self.min, &self.max)
    }

    /// The first surface the ray from `origin` along the unit `direction` meets within
    /// `max_distance`.
    pub fn cast(&self, origin: &Point3, direction: &Vector3, max_distance: Real) -> Option<Hit> {
        let ray = Ray::new(*origin, *direction);
        let hit = self.mesh.cast_local_ray_and_get_normal(&ray, max_distance, false)?;
        let triangles = self.link_of_triangle.len() as u32;
        let FeatureId::Face(face) = hit.feature else {
            return None;
        };
        let (triangle, back) =
            if face >= triangles { (face - triangles, true) } else { (face, false) };
        let facing = -hit.normal.dot(direction);
        Some(Hit {
            distance: hit.time_of_impact,
            link: self.link_of_triangle[triangle as usize] as usize,
            facing,
            back,
            normal: if facing < 0.0 { -hit.normal } else { hit.normal },
        })
    }
}

/// The eight corners of the box from `min` to `max`, corner `i` taking the upper bound on
/// axis `a` when bit `a` of `i` is set.
pub fn box_corners(min: &Point3, max: &Point3) -> [Point3; 8] {
    std::array::from_fn(|i| {
        let pick = |bit: usize, lo: Real, hi: Real| if i >> bit & 1 == 0 { lo } else { hi };
        Point3::new(pick(0, min.x, max.x), pick(1, min.y, max.y), pick(2, min.z, max.z))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use articulated::mesh::Mesh;
    use articulated::objects::Link;

    #[test]
    fn rays_hit_the_right_link_at_the_right_distance() {
        let cube = |x: Real| Mesh::cuboid(Point3::new(x, 0.0, 0.0), Point3::new(x + 1.0, 1.0, 1.0));
        let mut object = ArticulatedObject::new("test", Link { name: "a".into(), mesh: cube(0.0) });
        object.links.push(Link { name: "b".into(), mesh: cube(2.0) });
        let shifted = Isometry3::translation(0.0, 0.0, 1.0);
        let scene = PosedScene::new(&object, &[Isometry3::identity(), shifted]).expect("scene");
        let down = -Vector3::z();
        let hit = scene.cast(&Point3::new(2.5, 0.5, 5.0), &down, 10.0).expect("hits b");
        assert_eq!(hit.link, 1);
        assert!((hit.distance - 3.0).abs() < 1e-5 && !hit.back && (hit.facing - 1.0).abs() < 1e-5);
        let hit = scene.cast(&Point3::new(0.5, 0.5, 5.0), &down, 10.0).expect("hits a");
        assert_eq!((hit.link, hit.distance), (0, 4.0));
        assert!(scene.cast(&Point3::new(1.5, 0.5, 5.0), &down, 10.0).is_none());
        assert!((scene.diagonal() - (9.0f32 + 1.0 + 4.0).sqrt()).abs() < 1e-5);
    }
}
