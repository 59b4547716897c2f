//! Point clouds back-projected from a native render's depth images, for the methods that
//! work on points: per object, every view's depth pixels of state 0 and of state 1 turned
//! into object-frame points (with the part their label image names), then thinned by
//! farthest point sampling. With each part's true motion from state 0 to state 1, they
//! make a pair in the benchmark's sense (`evaluator --all` scores joints on them).

use std::path::Path;

use nalgebra::Matrix4;
use pairs::math::{Isometry3, Point3, Real};
use pairs::renders::{RenderRecord, RENDER_FILE};
use pairs::sampling::farthest_point_sampling;
use pairs::PartId;
use serde::Deserialize;

use crate::cameras;
use crate::RenderError;

/// One object's two states as point clouds with their parts.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderPair {
    /// The object's folder (the key of `ground_truth.json`).
    pub folder: String,
    /// State 0's points, object frame.
    pub p: Vec<Point3>,
    /// Their parts.
    pub part_p: Vec<PartId>,
    /// State 1's points.
    pub q: Vec<Point3>,
    /// Their parts.
    pub part_q: Vec<PartId>,
    /// Each part's motion from state 0 to state 1, object frame.
    pub motions: Vec<Isometry3>,
}

#[derive(Deserialize)]
struct ObjectRecord {
    depth_scale: Real,
    part_motions: Vec<Vec<[[Real; 4]; 4]>>,
}

fn read<T: serde::de::DeserializeOwned>(path: &Path) -> Result<T, RenderError> {
    let text = std::fs::read_to_string(path)
        .map_err(|error| RenderError::Io { path: path.into(), error })?;
    serde_json::from_str(&text).map_err(|e| RenderError::Io {
        path: path.into(),
        error: std::io::Error::new(std::io::ErrorKind::InvalidData, e.to_string()),
    })
}

fn image_error(path: &Path, source: image::ImageError) -> RenderError {
    RenderError::Image { path: path.into(), error: source }
}

/// Every object of the native render in `dir` as a pair of `points` points per state.
pub fn render_pairs(dir: &Path, points: usize) -> Result<Vec<RenderPair>, RenderError> {
    let record: RenderRecord<serde_json::Value> = read(&dir.join(RENDER_FILE))?;
    if record.layout != "native" {
        return Err(RenderError::Layout {
            object: dir.display().to_string(),
            layout: "native",
            reason: format!(
                "point clouds are read from native renders, this one is {}",
                record.layout
            ),
        });
    }
    record.objects.iter().map(|folder| object_pair(&dir.join(folder), folder, points)).collect()
}

fn object_pair(dir: &Path, folder: &str, points: usize) -> Result<RenderPair, RenderError> {
    let object: ObjectRecord = read(&dir.join("object.json"))?;
    let cameras = cameras::read(&dir.join("cameras.json"))?;
    let cloud = |state: usize| -> Result<(Vec<Point3>, Vec<PartId>), RenderError> {
        let (mut xs, mut parts) = (Vec::new(), Vec::new());
        for (v, camera) in cameras.iter().enumerate() {
            let file = format!("{v:04}.png");
            let depth_path = dir.join(format!("state_{state}/depth")).join(&file);
            let label_path = dir.join(format!("state_{state}/label")).join(&file);
            let depth =
                image::open(&depth_path).map_err(|e| image_error(&depth_path, e))?.into_luma16();
            let label =
                image::open(&label_path).map_err(|e| image_error(&label_path, e))?.into_luma8();
            for (u, w, d) in depth.enumerate_pixels() {
                let l = label.get_pixel(u, w)[0];
                if d[0] == 0 || l == 0 {
                    continue;
                }
                let z = Real::from(d[0]) * object.depth_scale;
                let local = camera.intrinsics.back_project(u as Real, w as Real, z);
                xs.push(camera.pose * local);
                parts.push(l - 1);
            }
        }
        if xs.len() < points {
            return Err(RenderError::Layout {
                object: folder.into(),
                layout: "native",
                reason: format!("state {state} gives {} points, fewer than {points}", xs.len()),
            });
        }
        let keep = farthest_point_sampling(&xs, points, 0);
        Ok((keep.iter().map(|&i| xs[i]).collect(), keep.iter().map(|&i| parts[i]).collect()))
    };
    let (p, part_p) = cloud(0)?;
    let (q, part_q) = cloud(1)?;
    let motions = object
        .part_motions
        .get(1)
        .ok_or_else(|| RenderError::Layout {
            object: folder.into(),
            layout: "native",
            reason: "object.json has no state 1".into(),
        })?
        .iter()
        .map(|m| {
            let m = Matrix4::<Real>::from_fn(|r, c| m[r][c]);
            Isometry3::from_parts(
                m.fixed_view::<3, 1>(0, 3).into_owned().into(),
                pairs::math::UnitQuaternion::from_matrix(&m.fixed_view::<3, 3>(0, 0).into_owned()),
            )
        })
        .collect();
    Ok(RenderPair { folder: folder.into(), p, part_p, q, part_q, motions })
}
