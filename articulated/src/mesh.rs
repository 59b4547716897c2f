//! Triangle meshes and the convex primitives the procedural objects are built from.
//!
//! Every primitive is convex, and a mesh remembers which vertices form each primitive
//! (its convex pieces), so that plausibility checks (`crate::check`) can measure gaps and
//! interpenetration between links exactly, with convex queries, instead of guessing from
//! a non-manifold union of triangles.

use pairs::math::{Isometry3, Point3, Real, UnitQuaternion, Vector3};
use parry3d::shape::{Ball, Cuboid, Cylinder};

/// An indexed triangle mesh in one frame, made of convex pieces.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions.
    pub vertices: Vec<Point3>,
    /// Triangles as indices into `vertices`, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
    /// First vertex of each convex piece; a piece's vertices run to the next piece's start.
    pub pieces: Vec<u32>,
}

impl Mesh {
    /// One convex piece from its vertices and triangles.
    fn piece(vertices: Vec<Point3>, triangles: Vec<[u32; 3]>) -> Self {
        Self { vertices, triangles, pieces: vec![0] }
    }

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
        Self::piece(vertices, triangles).transformed(pose)
    }

    /// A box from `a` to `b` (the centres of its two end faces) with a `width` x `height`
    /// cross-section; `up` picks the direction of `height` (it need not be orthogonal to
    /// the box's axis, only not parallel to it). The way beams, legs and arms are drawn.
    pub fn beam(a: Point3, b: Point3, width: Real, height: Real, up: Vector3) -> Self {
        let axis = b - a;
        // A right-handed frame (side, up, axis): side = up x axis, up = axis x side.
        let side = up.cross(&axis);
        let up = axis.cross(&side);
        let [side, up, along] = match [side, up, axis].map(|v| pairs::math::try_unit(&v)) {
            [Some(side), Some(up), Some(along)] => [side, up, along],
            // A zero-length beam, or `up` along the axis: any right-handed frame about the
            // axis (about z for a zero-length beam, which is drawn as a flat box).
            _ => {
                let along = pairs::math::unit_or(&axis, Vector3::z());
                let side = pairs::math::perpendicular(&along);
                [side, along.cross(&side), along]
            }
        };
        let frame = nalgebra::Matrix3::from_columns(&[side, up, along]);
        let rotation = UnitQuaternion::from_rotation_matrix(
            &nalgebra::Rotation3::from_matrix_unchecked(frame),
        );
        let centre = nalgebra::center(&a, &b);
        Self::oriented_cuboid(
            &Isometry3::from_parts(centre.coords.into(), rotation),
            Vector3::new(width * 0.5, height * 0.5, axis.norm() * 0.5),
        )
    }

    /// A closed cylinder from `a` to `b` with `segments` sides.
    pub fn cylinder(a: Point3, b: Point3, radius: Real, segments: u32) -> Self {
        let axis = b - a;
        let (vertices, triangles) = Cylinder::new(axis.norm() * 0.5, radius).to_trimesh(segments);
        Self::piece(vertices, triangles).transformed(&along(a, b))
    }

    /// A truncated cone from `a` (radius `radius_a`) to `b` (radius `radius_b`); a radius of
    /// zero gives a cone.
    pub fn frustum(a: Point3, b: Point3, radius_a: Real, radius_b: Real, segments: u32) -> Self {
        let half = (b - a).norm() * 0.5;
        let step = std::f32::consts::TAU / segments as Real;
        let ring = |y: Real, r: Real| {
            (0..segments).map(move |i| {
                let angle = i as Real * step;
                Point3::new(r * angle.cos(), y, r * angle.sin())
            })
        };
        let points: Vec<Point3> =
            ring(-half, radius_a.max(1e-5)).chain(ring(half, radius_b.max(1e-5))).collect();
        Self::hull(&points).transformed(&along(a, b))
    }

    /// A sphere of `radius` around `centre`, with `segments` meridians.
    pub fn sphere(centre: Point3, radius: Real, segments: u32) -> Self {
        let (vertices, triangles) = Ball::new(radius).to_trimesh(segments, segments / 2 + 1);
        Self::piece(vertices, triangles)
            .transformed(&Isometry3::translation(centre.x, centre.y, centre.z))
    }

    /// The convex hull of `points`: wedges, tapered blades and other convex pieces.
    pub fn hull(points: &[Point3]) -> Self {
        let (vertices, triangles) = parry3d::transformation::convex_hull(points);
        Self::piece(vertices, triangles)
    }

    /// A ring of `segments` boxes around `centre` in the plane normal to z, the way a
    /// handle loop is drawn: `radius` to the tube's centre line, `tube` its half thickness.
    pub fn ring(centre: Point3, radius: Real, tube: Real, segments: u32) -> Self {
        Self::arc(centre, radius, tube, (0.0, std::f32::consts::TAU), segments)
    }

    /// Part of a ring: boxes around `centre` in the plane normal to z from angle
    /// `angles.0` to `angles.1` (radians, from +x towards +y).
    pub fn arc(
        centre: Point3,
        radius: Real,
        tube: Real,
        angles: (Real, Real),
        segments: u32,
    ) -> Self {
        let step = (angles.1 - angles.0) / segments as Real;
        let half_chord = radius * (step.abs() * 0.5).tan() + tube;
        Self::union((0..segments).map(|i| {
            let angle = angles.0 + (i as Real + 0.5) * step;
            let pose = Isometry3::new(
                centre.coords + Vector3::new(angle.cos(), angle.sin(), 0.0) * radius,
                Vector3::z() * angle,
            );
            Self::oriented_cuboid(&pose, Vector3::new(tube, half_chord, tube))
        }))
    }

    /// Adds another mesh's triangles and pieces to this one.
    pub fn append(&mut self, other: Mesh) {
        let offset = self.vertices.len() as u32;
        self.vertices.extend(other.vertices);
        self.triangles.extend(other.triangles.into_iter().map(|t| t.map(|i| i + offset)));
        self.pieces.extend(other.pieces.into_iter().map(|p| p + offset));
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

    /// The mesh mirrored through the plane x = 0 (triangles re-wound to face outwards).
    pub fn mirrored_x(mut self) -> Self {
        self.vertices.iter_mut().for_each(|v| v.x = -v.x);
        self.triangles.iter_mut().for_each(|t| t.swap(1, 2));
        self
    }

    /// The vertices of each convex piece.
    pub fn convex_pieces(&self) -> impl Iterator<Item = &[Point3]> {
        let ends = self.pieces.iter().skip(1).copied().chain([self.vertices.len() as u32]);
        self.pieces.iter().zip(ends).map(|(&s, e)| &self.vertices[s as usize..e as usize])
    }

    /// The three corners of triangle `i`.
    pub fn corners(&self, i: usize) -> [Point3; 3] {
        self.triangles[i].map(|v| self.vertices[v as usize])
    }

    /// Total surface area.
    pub fn area(&self) -> Real {
        (0..self.triangles.len()).map(|i| pairs::sampling::triangle_area(&self.corners(i))).sum()
    }
}

