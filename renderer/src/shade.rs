//! One view of a posed object: a ray per pixel (through the pixel's centre, no
//! anti-aliasing), the first surface's depth, part, object-frame normal and shaded colour.

use pairs::math::{Real, Vector3};
use pairs::PartId;
use rayon::prelude::*;

use crate::appearance::{Appearance, Lighting};
use crate::scene::RenderScene;
use scanner::camera::Camera;
use scanner::render::window_of;

/// The images of one view, row-major from the top-left pixel.
#[derive(Debug, Clone, PartialEq)]
pub struct ViewImages {
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Linear RGB in [0, 1], 3 per pixel; the background's colour where nothing is hit.
    pub rgb: Vec<[Real; 3]>,
    /// Depth along the optical axis, object units; 0 where nothing is hit.
    pub depth: Vec<Real>,
    /// Part seen, `None` for background.
    pub part: Vec<Option<PartId>>,
    /// Unit normal of the surface seen, object frame, turned towards the camera; zero for
    /// background.
    pub normal: Vec<Vector3>,
}

impl ViewImages {
    /// Pixels that see the object.
    pub fn hits(&self) -> usize {
        self.part.iter().filter(|p| p.is_some()).count()
    }
}

/// What a view needs besides the scene and camera.
pub struct Shading<'a> {
    /// Materials of the links.
    pub appearance: &'a Appearance,
    /// Lights.
    pub lighting: &'a Lighting,
    /// Part of each link.
    pub part_of_link: &'a [PartId],
    /// Colour of pixels that see nothing, linear RGB.
    pub background: [Real; 3],
}

/// Renders one view. Only pixels inside the projection of the scene's bounding box cast
/// rays; each pixel is computed on its own, so the result does not depend on threads.
pub fn shade(scene: &RenderScene, camera: &Camera, shading: &Shading) -> ViewImages {
    let k = &camera.intrinsics;
    let (width, height) = (k.width, k.height);
    let pixels = (width * height) as usize;
    let mut out = ViewImages {
        width,
        height,
        rgb: vec![shading.background; pixels],
        depth: vec![0.0; pixels],
        part: vec![None; pixels],
        normal: vec![Vector3::zeros(); pixels],
    };
    let (u_range, v_range) = window_of(&scene.corners(), camera);
    let far = (camera.centre() - scene.centre()).norm() + scene.diagonal();
    let origin = camera.centre();
    let poses = scene.poses();
    type Pixel = Option<([Real; 3], Real, PartId, Vector3)>;
    let rows: Vec<Vec<Pixel>> = v_range
        .clone()
        .into_par_iter()
        .map(|v| {
            u_range
                .clone()
                .map(|u| {
                    let (dir, dz) = camera.ray(u as Real, v as Real);
                    let hit = scene.cast(&origin, &dir, far)?;
                    let point = origin + dir * hit.distance;
                    let rest = poses[hit.link].inverse_transform_point(&point);
                    let albedo = shading.appearance.albedo(hit.link, &rest);
                    let light = shading.lighting.irradiance(&hit.normal);
                    Some((
                        albedo.map(|a| a * light),
                        hit.distance * dz,
                        shading.part_of_link[hit.link],
                        hit.normal,
                    ))
                })
                .collect()
        })
        .collect();
    for (v, row) in v_range.zip(rows) {
        for (u, pixel) in u_range.clone().zip(row) {
            if let Some((rgb, depth, part, normal)) = pixel {
                let i = (v * width + u) as usize;
                (out.rgb[i], out.depth[i], out.part[i], out.normal[i]) =
                    (rgb, depth, Some(part), normal);
            }
        }
    }
    out
}

/// 8-bit RGB bytes of linear values in [0, 1].
pub fn rgb8(rgb: &[[Real; 3]]) -> Vec<u8> {
    rgb.iter().flat_map(|c| c.map(|x| (x.clamp(0.0, 1.0) * 255.0).round() as u8)).collect()
}

/// 8-bit RGB bytes of unit normals, `(n + 1) / 2 * 255`; background (zero) is black.
pub fn normal8(normals: &[Vector3]) -> Vec<u8> {
    normals
        .iter()
        .flat_map(|n| {
            if n.norm_squared() == 0.0 {
                [0, 0, 0]
            } else {
                [n.x, n.y, n.z].map(|x| ((x * 0.5 + 0.5).clamp(0.0, 1.0) * 255.0).round() as u8)
            }
        })
        .collect()
}
