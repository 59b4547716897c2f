//! Our render layout (docs/FORMAT.md, "Renders"): per object
//! - `object.json`: category, source, links and their parts, the states, every joint in
//!   every state (object frame), the material, the depth scale;
//! - `cameras.json`: the cameras ([`crate::cameras::CameraFile`], OpenCV axes,
//!   camera to object frame; the same cameras see every state);
//! - `state_<s>/{rgb,depth,label,normal}/<view, 4 digits>.png`: 8-bit RGB; 16-bit depth
//!   along the optical axis in units of `depth_scale` (0: nothing); 8-bit part id + 1 (0:
//!   background); 8-bit RGB normals `(n + 1) / 2 * 255` in the object frame (black:
//!   background).

use std::path::Path;

use image::ExtendedColorType;
use pairs::math::Real;
use serde::Serialize;

use super::{each_view, u16_bytes, write_json, write_png};
use crate::appearance::Appearance;
use crate::cameras::{CameraFile, CameraRecord};
use crate::shade::{normal8, rgb8};
use crate::{JointStates, RenderConfig, RenderError, RenderJob};
use assets::Source;

/// `object.json`.
#[derive(Debug, Serialize)]
struct ObjectRecord<'a> {
    object_id: u32,
    category: &'a str,
    source: &'a Source,
    links: Vec<&'a str>,
    part_of_link: &'a [pairs::PartId],
    parts: usize,
    states: &'a [Vec<Real>],
    joints: Vec<JointStates>,
    appearance: &'a Appearance,
    depth_scale: Real,
    /// Per state `s`, per part: its rigid motion from state 0 to state `s` (object frame),
    /// a row-major 4 x 4 matrix.
    part_motions: Vec<Vec<[[Real; 4]; 4]>>,
}

/// Writes one object; returns its folder name.
pub fn write_object(
    config: &RenderConfig,
    job: &RenderJob,
    out: &Path,
    tick: &(dyn Fn() + Sync),
) -> Result<String, RenderError> {
    let dir = out.join(&job.name);
    let object = &job.object.object;
    write_json(
        &dir.join("object.json"),
        &ObjectRecord {
            object_id: job.object.object_id,
            category: &object.category,
            source: &job.object.source,
            links: object.links.iter().map(|l| l.name.as_str()).collect(),
            part_of_link: &job.part_of_link,
            parts: job.parts,
            states: &job.states,
            joints: job.joints(),
            appearance: &job.appearance,
            depth_scale: job.depth_scale,
            part_motions: (0..job.states.len())
                .map(|s| {
                    (0..job.parts)
                        .map(|k| {
                            let m = job.part_motion(k as pairs::PartId, 0, s).to_homogeneous();
                            std::array::from_fn(|r| std::array::from_fn(|c| m[(r, c)]))
                        })
                        .collect()
                })
                .collect(),
        },
    )?;
    write_json(
        &dir.join("cameras.json"),
        &CameraFile { cameras: job.cameras.iter().map(CameraRecord::of).collect() },
    )?;
    each_view(config, job, tick, |state, view, images| {
        let (w, h) = (images.width, images.height);
        let state_dir = dir.join(format!("state_{state}"));
        let file = format!("{view:04}.png");
        write_png(
            &state_dir.join("rgb").join(&file),
            &rgb8(&images.rgb),
            w,
            h,
            ExtendedColorType::Rgb8,
        )?;
        let depth = depth_units(&images.depth, job.depth_scale);
        write_png(
            &state_dir.join("depth").join(&file),
            &u16_bytes(&depth),
            w,
            h,
            ExtendedColorType::L16,
        )?;
        let labels: Vec<u8> = images.part.iter().map(|p| p.map_or(0, |k| k + 1)).collect();
        write_png(&state_dir.join("label").join(&file), &labels, w, h, ExtendedColorType::L8)?;
        write_png(
            &state_dir.join("normal").join(&file),
            &normal8(&images.normal),
            w,
            h,
            ExtendedColorType::Rgb8,
        )?;
        Ok(())
    })?;
    Ok(job.name.clone())
}

/// Depths in units of `scale`, rounded, at least 1 where something was hit; 0 elsewhere.
pub fn depth_units(depth: &[Real], scale: Real) -> Vec<u16> {
    depth
        .iter()
        .map(|&z| if z > 0.0 { (z / scale).round().clamp(1.0, 65535.0) as u16 } else { 0 })
        .collect()
}
