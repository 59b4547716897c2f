//! Running one row on one set dataset: the row predicts every pair (view 0, view k) of every
//! set (in parallel over pairs, as a pair run does), the predictions of each set are lifted
//! to the set by the documented rule (`pairs::set_method::lift_pairs`, docs/METRICS.md
//! "Sets") and scored with `pairs::metrics::score_set_prediction` (segmentation, and the
//! motion of every matched part to every view). The per-set results are cached in
//! `<runs>/<dataset>/<row>.csv` with a `.json` sidecar naming the row's fingerprint and the
//! sets file's content hash, reused only while both match.

use std::path::Path;
use std::time::Instant;

use pairs::metrics::{check_prediction, score_set_prediction, SetScore};
use pairs::set_method::lift_pairs;
use pairs::Prediction;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::datasets::LoadedSets;
use crate::error::EvalError;
use crate::rows::registry::{Entry, Runner};
use crate::running::record::read_csv;
use crate::running::run::{
    matching_meta, own_flow, predict_pair, prepare, replace_run, runs_path, FlowCache, RunMeta,
    RunOptions, RUNS_VERSION,
};
use pairs::atomic::replace_file;

/// One set's row of a set runs file: its four scores, or why it failed.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct SetRow {
    /// The set's id.
    pub set: String,
    /// The object's category.
    pub category: String,
    /// Views K.
    pub views: u32,
    /// Why the set failed (a pair's prediction failed or could not be lifted); `None` when
    /// it was scored.
    pub failed: Option<String>,
    /// Milliseconds the row took on the set's K-1 pairs (not part of the board).
    pub ms: f64,
    /// Multi-scan mIoU.
    pub multi_scan_iou: Option<f64>,
    /// Per-scan mIoU.
    pub per_scan_iou: Option<f64>,
    /// Multi-scan Rand index.
    pub multi_scan_ri: Option<f64>,
    /// Per-scan Rand index.
    pub per_scan_ri: Option<f64>,
    /// (Set part, view k >= 1) couples matched to a segment with a motion to view k.
    pub matched: Option<u32>,
    /// Summed rotation error of those motions, degrees.
    pub rotation_sum: Option<f64>,
    /// Summed translation error of those motions, view k's normalised units.
    pub translation_sum: Option<f64>,
}

impl SetRow {
    /// Whether the set was scored.
    pub fn scored(&self) -> bool {
        self.failed.is_none()
    }

    fn new(set: &pairs::Set, ms: f64, outcome: Result<SetScore, String>) -> Self {
        let mut row = Self {
            set: set.id().to_owned(),
            category: set.provenance().category.clone(),
            views: set.len() as u32,
            ms,
            ..Self::default()
        };
        match outcome {
            Ok(SetScore { scores: s, motions }) => {
                row.multi_scan_iou = Some(s.multi_scan_iou);
                row.per_scan_iou = Some(s.per_scan_iou);
                row.multi_scan_ri = Some(s.multi_scan_ri);
                row.per_scan_ri = Some(s.per_scan_ri);
                row.matched = Some(motions.rotation_deg.len() as u32);
                row.rotation_sum = Some(motions.rotation_deg.iter().sum());
                row.translation_sum = Some(motions.translation.iter().sum());
            }
            Err(reason) => row.failed = Some(reason),
        }
        row
    }
}

/// The columns of a set runs file, [`SetRow`]'s fields.
const HEADER: [&str; 12] = [
    "set",
    "category",
    "views",
    "failed",
    "ms",
    "multi_scan_iou",
    "per_scan_iou",
    "multi_scan_ri",
    "per_scan_ri",
    "matched",
    "rotation_sum",
    "translation_sum",
];

/// The fingerprint of `entry`'s set run on `dataset`: its pair fingerprint and the set
/// runner's own code (`SOURCE_HASH_SETS`: `running/sets.rs`), so that a change to how sets
/// are run and lifted recomputes the set rows and only them.
fn set_fingerprint(entry: &Entry, dataset: &str) -> String {
    format!("{} sets {}", entry.fingerprint_for(dataset), env!("SOURCE_HASH_SETS"))
}

/// One row's results on one set dataset.
#[derive(Debug, Clone)]
pub struct SetRunResult {
    /// One row per set.
    pub rows: Vec<SetRow>,
    /// Whether it came from the cache.
    pub cached: bool,
}

/// Whether `entry` has a row on the set dataset `dataset`: every row on the segmentation
/// board (a flow-only row gives no segments to carry); a row read from prediction files
/// only where it has a file for that dataset (`evaluator score`).
pub fn runs_on_sets(entry: &Entry, dataset: &str) -> bool {
    entry.runs_on(dataset, false) && entry.board != crate::rows::registry::Board::Flow
}

