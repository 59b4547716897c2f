//! The render benchmark (`--all`): a small native render of the test categories
//! (`datasets/render`: two states, eight fixed cameras on a sphere), its depth images
//! back-projected into a pair of point clouds per object
//! ([`renderer::backproject`]), and every row that runs on a pair's input (a
//! whole method, or a segmenter on a method's flow; the `gt` oracle from the true parts and
//! motions) scored on the joints it implies, in every convention, into the render joints
//! board ([`crate::boards::render_joints`]). Joints are the method's own where it gives
//! them, else estimated from its segments' motions ([`pairs::joint_estimate`]), then put
//! in the render's object frame.

use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};

use generator::config::GeneratorConfig;
use generator::objects::built_in_objects;
use pairs::joint_estimate::{estimate_joint, estimate_joints, JointParams};
use pairs::math::Vector3;
use pairs::renders::{read_record, RenderJoint, GROUND_TRUTH_FILE, RENDER_FILE};
use pairs::{Cloud, JointKind, PairInput, PairKind, Prediction, Similarity};
use rayon::prelude::*;
use renderer::backproject::{render_pairs, RenderPair};
use renderer::layout::RENDER_FORMAT_VERSION;
use renderer::layout::{write_render, Layout};
use renderer::{RenderConfig, RenderJob};

use crate::error::EvalError;
use crate::rows::registry::{Board, Entry, FlowSource, Runner};
use crate::running::run::guarded;

/// The default render's name (its folder under the datasets root).
pub const RENDER_DATASET: &str = "render";
/// Points per back-projected cloud.
pub const RENDER_POINTS: usize = 512;
/// Objects of the default render (one per test category, in turn).
pub const RENDER_OBJECTS: u32 = 26;

/// The default render's settings: 320 x 240, eight cameras on a sphere, two states.
pub fn default_render_config() -> RenderConfig {
    RenderConfig { width: 320, height: 240, views: 8, states: 2, ..RenderConfig::default() }
}

/// Renders the default render into `root/render` unless a render of this format, layout and
/// these settings is there (one that differs is rendered again, and the notice says why);
/// returns its folder.
pub fn ensure_render(root: &Path, notice: &dyn Fn(&str)) -> Result<PathBuf, EvalError> {
    let dir = root.join(RENDER_DATASET);
    let config = default_render_config();
    let current = dir.join(RENDER_FILE).exists().then(|| {
        read_record::<RenderConfig>(&dir).is_ok_and(|r| {
            r.format_version == RENDER_FORMAT_VERSION
                && r.layout == Layout::Native.as_str()
                && r.seed == 0
                && r.config == config
        })
    });
    match current {
        Some(true) if dir.join(GROUND_TRUTH_FILE).exists() => return Ok(dir),
        Some(_) => notice(&format!(
            "rendering {} again: its format or settings are not this evaluator's",
            dir.display()
        )),
        None => notice(&format!("rendering {} (the render benchmark)", dir.display())),
    }
    let objects = GeneratorConfig { objects: RENDER_OBJECTS, ..GeneratorConfig::default() };
    let generate = |message: String| EvalError::Render { name: RENDER_DATASET.into(), message };
    let jobs = built_in_objects(&objects)
        .map_err(|e| generate(e.to_string()))?
        .into_iter()
        .map(|o| RenderJob::new(&config, objects.seed, o, None, Layout::Native));
    write_render(&config, objects.seed, jobs, Layout::Native, &dir, true, &|_| {})
        .map_err(|e| generate(e.to_string()))?;
    Ok(dir)
}

/// Whether `entry` runs on a render's pairs: a segmentation row (joints come from
/// segments; a flow-only baseline has none) that is the oracle, a whole method, or a
/// segmenter on a method's flow (not on the true flow, and not an external row).
pub fn runs_on_renders(entry: &Entry) -> bool {
    if entry.board == Board::Flow {
        return false;
    }
    match &entry.runner {
        Runner::Oracle | Runner::Method(_) => true,
        Runner::Segmenter { flow: FlowSource::Method(_), .. } => true,
        Runner::Segmenter { .. } | Runner::External(_) => false,
    }
}

/// One object's pair as a method sees it, with the true parts and motions.
struct Prepared {
    pair: RenderPair,
    input: PairInput,
}

/// One row's joints on a render: per object folder, the joints its prediction implies
/// (objects it failed on are left out).
pub type RowJoints = (String, BTreeMap<String, Vec<RenderJoint>>);

