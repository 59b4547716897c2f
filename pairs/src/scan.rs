//! The camera record of a scanned side (SF2P's Q, both sides of SP2P): pinhole intrinsics,
//! extrinsics, the depth image's scale and where its images lie in the dataset folder.
//!
//! Conventions are OpenCV's: the camera looks along +z, x points right and y down in the
//! image; pixel `(u, v)` (column, row, from the top-left) has its centre at integer
//! coordinates, so its ray passes through `((u - cx) / fx, (v - cy) / fy, 1)`. A depth
//! image holds z (distance along the optical axis), not ray length.

use crate::math::{Isometry3, Matrix3, Point3, Real, Vector3};

/// Pinhole intrinsics of an image, pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Intrinsics {
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Focal length along x, pixels.
    pub fx: Real,
    /// Focal length along y, pixels.
    pub fy: Real,
    /// Principal point x, pixels.
    pub cx: Real,
    /// Principal point y, pixels.
    pub cy: Real,
}

impl Intrinsics {
    /// Intrinsics with square pixels, the principal point at the image centre, and the
    /// given vertical field of view (radians).
    pub fn with_fov(width: u32, height: u32, fov_y: Real) -> Self {
        let f = 0.5 * height as Real / (0.5 * fov_y).tan();
        Self {
            width,
            height,
            fx: f,
            fy: f,
            cx: 0.5 * (width as Real - 1.0),
            cy: 0.5 * (height as Real - 1.0),
        }
    }

    /// The point at depth `z` (along the optical axis) behind pixel `(u, v)`, camera frame.
    pub fn back_project(&self, u: Real, v: Real, z: Real) -> Point3 {
        Point3::new((u - self.cx) / self.fx * z, (v - self.cy) / self.fy * z, z)
    }

    /// The pixel coordinates `(u, v)` and depth of a camera-frame point, or `None` behind
    /// the camera.
    pub fn project(&self, p: &Point3) -> Option<(Real, Real, Real)> {
        (p.z > 0.0).then(|| (self.fx * p.x / p.z + self.cx, self.fy * p.y / p.z + self.cy, p.z))
    }

    /// The pixel whose square holds `(u, v)`, or `None` outside the image.
    pub fn pixel(&self, u: Real, v: Real) -> Option<(u32, u32)> {
        let (u, v) = ((u + 0.5).floor(), (v + 0.5).floor());
        let inside = u >= 0.0 && v >= 0.0 && u < self.width as Real && v < self.height as Real;
        inside.then_some((u as u32, v as u32))
    }
}

/// The three images of a scan, by kind; `T` is a path (in the record) or PNG bytes (when
/// writing).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct ScanImages<T> {
    /// 16-bit grey PNG: depth = value * `depth_scale`, 0 where the scanner saw nothing.
    pub depth: T,
    /// 8-bit grey PNG: part id + 1 of the surface each pixel sees, 0 for background.
    pub labels: T,
    /// 8-bit RGB PNG: the surface shaded with one colour per part.
    pub colour: T,
}

impl ScanImages<String> {
    /// Where the images of side `side` (`"p"` or `"q"`) of pair `id` lie, relative to the
    /// dataset folder: `images/<id>_<side>_{depth,labels,colour}.png`.
    pub fn for_pair(id: &str, side: &str) -> Self {
        let path = |kind: &str| format!("{IMAGES_DIR}/{id}_{side}_{kind}.png");
        Self { depth: path("depth"), labels: path("labels"), colour: path("colour") }
    }
}

impl<T> ScanImages<T> {
    /// The images as `(kind, image)`, in the order depth, labels, colour.
    pub fn iter(&self) -> [(&'static str, &T); 3] {
        [("depth", &self.depth), ("labels", &self.labels), ("colour", &self.colour)]
    }
}

/// Folder of the images within a dataset folder.
pub const IMAGES_DIR: &str = "images";

/// How one side of a pair was scanned.
#[derive(Debug, Clone, PartialEq)]
pub struct Scan {
    /// Pinhole intrinsics.
    pub intrinsics: Intrinsics,
    /// Extrinsic rotation: camera frame to the side's object frame (the posed object
    /// before the cloud's normalisation; map on with the cloud's `Normalisation`).
    pub rotation: Matrix3,
    /// Extrinsic translation: the camera centre in the object frame, object units.
    pub translation: Vector3,
    /// Object units per unit of the depth PNG.
    pub depth_scale: Real,
    /// Paths of the images, relative to the dataset folder.
    pub images: ScanImages<String>,
}

impl Scan {
    /// A scan record from a camera pose (camera frame to object frame).
    pub fn new(
        intrinsics: Intrinsics,
        camera_to_object: &Isometry3,
        depth_scale: Real,
        images: ScanImages<String>,
    ) -> Self {
        Self {
            intrinsics,
            rotation: *camera_to_object.rotation.to_rotation_matrix().matrix(),
            translation: camera_to_object.translation.vector,
            depth_scale,
            images,
        }
    }

    /// The object-frame point seen at pixel `(u, v)` with depth `z`.
    pub fn back_project(&self, u: Real, v: Real, z: Real) -> Point3 {
        self.rotation * self.intrinsics.back_project(u, v, z) + self.translation
    }
}

/// The scans of a pair's two sides; `None` for a full shape.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Scans {
    /// P's scan (SP2P).
    pub p: Option<Scan>,
    /// Q's scan (SF2P, SP2P).
    pub q: Option<Scan>,
}

/// PNG bytes of the images of a pair's scanned sides, for the dataset writer.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PairImages {
    /// P's images, when P is a scan.
    pub p: Option<ScanImages<Vec<u8>>>,
    /// Q's images, when Q is a scan.
    pub q: Option<ScanImages<Vec<u8>>>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn projection_inverts_back_projection() {
        let k = Intrinsics::with_fov(320, 240, 45f32.to_radians());
        let p = k.back_project(10.0, 200.0, 2.5);
        let (u, v, z) = k.project(&p).expect("in front");
        assert!((u - 10.0).abs() < 1e-4 && (v - 200.0).abs() < 1e-4 && (z - 2.5).abs() < 1e-6);
        assert_eq!(k.pixel(u, v), Some((10, 200)));
        assert_eq!(k.pixel(-0.6, 3.0), None);
        assert_eq!(k.pixel(319.4, 239.4), Some((319, 239)));
        assert!(k.project(&Point3::new(0.0, 0.0, -1.0)).is_none());
    }

    #[test]
    fn image_paths_name_pair_and_side() {
        let paths = ScanImages::for_pair("sf2p-00003-1", "q");
        assert_eq!(paths.depth, "images/sf2p-00003-1_q_depth.png");
        assert_eq!(paths.iter()[2].1, "images/sf2p-00003-1_q_colour.png");
    }
}
