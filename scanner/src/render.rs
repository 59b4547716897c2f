//! Ray casting one depth image: a ray per pixel against the posed scene, in parallel over
//! rows (each pixel on its own, so the result does not depend on the thread count).

use pairs::math::Real;
use rayon::prelude::*;

use super::camera::Camera;
use super::scene::PosedScene;

/// Marks a pixel that sees no surface in [`Render::link`].
pub const NO_LINK: u32 = u32::MAX;

/// A noise-free rendering: per pixel (row-major, from the top-left) the depth along the
/// optical axis, the link seen and how squarely it faces the camera.
#[derive(Debug, Clone, PartialEq)]
pub struct Render {
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Depth along the optical axis, object units; 0 where the ray meets nothing.
    pub depth: Vec<Real>,
    /// Link seen, or [`NO_LINK`].
    pub link: Vec<u32>,
    /// Cosine between the surface normal and the ray back to the camera; 0 for background.
    pub facing: Vec<Real>,
}

impl Render {
    /// Number of pixels that see the object.
    pub fn hits(&self) -> usize {
        self.link.iter().filter(|&&l| l != NO_LINK).count()
    }
}

/// Renders `scene` through `camera`. Only pixels inside the projection of the scene's
/// bounding box cast rays; the others cannot meet the object.
pub fn render(scene: &PosedScene, camera: &Camera) -> Render {
    let k = &camera.intrinsics;
    let (width, height) = (k.width, k.height);
    let (u_range, v_range) = pixel_window(scene, camera);
    let far = (camera.centre() - scene.centre()).norm() + scene.diagonal();
    let rows: Vec<Vec<(Real, u32, Real)>> = v_range
        .clone()
        .into_par_iter()
        .map(|v| {
            u_range
                .clone()
                .map(|u| {
                    let (dir, dz) = camera.ray(u as Real, v as Real);
                    match scene.cast(&camera.centre(), &dir, far) {
                        Some(hit) => (hit.distance * dz, hit.link as u32, hit.facing.abs()),
                        None => (0.0, NO_LINK, 0.0),
                    }
                })
                .collect()
        })
        .collect();
    let pixels = (width * height) as usize;
    let mut out = Render {
        width,
        height,
        depth: vec![0.0; pixels],
        link: vec![NO_LINK; pixels],
        facing: vec![0.0; pixels],
    };
    for (v, row) in v_range.zip(rows) {
        for (u, (depth, link, facing)) in u_range.clone().zip(row) {
            let i = (v * width + u) as usize;
            (out.depth[i], out.link[i], out.facing[i]) = (depth, link, facing);
        }
    }
    out
}

/// The columns and rows the scene's bounding box covers (the whole image if a corner lies
/// behind the camera): the pixels [`render`] casts rays for.
pub fn pixel_window(
    scene: &PosedScene,
    camera: &Camera,
) -> (std::ops::Range<u32>, std::ops::Range<u32>) {
    window_of(&scene.corners(), camera)
}

/// The columns and rows a bounding box with `corners` covers through `camera` (the whole
/// image if a corner lies behind it).
pub fn window_of(
    corners: &[pairs::math::Point3; 8],
    camera: &Camera,
) -> (std::ops::Range<u32>, std::ops::Range<u32>) {
    let k = &camera.intrinsics;
    let whole = (0..k.width, 0..k.height);
    let mut lo = [Real::MAX; 2];
    let mut hi = [Real::MIN; 2];
    for corner in corners {
        let Some((u, v, _)) = camera.project(corner) else {
            return whole;
        };
        lo = [lo[0].min(u), lo[1].min(v)];
        hi = [hi[0].max(u), hi[1].max(v)];
    }
    let clamp = |x: Real, n: u32| x.clamp(0.0, n as Real) as u32;
    let u = clamp(lo[0].floor(), k.width)..clamp(hi[0].ceil() + 1.0, k.width);
    let v = clamp(lo[1].floor(), k.height)..clamp(hi[1].ceil() + 1.0, k.height);
    (u, v)
}
