//! Rotors: a hub with evenly spaced, pitched blades, for fans and windmills.

use pairs::math::{Isometry3, Point3, Real, UnitQuaternion, Vector3};

use crate::mesh::Mesh;

/// The shape of a rotor, in object units and radians.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rotor {
    /// Number of blades.
    pub blades: u32,
    /// Radius of the hub.
    pub hub_radius: Real,
    /// Length of the hub along the rotor axis.
    pub hub_length: Real,
    /// Distance from the axis to the blade tips.
    pub radius: Real,
    /// Chord of a blade at its root, by the hub.
    pub root_chord: Real,
    /// Chord of a blade at its tip.
    pub tip_chord: Real,
    /// Thickness of a blade.
    pub thickness: Real,
    /// Angle between a blade's chord and the rotor plane.
    pub pitch: Real,
}

impl Rotor {
    /// The rotor centred on `centre`, turning about the z axis (its blades in the plane
    /// normal to z): a hub cylinder, a nose cone in front, and one convex blade per step.
    pub fn mesh(&self, centre: Point3) -> Mesh {
        let half = 0.5 * self.hub_length;
        let hub = Mesh::cylinder(
            Point3::new(0.0, 0.0, -half),
            Point3::new(0.0, 0.0, half),
            self.hub_radius,
            12,
        );
        let nose = Mesh::frustum(
            Point3::new(0.0, 0.0, half),
            Point3::new(0.0, 0.0, half + self.hub_radius),
            self.hub_radius,
            0.3 * self.hub_radius,
            12,
        );
        let step = std::f32::consts::TAU / self.blades as Real;
        let blades = (0..self.blades).map(|k| {
            let turn = Isometry3::rotation(Vector3::z() * (k as Real * step));
            self.blade().transformed(&turn)
        });
        Mesh::union([hub, nose].into_iter().chain(blades))
            .transformed(&Isometry3::translation(centre.x, centre.y, centre.z))
    }

    /// One blade along +x, its root inside the hub.
    fn blade(&self) -> Mesh {
        // Chord and thickness directions, turned from the rotor plane by the pitch.
        let pitch = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), self.pitch);
        let (chord, across) = (pitch * Vector3::y(), pitch * Vector3::z());
        let section = |x: Real, c: Real| {
            [-1.0, 1.0].into_iter().flat_map(move |s| {
                [-1.0, 1.0].into_iter().map(move |t| {
                    Point3::new(x, 0.0, 0.0)
                        + chord * (0.5 * s * c)
                        + across * (0.5 * t * self.thickness)
                })
            })
        };
        let points: Vec<Point3> = section(0.8 * self.hub_radius, self.root_chord)
            .chain(section(self.radius, self.tip_chord))
            .collect();
        Mesh::hull(&points)
    }
}