/// Reads a set runs file.
pub fn read_set_rows(path: &Path) -> Result<Vec<SetRow>, EvalError> {
    let header: Vec<String> = HEADER.iter().map(|h| h.to_string()).collect();
    Ok(read_csv::<SetRow>(path, &header)?.into_iter().map(|(_, row)| row).collect())
}

/// Writes a set runs file, replacing an old one only once the new one is complete.
pub fn write_set_rows(path: &Path, rows: &[SetRow]) -> Result<(), EvalError> {
    let bad = |e: csv::Error| EvalError::Csv { path: path.to_path_buf(), message: e.to_string() };
    replace_file(path, |out| {
        let mut writer = csv::WriterBuilder::new().has_headers(false).from_writer(out);
        writer.write_record(HEADER).map_err(bad)?;
        for row in rows {
            writer.serialize(row).map_err(bad)?;
        }
        writer.flush().map_err(|source| EvalError::Io { path: path.to_path_buf(), source })
    })
}

/// The cached run of `entry` on `sets`, if one matches: same runs version, fingerprint and
/// sets hash, one row per set in the dataset's order.
pub fn cached_set_run(
    entry: &Entry,
    sets: &LoadedSets,
    options: &RunOptions,
) -> Option<SetRunResult> {
    let name = &sets.pairs.name;
    let path = runs_path(&options.runs, name, &entry.name);
    matching_meta(&path, &set_fingerprint(entry, name), &sets.pairs.content_hash)?;
    let rows = read_set_rows(&path).ok()?;
    let same = rows.len() == sets.sets.len()
        && rows.iter().zip(&sets.sets).all(|(row, set)| row.set == set.id());
    same.then_some(SetRunResult { rows, cached: true })
}

/// Runs `entry` on the set dataset `sets` (or reuses its cached run unless `force`), calling
/// `progress` once per pair (0, k).
pub fn run_set_entry(
    entry: &Entry,
    sets: &LoadedSets,
    flows: &FlowCache,
    options: &RunOptions,
    progress: &(dyn Fn() + Sync),
) -> Result<SetRunResult, EvalError> {
    if !options.force {
        if let Some(cached) = cached_set_run(entry, sets, options) {
            return Ok(cached);
        }
    }
    let dataset = &sets.pairs;
    let path = runs_path(&options.runs, &dataset.name, &entry.name);
    let meta_path = path.with_extension("json");
    // A prediction file for a set dataset holds the pairs (0, k) (docs/FORMAT.md).
    let (source_flows, runner) = prepare(entry, dataset, flows)?;
    let runner = &runner;
    let predictions: Vec<(Result<Prediction, String>, f64)> = dataset
        .pairs
        .par_iter()
        .enumerate()
        .map(|(i, pair)| {
            let started = Instant::now();
            // Checked as a pair run checks it (lengths, finiteness) before it is lifted.
            let prediction = predict_pair(runner, pair, source_flows.as_ref().map(|f| &f[i]))
                .and_then(|p| match check_prediction(&p, pair.input()) {
                    Ok(()) => Ok(p),
                    Err(e) => Err(format!("pair {}: {e}", pair.id())),
                });
            progress();
            (prediction, started.elapsed().as_secs_f64() * 1e3)
        })
        .collect();
    if let Runner::Method(m) = &entry.runner {
        let own = predictions.iter().map(|(p, _)| own_flow(&entry.name, p)).collect();
        flows.offer(m.name(), &dataset.name, own);
    }
    let mut rows = Vec::with_capacity(sets.sets.len());
    let mut next = 0;
    for set in &sets.sets {
        let k = set.len() - 1;
        let mine = &predictions[next..next + k];
        next += k;
        let ms = mine.iter().map(|(_, ms)| ms).sum();
        let outcome = mine
            .iter()
            .map(|(p, _)| p.clone())
            .collect::<Result<Vec<_>, _>>()
            .and_then(|made| lift_pairs(set.input(), &made))
            .and_then(|lifted| {
                score_set_prediction(&lifted, set.truth()).map_err(|e| e.to_string())
            });
        rows.push(SetRow::new(set, ms, outcome));
    }
    let meta = RunMeta {
        version: RUNS_VERSION,
        fingerprint: set_fingerprint(entry, &dataset.name),
        dataset: dataset.content_hash.clone(),
        peak_mib: None,
        gallery: Default::default(),
    };
    replace_run(&meta_path, &meta, || write_set_rows(&path, &rows))?;
    Ok(SetRunResult { rows, cached: false })
}
