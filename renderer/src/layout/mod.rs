//! Writing renders to disk: our own layout ([`native`]), or the folder trees PARIS
//! ([`paris`]), DigitalTwinArt ([`dta`]) and ArtGS ([`artgs`]) read. Every layout is written into a
//! staging folder and swapped into place when complete (an interrupted render never
//! changes what was there), views in parallel, objects one after another.

pub mod artgs;
pub mod dta;
pub mod gt;
pub mod native;
pub mod paris;

use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};

use image::ExtendedColorType;
use rayon::prelude::*;
use serde::Serialize;

use crate::{RenderConfig, RenderError, RenderJob};
use pairs::atomic::Staging;

/// Version of the native layout, in `render.json`.
pub const RENDER_FORMAT_VERSION: u32 = 2;

/// A folder layout.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Layout {
    /// Ours: every image kind, cameras and joints in one JSON per object (docs/FORMAT.md,
    /// "Renders").
    Native,
    /// PARIS's `data/sapien/<category>/<id>` tree.
    Paris,
    /// DigitalTwinArt's tree.
    Dta,
    /// ArtGS's tree (its own, not DigitalTwinArt's; the same `gt/` folder).
    Artgs,
}

impl Layout {
    /// The name `--layout` takes.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Native => "native",
            Self::Paris => "paris",
            Self::Dta => "dta",
            Self::Artgs => "artgs",
        }
    }

    /// Whether only one joint moves (PARIS models one moving part).
    pub fn one_joint(self) -> bool {
        self == Self::Paris
    }

    /// The states a layout holds, if fixed.
    pub fn states(self) -> Option<u32> {
        match self {
            Self::Native => None,
            Self::Paris | Self::Dta | Self::Artgs => Some(2),
        }
    }

    /// The world a layout writes in: our object frame for `native` and `dta` (which
    /// normalises the scene itself), PARIS's Z-up frame with the object centred and its
    /// largest half extent 1 for `paris` and `artgs`.
    pub fn frame(self, job: &RenderJob) -> gt::WorldFrame {
        match self {
            Self::Native | Self::Dta => gt::WorldFrame::identity(),
            Self::Paris | Self::Artgs => gt::WorldFrame::normalised(job, true),
        }
    }

    /// The intrinsics of a layout's cameras from a config: DigitalTwinArt puts the
    /// principal point at `(W/2, H/2)` with pixel centres at integer coordinates
    /// (`nerf_utils.py:20,28`); the others at the image's centre, pixel centres at half
    /// integers (PARIS `models/ray_utils.py:9-19`, ArtGS's field of view).
    pub fn intrinsics(self, config: &RenderConfig) -> pairs::Intrinsics {
        let mut k = config.intrinsics();
        if self == Self::Dta {
            k.cx = 0.5 * k.width as pairs::math::Real;
            k.cy = 0.5 * k.height as pairs::math::Real;
        }
        k
    }
}

impl std::str::FromStr for Layout {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "native" => Ok(Self::Native),
            "paris" => Ok(Self::Paris),
            "dta" | "digitaltwinart" => Ok(Self::Dta),
            "artgs" => Ok(Self::Artgs),
            _ => Err(format!("unknown layout {s:?}: native, paris, dta or artgs")),
        }
    }
}

/// What a render wrote.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Rendered {
    /// Object folders, relative to the output folder.
    pub objects: Vec<String>,
    /// Views rendered (objects x states x cameras).
    pub views: u64,
}

/// The record at the root of every layout (`render.json`).
#[derive(Debug, Serialize)]
struct RenderRecord<'a> {
    format_version: u32,
    generator_version: &'a str,
    layout: Layout,
    seed: u64,
    config: &'a RenderConfig,
    objects: &'a [String],
}

