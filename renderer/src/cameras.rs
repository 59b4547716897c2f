//! The cameras of a render: V views spread evenly (a Fibonacci lattice) over a sphere or
//! the upper hemisphere (+y up) around the object, each aimed at its centre from a distance
//! at which the object's bounding sphere fits the field of view; or read from a file.

use std::path::Path;

use pairs::math::{Isometry3, Matrix3, Point3, Real, Rotation3, UnitQuaternion, Vector3};
use pairs::Intrinsics;
use serde::{Deserialize, Serialize};

use crate::RenderError;
use scanner::camera::Camera;

/// Where the cameras stand.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Placement {
    /// The whole sphere.
    Sphere,
    /// The upper hemisphere (elevation from 0 to 90 degrees above the horizontal plane).
    Hemisphere,
}

impl std::str::FromStr for Placement {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "sphere" => Ok(Self::Sphere),
            "hemisphere" => Ok(Self::Hemisphere),
            _ => Err(format!("unknown camera placement {s:?}: sphere or hemisphere")),
        }
    }
}

/// `views` cameras on the sphere or hemisphere of radius `distance` around `centre`.
/// View `i` sits at height `1 - (i + 1/2) * 2 / V` (sphere) or `1 - (i + 1/2) / V`
/// (hemisphere) of the unit sphere, turned by `i` golden angles about +y.
pub fn placed(
    intrinsics: Intrinsics,
    placement: Placement,
    views: u32,
    centre: &Point3,
    distance: Real,
) -> Vec<Camera> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..views)
        .map(|i| {
            let t = (f64::from(i) + 0.5) / f64::from(views);
            let y = match placement {
                Placement::Sphere => 1.0 - 2.0 * t,
                Placement::Hemisphere => 1.0 - t,
            };
            let ring = (1.0 - y * y).max(0.0).sqrt();
            let azimuth = golden * f64::from(i);
            let direction = Vector3::new(
                (ring * azimuth.sin()) as Real,
                y as Real,
                (ring * azimuth.cos()) as Real,
            );
            Camera::look_at(intrinsics, &(centre + direction * distance), centre)
        })
        .collect()
}

/// The distance at which a sphere of `radius` fills `fill` of the narrower field of view.
pub fn fitting_distance(intrinsics: &Intrinsics, radius: Real, fill: Real) -> Real {
    let half_x = (0.5 * intrinsics.width as Real / intrinsics.fx).atan();
    let half_y = (0.5 * intrinsics.height as Real / intrinsics.fy).atan();
    radius / (fill * half_x.min(half_y).sin())
}

/// One camera of a camera file: intrinsics and camera-to-object transform (OpenCV axes: x
/// right, y down, z forward), a 4 x 4 row-major matrix.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraRecord {
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Focal lengths and principal point, pixels (pixel centres at integer coordinates).
    pub fx: f64,
    #[allow(missing_docs)]
    pub fy: f64,
    #[allow(missing_docs)]
    pub cx: f64,
    #[allow(missing_docs)]
    pub cy: f64,
    /// Camera frame to object frame.
    pub camera_to_world: [[f64; 4]; 4],
}

/// A camera file: `{"cameras": [CameraRecord, ...]}`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraFile {
    /// The cameras, in view order.
    pub cameras: Vec<CameraRecord>,
}

impl CameraRecord {
    /// The record of a camera.
    pub fn of(camera: &Camera) -> Self {
        let k = &camera.intrinsics;
        let m = camera.pose.to_homogeneous();
        Self {
            width: k.width,
            height: k.height,
            fx: f64::from(k.fx),
            fy: f64::from(k.fy),
            cx: f64::from(k.cx),
            cy: f64::from(k.cy),
            camera_to_world: std::array::from_fn(|r| std::array::from_fn(|c| f64::from(m[(r, c)]))),
        }
    }

