//! The layout DigitalTwinArt reads (`NVlabs/DigitalTwinArt` at 1a48b402; docs/FORMAT.md,
//! "DigitalTwinArt layout"), one folder per object (its `--data_dir`):
//! - `cam_K.txt`: the 3 x 3 intrinsics, row-major, pixels (`main.py:58`); the principal
//!   point at `(W/2, H/2)` with pixel centres at integer coordinates, as its ray code
//!   assumes (`nerf_utils.py:20,28`);
//! - `init_keyframes.yml`: `frame_<T>_<I>: {cam_in_ob: 16 numbers, time: T}`, camera to
//!   object, row-major, OpenGL camera axes (`model.py:155`), every number written with a
//!   decimal point (its preprocessing drops bare integers); `T` is 0 (start) or 1 (end);
//! - `color_segmented/`, `depth_filtered/`, `mask/`: `<T>_<I>.png` with `T` as 5 digits and
//!   `I` as 4: 8-bit RGB; 16-bit depth along the optical axis in millimetres (object units
//!   read as metres, `main.py:84`); 8-bit mask, 255 on the object (`main.py:89-91`);
//! - `gt/trans.json` and `gt/{start,end}/<state>{,_static,_dynamic[_<i>]}_rotate.ply`
//!   (`model.py:558-568`), in the object frame: DigitalTwinArt normalises the scene itself.
//!
//! Not written: the LoFTR correspondences its training needs
//! (`correspondence_loftr/no_filter/*.npz`); its `preproc/gen_correspondence.py` makes them
//! from these images.

use std::fmt::Write as _;
use std::path::Path;

use image::ExtendedColorType;

use super::gt::{camera_to_world, part_joints, trans_json, write_meshes};
use super::native::depth_units;
use super::{each_view, u16_bytes, write_bytes, write_json, write_png};
use crate::shade::rgb8;
use crate::{RenderConfig, RenderError, RenderJob};

/// Writes one object; returns its folder name.
pub fn write_object(
    config: &RenderConfig,
    job: &RenderJob,
    out: &Path,
    tick: &(dyn Fn() + Sync),
) -> Result<String, RenderError> {
    super::two_states(job, "dta", "DigitalTwinArt")?;
    let dir = out.join(&job.name);
    let k = &job.cameras[0].intrinsics;
    let cam_k = format!("{:.9} 0.0 {:.9}\n0.0 {:.9} {:.9}\n0.0 0.0 1.0\n", k.fx, k.cx, k.fy, k.cy);
    write_bytes(&dir.join("cam_K.txt"), cam_k.as_bytes())?;
    let frame = super::Layout::Dta.frame(job);
    let mut yml = String::new();
    for time in 0..2 {
        for (i, camera) in job.cameras.iter().enumerate() {
            let m = camera_to_world(&frame, camera);
            let numbers: Vec<String> = m.iter().flatten().map(|x| format!("{x:.9}")).collect();
            let _ = write!(
                yml,
                "frame_{}:\n  cam_in_ob: [{}]\n  time: {time}\n",
                stem(time, i),
                numbers.join(", ")
            );
        }
    }
    write_bytes(&dir.join("init_keyframes.yml"), yml.as_bytes())?;
    each_view(config, job, tick, |state, view, images| {
        let file = format!("{}.png", stem(state, view));
        let (w, h) = (images.width, images.height);
        write_png(
            &dir.join("color_segmented").join(&file),
            &rgb8(&images.rgb),
            w,
            h,
            ExtendedColorType::Rgb8,
        )?;
        let depth = depth_units(&images.depth, 1e-3);
        write_png(
            &dir.join("depth_filtered").join(&file),
            &u16_bytes(&depth),
            w,
            h,
            ExtendedColorType::L16,
        )?;
        let mask: Vec<u8> = images.part.iter().map(|p| if p.is_some() { 255 } else { 0 }).collect();
        write_png(&dir.join("mask").join(&file), &mask, w, h, ExtendedColorType::L8)
    })?;
    let gt = dir.join("gt");
    write_json(&gt.join("trans.json"), &trans_json(&frame, &part_joints(job)))?;
    write_meshes(job, &frame, &gt, &[(0, "start"), (1, "end")])?;
    Ok(job.name.clone())
}

/// `<T>_<I>`: the state as 5 digits, the view as 4.
pub fn stem(state: usize, view: usize) -> String {
    format!("{state:05}_{view:04}")
}
