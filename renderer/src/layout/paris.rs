//! The layout PARIS reads (`3dlg-hcvc/paris` at fcab60d2; docs/FORMAT.md, "PARIS layout"),
//! for `source = sapien/<category>/<object folder>`:
//! - `load/<source>/{start,end}/camera_{train,val,test}.json`: `"K"` (3 x 3; the loader uses
//!   only `K[0][0]` and puts the principal point at the image centre,
//!   `datasets/blender_paris.py:56-60`) and `"NNNN"`: 4 x 4 camera-to-world matrices with
//!   OpenGL camera axes (x right, y up, looking along -z; `models/ray_utils.py:17`);
//! - `load/<source>/{start,end}/{train,val,test}/NNNN.png`: 8-bit RGBA, alpha 255 on the
//!   object and 0 elsewhere (the loader's mask is `alpha > 0`, `blender_paris.py:81`);
//! - `data/<source>/textured_objs/trans.json`: the moving joint, `trans_info.{type, axis.o,
//!   axis.d, rotate|translate.{l, r}}`, degrees or world units, start = `l`, end = `r`
//!   (`systems/utils.py:354-388`);
//! - `data/<source>/textured_objs/start/start{,_static,_dynamic}_rotate.ply`: the start state's
//!   whole object, static part and moving part (`systems/base.py:446-448`).
//!
//! PARIS models one moving part: only the object's first driven joint moves between
//! `start` and `end`. Its world is Z-up and must fit in [-1.3, 1.3]^3
//! (`models/geometry.py:100`): our Y-up object frame is mapped by `x' = s C (x - c)`, with
//! `C = [[1,0,0],[0,0,-1],[0,1,0]]` (PARIS's `preprocess.py:245-252`), `c` the centre of
//! the object's bounding box over both states and `s` the scale that brings its largest
//! half extent to 1 (`gt::normalised_frame`); `s` and `c` are in `frame.json` beside
//! `trans.json`. Training views are
//! the configured cameras; `val` and `test` share a turntable of views at 30 degrees
//! elevation, the same in both states (`--predict` uses the start state's test cameras for
//! both, `blender_paris.py:117`).

use std::path::Path;

use image::ExtendedColorType;
use pairs::math::{Point3, Real, Vector3};
use rayon::prelude::*;
use serde_json::{json, Map, Value};

use super::gt::{camera_to_world, part_joints, trans_json, write_meshes, FrameFile};
use super::{each_view, write_json, write_png};
use crate::shade::rgb8;
use crate::shade::ViewImages;
use crate::{RenderConfig, RenderError, RenderJob};
use pairs::renders::WorldFrame;
use scanner::camera::Camera;

/// State folders, in state order.
pub const STATES: [&str; 2] = ["start", "end"];
/// Elevation of the turntable of `val` and `test` views, degrees (PARIS's generator:
/// `utils/blender_cam.py:40-42`).
pub const TURNTABLE_ELEVATION_DEG: Real = 30.0;