    /// The camera, checking that the intrinsics are positive and finite and the rotation
    /// orthonormal; `what` names the camera in errors.
    pub fn camera(&self, what: &str) -> Result<Camera, RenderError> {
        let bad = |reason: String| RenderError::Cameras { what: what.into(), reason };
        if self.width == 0 || self.height == 0 {
            return Err(bad(format!("image size {} x {}", self.width, self.height)));
        }
        for (name, v) in [("fx", self.fx), ("fy", self.fy)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(bad(format!("{name} = {v} is not a positive focal length")));
            }
        }
        if !(self.cx.is_finite() && self.cy.is_finite()) {
            return Err(bad("the principal point is not finite".into()));
        }
        let m = &self.camera_to_world;
        if m.iter().flatten().any(|v| !v.is_finite()) {
            return Err(bad("camera_to_world holds a non-finite value".into()));
        }
        if m[3] != [0.0, 0.0, 0.0, 1.0] {
            return Err(bad("camera_to_world's last row is not 0 0 0 1".into()));
        }
        let r = Matrix3::from_fn(|i, j| m[i][j] as Real);
        let error = (r.transpose() * r - Matrix3::identity()).abs().max();
        if error > 1e-4 || r.determinant() < 0.0 {
            return Err(bad(format!(
                "camera_to_world's rotation is not a rotation (|R^T R - I| = {error:.2e}, det {:.3})",
                r.determinant()
            )));
        }
        let rotation = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(r));
        let translation = Vector3::new(m[0][3] as Real, m[1][3] as Real, m[2][3] as Real);
        Ok(Camera {
            intrinsics: Intrinsics {
                width: self.width,
                height: self.height,
                fx: self.fx as Real,
                fy: self.fy as Real,
                cx: self.cx as Real,
                cy: self.cy as Real,
            },
            pose: Isometry3::from_parts(translation.into(), rotation),
        })
    }
}

/// Reads a camera file (see [`CameraFile`]).
pub fn read(path: &Path) -> Result<Vec<Camera>, RenderError> {
    let text = std::fs::read_to_string(path)
        .map_err(|error| RenderError::Io { path: path.into(), error })?;
    let file: CameraFile = serde_json::from_str(&text).map_err(|e| RenderError::Cameras {
        what: path.display().to_string(),
        reason: e.to_string(),
    })?;
    if file.cameras.is_empty() {
        return Err(RenderError::Cameras {
            what: path.display().to_string(),
            reason: "no cameras".into(),
        });
    }
    file.cameras
        .iter()
        .enumerate()
        .map(|(i, c)| c.camera(&format!("{}, camera {i}", path.display())))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn placed_cameras_look_at_the_centre_from_the_distance() {
        let k = Intrinsics::with_fov(64, 48, 0.8);
        let centre = Point3::new(0.1, 0.2, -0.3);
        for placement in [Placement::Sphere, Placement::Hemisphere] {
            let cameras = placed(k, placement, 30, &centre, 2.5);
            let mut above = 0;
            for c in &cameras {
                assert!(((c.centre() - centre).norm() - 2.5).abs() < 1e-4);
                let (u, v, _) = c.project(&centre).expect("in front");
                assert!((u - k.cx).abs() < 1e-3 && (v - k.cy).abs() < 1e-3);
                above += usize::from(c.centre().y > centre.y);
            }
            match placement {
                Placement::Sphere => assert_eq!(above, 15),
                Placement::Hemisphere => assert_eq!(above, 30),
            }
        }
    }

    #[test]
    fn a_camera_record_round_trips_and_bad_ones_are_named() {
        let k = Intrinsics::with_fov(64, 48, 0.8);
        let camera = Camera::look_at(k, &Point3::new(1.0, 2.0, 3.0), &Point3::origin());
        let back = CameraRecord::of(&camera).camera("c").expect("valid");
        assert!((back.pose.to_homogeneous() - camera.pose.to_homogeneous()).abs().max() < 1e-6);
        let mut bad = CameraRecord::of(&camera);
        bad.camera_to_world[0][0] *= 2.0;
        let err = bad.camera("file.json, camera 3").expect_err("scaled rotation").to_string();
        assert!(err.contains("camera 3") && err.contains("not a rotation"), "{err}");
        let mut bad = CameraRecord::of(&camera);
        bad.fx = f64::NAN;
        assert!(bad.camera("c").is_err());
    }
}