/// Renders every job into `out` in `layout`, calling `progress` with the views written so
/// far (from worker threads).
pub fn write_render(
    config: &RenderConfig,
    seed: u64,
    jobs: impl IntoIterator<Item = Result<RenderJob, RenderError>>,
    layout: Layout,
    out: &Path,
    force: bool,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Rendered, RenderError> {
    config.validate()?;
    let staging = Staging::new(out, force)?;
    let done = AtomicU64::new(0);
    let tick = || progress(done.fetch_add(1, Ordering::Relaxed) + 1);
    let mut objects = Vec::new();
    let mut parts = Vec::new();
    let mut truths = Vec::new();
    for job in jobs {
        let job = job?;
        parts.push(job.parts);
        let folder = match layout {
            Layout::Native => native::write_object(config, &job, staging.path(), &tick)?,
            Layout::Paris => paris::write_object(config, &job, staging.path(), &tick)?,
            Layout::Dta => dta::write_object(config, &job, staging.path(), &tick)?,
            Layout::Artgs => artgs::write_object(config, &job, staging.path(), &tick)?,
        };
        truths.push(gt::object_truth(&job, &layout.frame(&job), &folder));
        objects.push(folder);
    }
    let record = RenderRecord {
        format_version: RENDER_FORMAT_VERSION,
        generator_version: articulated::GENERATOR_VERSION,
        layout,
        seed,
        config,
        objects: &objects,
    };
    write_json(&staging.path().join(pairs::renders::RENDER_FILE), &record)?;
    let truth =
        pairs::renders::RenderTruth { layout: layout.as_str().into(), seed, objects: truths };
    write_json(&staging.path().join(pairs::renders::GROUND_TRUTH_FILE), &truth)?;
    if layout == Layout::Artgs {
        artgs::write_registry(staging.path(), &objects, &parts)?;
    }
    staging.commit()?;
    Ok(Rendered { objects, views: done.into_inner() })
}

/// Renders every (state, view) of a job in parallel and hands each to `write` with its
/// state and view index.
pub(crate) fn each_view(
    config: &RenderConfig,
    job: &RenderJob,
    tick: &(dyn Fn() + Sync),
    write: impl Fn(usize, usize, &crate::shade::ViewImages) -> Result<(), RenderError> + Sync,
) -> Result<(), RenderError> {
    let views = job.cameras.len();
    (0..job.states.len() * views).into_par_iter().try_for_each(|i| {
        let (state, view) = (i / views, i % views);
        let images = job.view(config, state, view);
        write(state, view, &images)?;
        tick();
        Ok(())
    })
}

/// Refuses a job that is not of two states, for a layout whose method (`reader`) reads a
/// start and an end state only.
pub(crate) fn two_states(
    job: &RenderJob,
    layout: &'static str,
    reader: &str,
) -> Result<(), RenderError> {
    if job.states.len() == 2 {
        return Ok(());
    }
    Err(RenderError::Layout {
        object: job.name.clone(),
        layout,
        reason: format!("{reader} reads two states, not {}", job.states.len()),
    })
}

/// Writes pretty JSON.
pub(crate) fn write_json(path: &Path, value: &impl Serialize) -> Result<(), RenderError> {
    let mut text = serde_json::to_string_pretty(value)
        .map_err(|e| RenderError::Io { path: path.into(), error: std::io::Error::other(e) })?;
    text.push('\n');
    write_bytes(path, text.as_bytes())
}

/// Writes a file, creating its folder.
pub(crate) fn write_bytes(path: &Path, bytes: &[u8]) -> Result<(), RenderError> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)
            .map_err(|error| RenderError::Io { path: dir.into(), error })?;
    }
    std::fs::write(path, bytes).map_err(|error| RenderError::Io { path: path.into(), error })
}

/// Writes a PNG.
pub(crate) fn write_png(
    path: &Path,
    data: &[u8],
    width: u32,
    height: u32,
    colour: ExtendedColorType,
) -> Result<(), RenderError> {
    let bytes = scanner::images::png(data, width, height, colour)
        .map_err(|error| RenderError::Image { path: path.into(), error })?;
    write_bytes(path, &bytes)
}

/// Bytes of 16-bit values in the order the PNG encoder takes them (native).
pub(crate) fn u16_bytes(values: &[u16]) -> Vec<u8> {
    values.iter().flat_map(|d| d.to_ne_bytes()).collect()
}