/// Writes one object; returns its folder (`sapien/<category>/<object folder>`).
pub fn write_object(
    config: &RenderConfig,
    job: &RenderJob,
    out: &Path,
    tick: &(dyn Fn() + Sync),
) -> Result<String, RenderError> {
    let refuse =
        |reason: String| RenderError::Layout { object: job.name.clone(), layout: "paris", reason };
    super::two_states(job, "paris", "PARIS")?;
    let joints = part_joints(job);
    if joints.len() != 1 || job.parts != 2 {
        return Err(refuse(format!(
            "PARIS reads one moving part, the render has {}",
            job.parts - 1
        )));
    }
    for c in &job.cameras {
        let k = &c.intrinsics;
        let centred = (k.cx - 0.5 * (k.width as Real - 1.0)).abs() < 1e-3
            && (k.cy - 0.5 * (k.height as Real - 1.0)).abs() < 1e-3;
        if (k.fx - k.fy).abs() > 1e-3 * k.fx
            || !centred
            || k.width != job.cameras[0].intrinsics.width
        {
            return Err(refuse(
                "PARIS's loader takes one image size, fy = fx and the principal point at the \
                 image centre"
                    .into(),
            ));
        }
    }
    let frame = super::Layout::Paris.frame(job);
    let source = format!(
        "sapien/{}/{}",
        articulated::objects::identifier(&job.object.object.category),
        job.name
    );
    let load = out.join("load").join(&source);
    let data = out.join("data").join(&source).join("textured_objs");

    let turntable = turntable(job, &Point3::from(frame.centre.map(|c| c as Real)));
    for state in STATES {
        let dir = load.join(state);
        write_json(&dir.join("camera_train.json"), &camera_json(&frame, &job.cameras))?;
        write_json(&dir.join("camera_val.json"), &camera_json(&frame, &turntable))?;
        write_json(&dir.join("camera_test.json"), &camera_json(&frame, &turntable))?;
    }
    each_view(config, job, tick, |state, view, images| {
        write_rgba(&load.join(STATES[state]).join("train").join(format!("{view:04}.png")), images)
    })?;
    (0..2 * turntable.len()).into_par_iter().try_for_each(|i| {
        let (state, view) = (i / turntable.len(), i % turntable.len());
        let images = job.view_from(config, state, &turntable[view]);
        for split in ["val", "test"] {
            write_rgba(
                &load.join(STATES[state]).join(split).join(format!("{view:04}.png")),
                &images,
            )?;
        }
        Ok::<_, RenderError>(())
    })?;
    write_json(&data.join("trans.json"), &trans_json(&frame, &joints))?;
    write_json(&data.join("frame.json"), &FrameFile::of(&frame))?;
    write_meshes(job, &frame, &data, &[(0, "start")])?;
    Ok(source)
}

/// The `val` and `test` views: a quarter as many as the training views (at least 4) on a
/// turntable at 30 degrees elevation, with the training cameras' intrinsics and mean
/// distance.
pub fn turntable(job: &RenderJob, centre: &Point3) -> Vec<Camera> {
    let n = (job.cameras.len() / 4).max(4);
    let k = &job.cameras[0].intrinsics;
    let distance = job.cameras.iter().map(|c| (c.centre() - centre).norm()).sum::<Real>()
        / job.cameras.len() as Real;
    let e = TURNTABLE_ELEVATION_DEG.to_radians();
    (0..n)
        .map(|i| {
            let azimuth = std::f64::consts::TAU as Real * i as Real / n as Real;
            let dir = Vector3::new(e.cos() * azimuth.sin(), e.sin(), e.cos() * azimuth.cos());
            Camera::look_at(*k, &(centre + dir * distance), centre)
        })
        .collect()
}

/// An RGBA PNG: the shaded colour, alpha 255 where the object is and 0 elsewhere.
pub(crate) fn write_rgba(path: &Path, images: &ViewImages) -> Result<(), RenderError> {
    let rgb = rgb8(&images.rgb);
    let rgba: Vec<u8> = rgb
        .chunks_exact(3)
        .zip(&images.part)
        .flat_map(|(c, p)| [c[0], c[1], c[2], if p.is_some() { 255 } else { 0 }])
        .collect();
    write_png(path, &rgba, images.width, images.height, ExtendedColorType::Rgba8)
}

/// A camera file: `"K"` (principal point in PARIS's half-integer pixel centres) then the
/// views by 4-digit key, in order.
fn camera_json(frame: &WorldFrame, cameras: &[Camera]) -> Value {
    let mut map = Map::new();
    let k = &cameras[0].intrinsics;
    map.insert(
        "K".into(),
        json!([[k.fx, 0.0, k.cx + 0.5], [0.0, k.fy, k.cy + 0.5], [0.0, 0.0, 1.0]]),
    );
    for (i, c) in cameras.iter().enumerate() {
        map.insert(format!("{i:04}"), json!(camera_to_world(frame, c)));
    }
    Value::Object(map)
}
