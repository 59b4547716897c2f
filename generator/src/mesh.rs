//! Triangle meshes and the primitives the procedural objects are built from.

use pairs::math::{Isometry3, Point3, Real, UnitQuaternion, Vector3};
use parry3d::shape::{Cuboid, Cylinder};

/// An indexed triangle mesh in one frame.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions.
    pub vertices: Vec<Point3>,
    /// Triangles as indices into `vertices`, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
}

impl Mesh {
    /// An axis-aligned box spanning two opposite corners.
    pub fn cuboid(min: Point3, max: Point3) -> Self {
        let centre = nalgebra::center(&min, &max);
        Self::oriented_cuboid(
            &Isometry3::translation(centre.x, centre.y, centre.z),
            (max - min) * 0.5,
        )
    }

    /// A box with the given half extents, placed by `pose`.
    pub fn oriented_cuboid(pose: &Isometry3, half_extents: Vector3) -> Self {
        let (vertices, triangles) = Cuboid::new(half_extents.abs()).to_trimesh();
        Self { vertices, triangles }.transformed(pose)
    }

    /// A closed cylinder from `a` to `b` with `segments` sides.
    pub fn cylinder(a: Point3, b: Point3, radius: Real, segments: u32) -> Self {
        let axis = b - a;
        let (vertices, triangles) = Cylinder::new(axis.norm() * 0.5, radius).to_trimesh(segments);
        // parry's cylinder runs along y; turn y onto the axis (half a turn if they oppose).
        let rotation =
            UnitQuaternion::rotation_between(&Vector3::y(), &axis).unwrap_or_else(|| {
                UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f32::consts::PI)
            });
        let centre = nalgebra::center(&a, &b);
        Self { vertices, triangles }
            .transformed(&Isometry3::from_parts(centre.coords.into(), rotation))
    }

    /// A ring of `segments` boxes around `centre` in the plane normal to z, the way a
    /// handle loop is drawn: `radius` to the tube's centre line, `tube` its half thickness.
    pub fn ring(centre: Point3, radius: Real, tube: Real, segments: u32) -> Self {
        let mut mesh = Self::default();
        let step = std::f32::consts::TAU / segments as Real;
        let half_chord = radius * (step * 0.5).tan() + tube;
        for i in 0..segments {
            let angle = i as Real * step;
            let pose = Isometry3::new(
                centre.coords + Vector3::new(angle.cos(), angle.sin(), 0.0) * radius,
                Vector3::z() * angle,
            );
            mesh.append(Self::oriented_cuboid(&pose, Vector3::new(tube, half_chord, tube)));
        }
        mesh
    }

    /// Adds another mesh's triangles to this one.
    pub fn append(&mut self, other: Mesh) {
        let offset = self.vertices.len() as u32;
        self.vertices.extend(other.vertices);
        self.triangles.extend(other.triangles.into_iter().map(|t| t.map(|i| i + offset)));
    }

    /// Joins several meshes into one.
    pub fn union(parts: impl IntoIterator<Item = Mesh>) -> Self {
        let mut mesh = Self::default();
        parts.into_iter().for_each(|m| mesh.append(m));
        mesh
    }

    /// The mesh with every vertex moved by `pose`.
    pub fn transformed(mut self, pose: &Isometry3) -> Self {
        self.vertices.iter_mut().for_each(|v| *v = pose * *v);
        self
    }

    /// The three corners of triangle `i`.
    pub fn corners(&self, i: usize) -> [Point3; 3] {
        self.triangles[i].map(|v| self.vertices[v as usize])
    }

    /// Total surface area.
    pub fn area(&self) -> Real {
        (0..self.triangles.len()).map(|i| triangle_area(&self.corners(i))).sum()
    }
}

/// Area of a triangle.
pub fn triangle_area([a, b, c]: &[Point3; 3]) -> Real {
    (b - a).cross(&(c - a)).norm() * 0.5
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn primitives_have_their_analytic_areas() {
        let cube = Mesh::cuboid(Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 2.0, 3.0));
        assert!((cube.area() - 22.0).abs() < 1e-4);
        let cyl = Mesh::cylinder(Point3::origin(), Point3::new(0.0, 0.0, 2.0), 0.5, 64);
        let exact = std::f32::consts::TAU * 0.5 * 2.0 + 2.0 * std::f32::consts::PI * 0.25;
        assert!((cyl.area() - exact).abs() / exact < 0.01);
        let ends = cyl
            .vertices
            .iter()
            .map(|v| v.z)
            .fold((f32::MAX, f32::MIN), |(lo, hi), z| (lo.min(z), hi.max(z)));
        assert!(ends.0.abs() < 1e-5 && (ends.1 - 2.0).abs() < 1e-5);
    }
}