/// The pose that turns parry's y-aligned primitives (centred at the origin) onto the
/// segment from `a` to `b`.
fn along(a: Point3, b: Point3) -> Isometry3 {
    // Half a turn about x when the segment points down y, where `rotation_between` fails.
    let rotation = UnitQuaternion::rotation_between(&Vector3::y(), &(b - a)).unwrap_or_else(|| {
        UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f32::consts::PI)
    });
    Isometry3::from_parts(nalgebra::center(&a, &b).coords.into(), rotation)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn z_range(mesh: &Mesh) -> (Real, Real) {
        mesh.vertices.iter().fold((Real::MAX, Real::MIN), |(lo, hi), v| (lo.min(v.z), hi.max(v.z)))
    }

    #[test]
    fn primitives_have_their_analytic_areas() {
        let cube = Mesh::cuboid(Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 2.0, 3.0));
        assert!((cube.area() - 22.0).abs() < 1e-4);
        let cyl = Mesh::cylinder(Point3::origin(), Point3::new(0.0, 0.0, 2.0), 0.5, 64);
        let exact = std::f32::consts::TAU * 0.5 * 2.0 + 2.0 * std::f32::consts::PI * 0.25;
        assert!((cyl.area() - exact).abs() / exact < 0.01);
        let ends = z_range(&cyl);
        assert!(ends.0.abs() < 1e-5 && (ends.1 - 2.0).abs() < 1e-5);
        let ball = Mesh::sphere(Point3::new(1.0, 0.0, 0.0), 0.5, 48);
        let exact = 4.0 * std::f32::consts::PI * 0.25;
        assert!((ball.area() - exact).abs() / exact < 0.02, "{}", ball.area());
        let cone = Mesh::frustum(Point3::origin(), Point3::new(0.0, 0.0, 1.0), 1.0, 0.0, 64);
        let exact = std::f32::consts::PI * (1.0 + 2f32.sqrt());
        assert!((cone.area() - exact).abs() / exact < 0.01, "{}", cone.area());
        assert_eq!(z_range(&cone), (0.0, 1.0));
    }

    #[test]
    fn beams_span_their_end_points() {
        let a = Point3::new(0.0, 0.0, 0.0);
        let b = Point3::new(1.0, 1.0, 0.0);
        let beam = Mesh::beam(a, b, 0.1, 0.2, Vector3::z());
        let exact = 2.0 * (0.1 * 0.2) + 2.0 * 2f32.sqrt() * (0.1 + 0.2);
        assert!((beam.area() - exact).abs() < 1e-4, "{}", beam.area());
        assert!((z_range(&beam).1 - 0.1).abs() < 1e-5);
        // `up` along the axis has no frame of its own: the beam is still whole and finite.
        let upright = Mesh::beam(a, Point3::new(0.0, 0.0, 2.0), 0.1, 0.2, Vector3::z());
        assert!(upright.vertices.iter().all(|v| v.coords.iter().all(|c| c.is_finite())));
        assert!((upright.area() - (2.0 * 0.1 * 0.2 + 2.0 * 2.0 * 0.3)).abs() < 1e-4);
        assert_eq!(z_range(&upright), (0.0, 2.0));
    }

    #[test]
    fn unions_keep_their_convex_pieces() {
        let ring = Mesh::ring(Point3::origin(), 1.0, 0.1, 12);
        assert_eq!(ring.convex_pieces().count(), 12);
        assert!(ring.convex_pieces().all(|p| p.len() == 8));
        let both = Mesh::union([ring, Mesh::sphere(Point3::origin(), 0.5, 8)]);
        assert_eq!(both.convex_pieces().count(), 13);
        assert_eq!(both.convex_pieces().map(<[_]>::len).sum::<usize>(), both.vertices.len());
    }
}
