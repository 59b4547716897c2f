//! The layout ArtGS reads (`YuLiu-LY/ArtGS` at b11a0e1e; docs/FORMAT.md, "ArtGS layout"):
//! not DigitalTwinArt's, though its `gt/` folder is the same. Per object, under
//! `data/part_induction/render/<object folder>/` (ArtGS finds its outputs by replacing
//! `data/` in the path, `train.py:47`):
//! - `transforms_train_{start,end}.json`: `camera_angle_x`, `camera_angle_y` (radians;
//!   principal point at the centre) and `frames[]` of `file_path`, `time` (0.0 start, 1.0
//!   end) and `transform_matrix`, camera to world with OpenGL axes
//!   (`scene/dataset_readers.py:116-199`); `transforms_train.json` holds both states' frames
//!   (ArtGS only checks that it exists, `scene/__init__.py:42`);
//! - `{start,end}/train/rgba/NNNN.png`: 8-bit RGBA, alpha the mask; `.../depth/NNNN.png`:
//!   16-bit depth along the optical axis in millimetres of world units;
//! - `gt/trans.json`, `gt/{start,end}/<state>{,_static,_dynamic[_<i>]}_rotate.ply`.
//!
//! The world is PARIS's (Z up, the object centred with its largest half extent 1,
//! `gt::normalised_frame`, recorded in `frame.json`): ArtGS does not normalise the scene and
//! initialises in [-1.3, 1.3]^3 (`dataset_readers.py:228`). `arguments/*.json` at the
//! output's root hold the entries ArtGS's per-scene registry needs (parts per object in
//! `num_slots.json`), to merge into its own `arguments/`.

use std::path::Path;

use image::ExtendedColorType;
use pairs::math::Real;
use serde_json::{json, Map, Value};

use super::gt::{camera_to_world, part_joints, trans_json, write_meshes, FrameFile};
use super::native::depth_units;
use super::paris::{write_rgba, STATES};
use super::{each_view, u16_bytes, write_json, write_png};
use crate::{RenderConfig, RenderError, RenderJob};

/// ArtGS's dataset and subset names for our renders.
pub const DATASET: (&str, &str) = ("part_induction", "render");

/// The folder of one object, relative to the output folder.
pub fn object_folder(name: &str) -> String {
    format!("data/{}/{}/{name}", DATASET.0, DATASET.1)
}

/// Writes one object; returns its folder (relative to `out`).
pub fn write_object(
    config: &RenderConfig,
    job: &RenderJob,
    out: &Path,
    tick: &(dyn Fn() + Sync),
) -> Result<String, RenderError> {
    super::two_states(job, "artgs", "ArtGS")?;
    let folder = object_folder(&job.name);
    let dir = out.join(&folder);
    let frame = super::Layout::Artgs.frame(job);
    let k = &job.cameras[0].intrinsics;
    let angle = |size: u32, f: Real| 2.0 * (0.5 * size as Real / f).atan();
    let transforms = |states: &[usize]| {
        let frames: Vec<Value> = states
            .iter()
            .flat_map(|&s| {
                job.cameras.iter().enumerate().map(move |(i, c)| {
                    json!({
                        "file_path": format!("{}/train/rgba/{i:04}.png", STATES[s]),
                        "time": s as f64,
                        "transform_matrix": camera_to_world(&frame, c),
                    })
                })
            })
            .collect();
        json!({
            "camera_angle_x": angle(k.width, k.fx),
            "camera_angle_y": angle(k.height, k.fy),
            "frames": frames,
        })
    };
    write_json(&dir.join("transforms_train_start.json"), &transforms(&[0]))?;
    write_json(&dir.join("transforms_train_end.json"), &transforms(&[1]))?;
    write_json(&dir.join("transforms_train.json"), &transforms(&[0, 1]))?;
    each_view(config, job, tick, |state, view, images| {
        let base = dir.join(STATES[state]).join("train");
        let file = format!("{view:04}.png");
        write_rgba(&base.join("rgba").join(&file), images)?;
        let depth = depth_units(&images.depth, 1e-3 / frame.scale as Real);
        write_png(
            &base.join("depth").join(&file),
            &u16_bytes(&depth),
            images.width,
            images.height,
            ExtendedColorType::L16,
        )
    })?;
    write_json(&dir.join("frame.json"), &FrameFile::of(&frame))?;
    let gt = dir.join("gt");
    write_json(&gt.join("trans.json"), &trans_json(&frame, &part_joints(job)))?;
    write_meshes(job, &frame, &gt, &[(0, "start"), (1, "end")])?;
    Ok(folder)
}

/// `arguments/{num_slots,larger_motion_state,joint_types_cgs}.json`: the parts of each
/// object (`train_coarse.py:164`) and the empty tables ArtGS's scripts fill.
pub fn write_registry(out: &Path, objects: &[String], parts: &[usize]) -> Result<(), RenderError> {
    let names = objects.iter().map(|o| o.rsplit('/').next().unwrap_or(o).to_string());
    let slots: Map<String, Value> = names.zip(parts).map(|(n, &p)| (n, json!(p))).collect();
    let nest = |inner: Value| json!({ DATASET.0: { DATASET.1: inner } });
    let args = out.join("arguments");
    write_json(&args.join("num_slots.json"), &nest(Value::Object(slots)))?;
    write_json(&args.join("larger_motion_state.json"), &nest(json!({})))?;
    write_json(&args.join("joint_types_cgs.json"), &nest(json!({})))
}
