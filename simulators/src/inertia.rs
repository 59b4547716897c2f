//! Mass, centre of mass and inertia of an exported link, from its geometry and a density.
//!
//! - A link whose mesh is closed (every piece watertight and consistently oriented, as
//!   every built-in piece is) gets the exact mass properties of the solid the mesh
//!   encloses, at `density` ([`parry3d::mass_properties::MassProperties::from_trimesh`];
//!   pieces that overlap count twice, as the generator's own volume does).
//! - A link with an open or non-manifold piece encloses no well-defined volume (the
//!   integral would depend on the origin): it gets the mass properties of its collision
//!   hulls instead ([`crate::collision`]), and says so ([`MassSource::Hulls`]).
//!
//! Every principal moment is at least [`MIN_MOMENT_FRACTION`] of the largest, so that a
//! flat link still has a positive-definite inertia that simulators accept.

use pairs::math::{Point3, Real, UnitQuaternion};
use parry3d::mass_properties::MassProperties;
use serde::Serialize;

use crate::collision::Hull;
use articulated::mesh::Mesh;

/// Default density, kilograms per cubic object unit (the built-in categories are modelled
/// at real-world sizes in metres: 500 kg/m³ is a light wood or a plastic).
pub const DEFAULT_DENSITY: f64 = 500.0;

/// Smallest principal moment, as a fraction of the largest.
pub const MIN_MOMENT_FRACTION: f64 = 1e-4;

/// Where a link's mass properties came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum MassSource {
    /// The closed visual mesh (exact).
    Mesh,
    /// The collision hulls (the visual mesh is open).
    Hulls,
}

/// A link's mass properties in the object's rest frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inertial {
    /// Mass, kilograms.
    pub mass: f64,
    /// Centre of mass, rest frame.
    pub com: Point3,
    /// Principal moments of inertia about the centre of mass.
    pub principal: [f64; 3],
    /// Rotation from the principal axes to the object's axes.
    pub principal_frame: UnitQuaternion,
    /// Where they came from.
    pub source: MassSource,
}

impl Inertial {
    /// The inertia tensor about the centre of mass, in the object's axes (row-major).
    pub fn tensor(&self) -> [[f64; 3]; 3] {
        let r = self.principal_frame.to_rotation_matrix().into_inner().cast::<f64>();
        let d = nalgebra::Matrix3::from_diagonal(&nalgebra::Vector3::from(self.principal));
        let m = r * d * r.transpose();
        std::array::from_fn(|i| std::array::from_fn(|j| 0.5 * (m[(i, j)] + m[(j, i)])))
    }
}

/// The mass properties of a link with `mesh` and collision `hulls`, at `density`; `closed`
/// tells whether every piece of the mesh is closed.
pub fn inertial(mesh: &Mesh, closed: bool, hulls: &[Hull], density: f64) -> Inertial {
    let rho = density as Real;
    let from_mesh = closed
        .then(|| MassProperties::from_trimesh(rho, &mesh.vertices, &mesh.triangles))
        .filter(|m| m.mass() > 0.0 && m.mass().is_finite());
    let (props, source) = match from_mesh {
        Some(m) => (m, MassSource::Mesh),
        None => {
            let sum = hulls
                .iter()
                .map(|h| MassProperties::from_convex_polyhedron(rho, &h.vertices, &h.triangles))
                .fold(MassProperties::default(), |a, b| a + b);
            (sum, MassSource::Hulls)
        }
    };
    let principal = props.principal_inertia();
    let largest = principal.iter().fold(0.0f64, |m, &x| m.max(f64::from(x)));
    let floor = (largest * MIN_MOMENT_FRACTION).max(1e-12);
    Inertial {
        mass: f64::from(props.mass()).max(1e-9),
        com: props.local_com,
        principal: std::array::from_fn(|k| f64::from(principal[k]).max(floor)),
        principal_frame: props.principal_inertia_local_frame,
        source,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_box_has_the_textbook_inertia() {
        // 1 x 2 x 3 at density 2: mass 12, I = m/12 (b^2 + c^2) about each axis.
        let mesh = Mesh::cuboid(Point3::new(1.0, 1.0, 1.0), Point3::new(2.0, 3.0, 4.0));
        let i = inertial(&mesh, true, &[], 2.0);
        assert_eq!(i.source, MassSource::Mesh);
        assert!((i.mass - 12.0).abs() < 1e-4, "{i:?}");
        assert!((i.com - Point3::new(1.5, 2.0, 2.5)).norm() < 1e-5);
        let t = i.tensor();
        let expected = [12.0 / 12.0 * 13.0, 12.0 / 12.0 * 10.0, 12.0 / 12.0 * 5.0];
        for k in 0..3 {
            assert!((t[k][k] - expected[k]).abs() < 1e-3, "{t:?}");
            assert!(t[k][(k + 1) % 3].abs() < 1e-3, "{t:?}");
        }
    }

    #[test]
    fn an_open_mesh_takes_its_hulls() {
        let mut mesh = Mesh::cuboid(Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0));
        mesh.triangles.truncate(10);
        let c = crate::collision::decompose(&mesh, Default::default());
        let i = inertial(&mesh, false, &c.hulls, 3.0);
        assert_eq!(i.source, MassSource::Hulls);
        assert!((i.mass - 3.0).abs() < 1e-4, "{i:?}");
    }
}
