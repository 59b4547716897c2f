//! The scanner's pinhole camera: drawn at a random viewpoint around the posed object and
//! aimed at its centre (ranges in [`ScanConfig`]).

use pairs::math::{Isometry3, Matrix3, Point3, Real, Rotation3, UnitQuaternion, Vector3};
use pairs::Intrinsics;
use rand::Rng as _;

use crate::config::ScanConfig;
use articulated::seed::Rng;

/// A pinhole camera placed in an object frame (OpenCV axes: x right, y down, z forward).
#[derive(Debug, Clone, PartialEq)]
pub struct Camera {
    /// Image size and focal lengths.
    pub intrinsics: Intrinsics,
    /// Camera frame to object frame.
    pub pose: Isometry3,
}

impl Camera {
    /// A camera at `eye` looking at `target`, with image up along the object's +y.
    pub fn look_at(intrinsics: Intrinsics, eye: &Point3, target: &Point3) -> Self {
        // An eye on the target looks along +z.
        let forward = pairs::math::unit_or(&(target - eye), Vector3::z());
        // Image down is world down made perpendicular to the viewing direction; looking
        // straight up or down, the object's -z stands in.
        let mut down = -Vector3::y() + forward * forward.y;
        if down.norm() < 1e-3 {
            down = -Vector3::z() + forward * forward.z;
        }
        // At least 1e-3 long after the fallback above, so `unit_or` never falls back here.
        let down = pairs::math::unit_or(&down, -Vector3::z());
        let right = down.cross(&forward);
        let rotation =
            Rotation3::from_matrix_unchecked(Matrix3::from_columns(&[right, down, forward]));
        let pose = Isometry3::from_parts(
            eye.coords.into(),
            UnitQuaternion::from_rotation_matrix(&rotation),
        );
        Self { intrinsics, pose }
    }

    /// A viewpoint drawn from the ranges of `config`, around a scene with bounding-box
    /// centre `centre` and diagonal `diagonal`.
    pub fn draw(config: &ScanConfig, centre: &Point3, diagonal: Real, rng: &mut Rng) -> Self {
        let intrinsics = Intrinsics::with_fov(
            config.width,
            config.height,
            (config.fov_y_deg as Real).to_radians(),
        );
        let draw = |[lo, hi]: [f64; 2], rng: &mut Rng| {
            if lo < hi {
                rng.random_range(lo..hi) as Real
            } else {
                lo as Real
            }
        };
        let azimuth = draw(config.azimuth_deg, rng).to_radians();
        let elevation = draw(config.elevation_deg, rng).to_radians();
        let factor = draw(config.distance, rng);
        let half_fov = (0.5 * config.fov_y_deg as Real)
            .to_radians()
            .min((0.5 * config.width as Real / intrinsics.fx).atan());
        let distance = factor * 0.5 * diagonal / half_fov.sin();
        let direction = Vector3::new(
            elevation.cos() * azimuth.sin(),
            elevation.sin(),
            elevation.cos() * azimuth.cos(),
        );
        Self::look_at(intrinsics, &(centre + direction * distance), centre)
    }

    /// The camera centre in the object frame.
    pub fn centre(&self) -> Point3 {
        self.pose.translation.vector.into()
    }

    /// The unit direction (object frame) of the ray through pixel `(u, v)`, and the depth
    /// gained per unit of distance along it.
    pub fn ray(&self, u: Real, v: Real) -> (Vector3, Real) {
        let k = &self.intrinsics;
        let local = Vector3::new((u - k.cx) / k.fx, (v - k.cy) / k.fy, 1.0);
        let norm = local.norm();
        (self.pose.rotation * (local / norm), 1.0 / norm)
    }

    /// Pixel coordinates and depth of an object-frame point, or `None` behind the camera.
    pub fn project(&self, p: &Point3) -> Option<(Real, Real, Real)> {
        self.intrinsics.project(&self.pose.inverse_transform_point(p))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn drawn_cameras_look_at_the_centre_from_the_configured_distance() {
        let config = ScanConfig::default();
        let centre = Point3::new(0.3, -0.2, 1.0);
        let mut rng = Rng::seed_from_u64(3);
        for _ in 0..50 {
            let camera = Camera::draw(&config, &centre, 2.0, &mut rng);
            let (u, v, z) = camera.project(&centre).expect("in front");
            let k = &camera.intrinsics;
            assert!((u - k.cx).abs() < 1e-3 && (v - k.cy).abs() < 1e-3, "{u} {v}");
            let fit = 1.0 / (22.5f32).to_radians().sin();
            assert!(z >= fit * 0.999 && z <= 1.6 * fit * 1.001, "{z}");
            let up = camera.pose.rotation * -Vector3::y();
            assert!(up.y > 0.0, "image up points up: {up}");
        }
    }

    #[test]
    fn a_pixel_ray_projects_back_onto_its_pixel() {
        let k = Intrinsics::with_fov(64, 48, 1.0);
        let camera = Camera::look_at(k, &Point3::new(1.0, 2.0, 3.0), &Point3::origin());
        let (dir, dz) = camera.ray(10.0, 40.0);
        let p = camera.centre() + dir * 2.0;
        let (u, v, z) = camera.project(&p).expect("in front");
        assert!((u - 10.0).abs() < 1e-3 && (v - 40.0).abs() < 1e-3);
        assert!((z - 2.0 * dz).abs() < 1e-5);
    }
}
