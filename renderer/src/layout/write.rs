//! Rendering a set of objects into a staging folder in one layout, views in parallel,
//! objects one after another, and the record at the root of the folder (`render.json`).

use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};

use rayon::prelude::*;
use serde::Serialize;

use super::{artgs, dta, gt, native, paris, write_json, Layout, RENDER_FORMAT_VERSION};
use crate::shade::ViewImages;
use crate::{RenderConfig, RenderError, RenderJob};
use pairs::atomic::Staging;
use pairs::renders::RenderRecord;

/// What a render wrote.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Rendered {
    /// Object folders, relative to the output folder.
    pub objects: Vec<String>,
    /// Views rendered (objects x states x cameras).
    pub views: u64,
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
        generator_version: articulated::GENERATOR_VERSION.into(),
        layout: layout.as_str().into(),
        seed,
        config,
        objects: objects.clone(),
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
    write: impl Fn(usize, usize, &ViewImages) -> Result<(), RenderError> + Sync,
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