/// Every row of `entries` that runs on renders, on the render `name` in `dir` (a native
/// render): its joints.
pub fn render_joints(
    entries: &[&Entry],
    name: &str,
    dir: &Path,
    progress: &dyn Fn(&str),
) -> Result<Vec<RowJoints>, EvalError> {
    let generate = |message: String| EvalError::Render { name: name.into(), message };
    let prepared: Vec<Prepared> = render_pairs(dir, RENDER_POINTS)
        .map_err(|e| generate(e.to_string()))?
        .into_iter()
        .map(|pair| {
            let (p, q) = (Cloud::normalise(&pair.p), Cloud::normalise(&pair.q));
            let (Some(p), Some(q)) = (p, q) else {
                return Err(generate(format!("{}: a degenerate cloud", pair.folder)));
            };
            let input = PairInput { id: pair.folder.clone(), kind: PairKind::Sf2f, p, q };
            Ok(Prepared { pair, input })
        })
        .collect::<Result<_, _>>()?;
    let mut flows: HashMap<String, Vec<Result<Vec<Vector3>, String>>> = HashMap::new();
    let mut rows = Vec::new();
    for entry in entries.iter().copied().filter(|e| runs_on_renders(e)) {
        progress(&entry.name);
        if let Runner::Segmenter { flow: FlowSource::Method(m), .. } = &entry.runner {
            flows.entry(m.name().to_string()).or_insert_with(|| {
                prepared
                    .par_iter()
                    .map(|p| {
                        guarded(|| m.predict(&p.input).map_err(|e| e.to_string()))?
                            .flow
                            .ok_or_else(|| format!("{} gives no flow", m.name()))
                    })
                    .collect()
            });
        }
        let predicted: BTreeMap<String, Vec<RenderJoint>> = prepared
            .par_iter()
            .enumerate()
            .filter_map(|(i, p)| {
                let prediction = predict(entry, p, flows.get(&flow_name(entry)).map(|f| &f[i]));
                prediction.ok().map(|pred| (p.pair.folder.clone(), joints_of(&pred, &p.input)))
            })
            .collect();
        rows.push((entry.name.clone(), predicted));
    }
    Ok(rows)
}

fn flow_name(entry: &Entry) -> String {
    match &entry.runner {
        Runner::Segmenter { flow: FlowSource::Method(m), .. } => m.name().to_string(),
        _ => String::new(),
    }
}

/// A row's prediction on one object's pair, or why it failed.
fn predict(
    entry: &Entry,
    p: &Prepared,
    flow: Option<&Result<Vec<Vector3>, String>>,
) -> Result<Prediction, String> {
    match &entry.runner {
        Runner::Oracle => {
            let (norm_p, norm_q) = (&p.input.p.normalisation, &p.input.q.normalisation);
            let motions: Vec<Similarity> = p
                .pair
                .motions
                .iter()
                .map(|m| Similarity::between_normalised(m, norm_p, norm_q))
                .collect();
            // Each part's joint relative to part 0, the static one (a method has to guess
            // its base: `joints_of` takes its largest segment).
            let joints = (0..motions.len())
                .map(|k| {
                    let points: Vec<_> = p
                        .input
                        .p
                        .points
                        .iter()
                        .zip(&p.pair.part_p)
                        .filter(|(_, &part)| usize::from(part) == k)
                        .map(|(x, _)| x.coords)
                        .collect();
                    let centroid = points.iter().sum::<Vector3>() / points.len().max(1) as f32;
                    (k > 0)
                        .then(|| {
                            estimate_joint(
                                &motions[0],
                                &motions[k],
                                &centroid.into(),
                                &JointParams::default(),
                            )
                        })
                        .flatten()
                })
                .collect();
            Ok(Prediction {
                flow: None,
                segments_p: p.pair.part_p.iter().map(|&k| u32::from(k)).collect(),
                segments_q: p.pair.part_q.iter().map(|&k| u32::from(k)).collect(),
                motions,
                corr_mask: None,
                segment_probs: None,
                joints: Some(joints),
            })
        }
        Runner::Method(m) => guarded(|| m.predict(&p.input).map_err(|e| e.to_string())),
        Runner::Segmenter { segmenter, .. } => {
            let flow = flow.ok_or("no flow")?.as_ref().map_err(|e| e.clone())?;
            guarded(|| segmenter.segment(&p.input, flow).map_err(|e| e.to_string()))
        }
        Runner::External(_) => Err("external rows do not run on renders".into()),
    }
}

/// The joints a prediction implies, in the render's object frame: its own, or those of its
/// segments' motions relative to its largest segment.
fn joints_of(prediction: &Prediction, input: &PairInput) -> Vec<RenderJoint> {
    let estimates = match &prediction.joints {
        Some(j) => j.clone(),
        None => estimate_joints(
            &input.p.points,
            &prediction.segments_p,
            &prediction.motions,
            &JointParams::default(),
        ),
    };
    let norm = &input.p.normalisation;
    estimates
        .into_iter()
        .flatten()
        .map(|e| {
            let pivot = norm.invert(&e.pivot);
            let state = match e.kind {
                JointKind::Revolute => e.value,
                JointKind::Prismatic => e.value * norm.scale,
            };
            RenderJoint {
                kind: e.kind,
                axis: [e.axis.x, e.axis.y, e.axis.z].map(f64::from),
                pivot: [pivot.x, pivot.y, pivot.z].map(f64::from),
                state: f64::from(state),
            }
        })
        .filter(|j| j.problem().is_none())
        .collect()
}
