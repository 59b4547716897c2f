//! Running one leaderboard row on one dataset: predictions in parallel over pairs (each pair
//! on its own, so results never depend on thread scheduling), every prediction checked and
//! scored, failures recorded with their reason, and the per-pair results cached in
//! `<runs>/<dataset>/<row>.csv` with a `.json` sidecar naming the row's fingerprint and the
//! dataset's content hash: a run is reused only while both match.

use std::collections::{BTreeMap, HashMap};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::Instant;

use pairs::math::Vector3;
use pairs::{Method, Pair, Prediction};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::datasets::LoadedDataset;
use crate::error::EvalError;
use crate::rows::registry::{method_flow_name, Entry, FlowSource, Runner};
use crate::running::memory;
use crate::running::passes::{passes_path, read_passes, score_passes, write_passes, PairPasses};
use crate::running::record::{joint_types, read_rows, write_rows, RunRow};
use pairs::atomic::replace_bytes;
use pairs::metrics::score_pair;

/// Version of the runs files; bump it when scoring changes so cached runs are recomputed.
pub const RUNS_VERSION: u32 = 3;

/// What is stored beside a runs file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunMeta {
    /// [`RUNS_VERSION`] of the evaluator that made it.
    pub version: u32,
    /// The row's fingerprint.
    pub fingerprint: String,
    /// The dataset's content hash.
    pub dataset: String,
    /// Peak resident memory of the evaluator while it ran, MiB (Linux only).
    pub peak_mib: Option<f64>,
    /// P's predicted segments on the gallery pairs, by pair id.
    pub gallery: BTreeMap<String, Vec<u32>>,
}

/// One row's results on one dataset.
#[derive(Debug, Clone)]
pub struct RunResult {
    /// One row per pair (as written to the runs file).
    pub rows: Vec<RunRow>,
    /// The sidecar.
    pub meta: RunMeta,
    /// Whether it came from the cache.
    pub cached: bool,
    /// Every pass's scores per pair, for a row whose method is iterative (`net-iter`).
    pub passes: Option<Vec<PairPasses>>,
}

/// Per pair of a dataset, a flow source's flow or why it has none.
pub type SourceFlows = Arc<Vec<Result<Vec<Vector3>, String>>>;

/// Flows of flow sources, computed once per source and dataset and shared by every
/// segmenter that runs on them.
#[derive(Default)]
pub struct FlowCache {
    flows: Mutex<HashMap<(String, String), SourceFlows>>,
}

impl FlowCache {
    /// The flows of `source` on every pair of `dataset`, computed on first use.
    pub fn get(&self, source: &FlowSource, dataset: &LoadedDataset) -> SourceFlows {
        let key = (source.name(), dataset.name.clone());
        if let Some(found) = self.flows.lock().unwrap_or_else(|e| e.into_inner()).get(&key) {
            return found.clone();
        }
        let flows: Vec<Result<Vec<Vector3>, String>> = dataset
            .pairs
            .par_iter()
            .map(|pair| match source {
                FlowSource::GroundTruth => pair.truth().flow.clone().ok_or_else(|| {
                    format!("{} has no true flow (a cross-instance pair)", pair.id())
                }),
                FlowSource::Method(m) => {
                    guarded(|| m.predict(pair.input()).map_err(|e| e.to_string()))
                        .and_then(|p| p.flow.ok_or_else(|| format!("{} reports no flow", m.name())))
                }
            })
            .collect();
        let flows = Arc::new(flows);
        self.flows.lock().unwrap_or_else(|e| e.into_inner()).insert(key, flows.clone());
        flows
    }
}

impl FlowCache {
    /// Keeps the flows a whole method's row just predicted, so segmenters on that method's
    /// flow do not predict it again.
    pub(crate) fn offer(
        &self,
        method: &str,
        dataset: &str,
        flows: Vec<Result<Vec<Vector3>, String>>,
    ) {
        let key = (method_flow_name(method), dataset.to_owned());
        self.flows.lock().unwrap_or_else(|e| e.into_inner()).entry(key).or_insert(Arc::new(flows));
    }
}

/// Runs `f`, turning a panic into an error message so one pair never aborts the run.
pub(crate) fn guarded<T>(f: impl FnOnce() -> Result<T, String>) -> Result<T, String> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(result) => result,
        Err(panic) => {
            let what = panic
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            Err(format!("panicked: {what}"))
        }
    }
}

/// The prediction of `runner` for `pair` (`flow`: its flow source's flow on the pair, for a
/// segmenter), with panics and errors turned into the reason the pair failed.
pub fn predict_pair(
    runner: &Runner,
    pair: &Pair,
    flow: Option<&Result<Vec<Vector3>, String>>,
) -> Result<Prediction, String> {
    match runner {
        Runner::Oracle => {
            let truth = pair.truth();
            Ok(Prediction {
                flow: truth.flow.clone(),
                segments_p: pairs::parts::part_segments(&truth.part_p),
                segments_q: pairs::parts::part_segments(&truth.part_q),
                motions: truth.motions.clone(),
                corr_mask: None,
                segment_probs: None,
                joints: None,
            })
        }
        Runner::Method(m) => guarded(|| m.predict(pair.input()).map_err(|e| e.to_string())),
        Runner::External(_) => Err("an external row's file is read by run_entry".into()),
        Runner::Segmenter { segmenter, flow: source } => {
            let flow = flow
                .ok_or_else(|| format!("no flow from {}", source.name()))?
                .as_ref()
                .map_err(|e| format!("flow source {} failed: {e}", source.name()))?;
            guarded(|| segmenter.segment(pair.input(), flow).map_err(|e| e.to_string()))
        }
    }
}

/// The method of a row whose passes are scored one by one ([`Method::iterative`]).
fn iterative(runner: &Runner) -> Option<&Arc<dyn Method>> {
    match runner {
        Runner::Method(m) if m.iterative() => Some(m),
        _ => None,
    }
}

/// The prediction of an iterative method (its last pass) and every pass's scores, or why
/// the pair failed; `Ok(None)` scores when a pass could not be scored (the prediction stands).
fn predict_passes(
    method: &dyn Method,
    pair: &Pair,
) -> (Result<Prediction, String>, Option<Vec<crate::running::passes::PassScore>>) {
    match guarded(|| method.predict_passes(pair.input()).map_err(|e| e.to_string())) {
        Ok(mut passes) => {
            let scores = guarded(|| score_passes(pair, &passes));
            if let Err(e) = &scores {
                tracing::warn!(
                    "{} pair {}: its passes were not scored: {e}",
                    method.name(),
                    pair.id()
                );
            }
            match passes.pop() {
                Some(last) => (Ok(last), scores.ok()),
                None => (Err(format!("{} made no pass", method.name())), None),
            }
        }
        Err(reason) => (Err(reason), None),
    }
}

/// Where the runs file of `entry` on `dataset` lives under `runs`.
pub fn runs_path(runs: &Path, dataset: &str, entry: &str) -> PathBuf {
    runs.join(dataset).join(format!("{entry}.csv"))
}

/// The sidecar of the runs file `path` when it matches: this evaluator's runs version, the
/// fingerprint `fingerprint` and the dataset content hash `dataset`.
pub(crate) fn matching_meta(path: &Path, fingerprint: &str, dataset: &str) -> Option<RunMeta> {
    let text = std::fs::read_to_string(path.with_extension("json")).ok()?;
    serde_json::from_str::<RunMeta>(&text).ok().filter(|m| {
        m.version == RUNS_VERSION && m.fingerprint == fingerprint && m.dataset == dataset
    })
}

/// The flow a whole method's prediction offers the segmenters on its flow, or why none.
pub(crate) fn own_flow(
    row: &str,
    prediction: &Result<Prediction, String>,
) -> Result<Vec<Vector3>, String> {
    match prediction {
        Ok(p) => p.flow.clone().ok_or_else(|| format!("{row} reports no flow")),
        Err(reason) => Err(reason.clone()),
    }
}

/// Options of a run.
#[derive(Debug, Clone)]
pub struct RunOptions {
    /// Folder of the runs files (`reports/runs`).
    pub runs: PathBuf,
    /// Recompute even when a matching cached run exists.
    pub force: bool,
    /// Pair ids whose predicted segments are kept for the gallery.
    pub gallery: Vec<String>,
}

/// The cached run of `entry` on `dataset`, if one matches: same runs version, fingerprint and
/// dataset hash, one row per pair, and every requested gallery pair saved (or failed).
pub fn cached_run(
    entry: &Entry,
    dataset: &LoadedDataset,
    options: &RunOptions,
) -> Option<RunResult> {
    let path = runs_path(&options.runs, &dataset.name, &entry.name);
    let meta = matching_meta(&path, &entry.fingerprint_for(&dataset.name), &dataset.content_hash)?;
    let rows = read_rows(&path).ok().filter(|rows| rows.len() == dataset.pairs.len())?;
    let failed = |id: &String| rows.iter().any(|r| &r.pair == id && !r.scored());
    let complete = options.gallery.iter().all(|id| meta.gallery.contains_key(id) || failed(id));
    // An iterative row's passes must be there too, and of this dataset's pairs.
    let passes = match iterative(&entry.runner) {
        Some(_) => {
            let passes = read_passes(&passes_path(&path)).ok()?;
            let known = |p: &PairPasses| dataset.pairs.iter().any(|d| d.id() == p.pair);
            if !passes.iter().all(known) {
                return None;
            }
            Some(passes)
        }
        None => None,
    };
    complete.then_some(RunResult { rows, meta, cached: true, passes })
}

/// Runs `entry` on `dataset` (or reuses its cached run unless `force`), calling `progress`
/// once per pair.
pub fn run_entry(
    entry: &Entry,
    dataset: &LoadedDataset,
    flows: &FlowCache,
    options: &RunOptions,
    progress: &(dyn Fn() + Sync),
) -> Result<RunResult, EvalError> {
    if !options.force {
        if let Some(cached) = cached_run(entry, dataset, options) {
            return Ok(cached);
        }
    }
    let path = runs_path(&options.runs, &dataset.name, &entry.name);
    let meta_path = path.with_extension("json");
    // The flow source runs before the memory reset: its cost is its own row's.
    let (source_flows, runner) = prepare(entry, dataset, flows)?;
    let runner = &runner;
    memory::reset_peak();
    let iterative = iterative(runner);
    type Outcome = (
        RunRow,
        Option<Vec<u32>>,
        Result<Vec<Vector3>, String>,
        Option<Vec<crate::running::passes::PassScore>>,
    );
    let outcomes: Vec<Outcome> = dataset
        .pairs
        .par_iter()
        .enumerate()
        .map(|(i, pair)| {
            let flow = source_flows.as_ref().map(|f| &f[i]);
            let started = Instant::now();
            let (prediction, passes) = match iterative {
                Some(m) => predict_passes(m.as_ref(), pair),
                None => (predict_pair(runner, pair, flow), None),
            };
            let ms = started.elapsed().as_secs_f64() * 1e3;
            let own_flow = own_flow(&entry.name, &prediction);
            let outcome = prediction.and_then(|p| {
                let scored = guarded(|| {
                    score_pair(&p, pair.input(), pair.truth()).map_err(|e| e.to_string())
                });
                scored.map(|s| (s, p.segments_p))
            });
            progress();
            let keep = options.gallery.iter().any(|g| g == pair.id());
            let types = joint_types(pair.truth());
            let category = &pair.provenance().category;
            let row = |outcome| RunRow::new(pair.id(), category, &types, ms, outcome);
            let (record, segments) = match outcome {
                Ok((score, segments)) => (row(Ok(&score)), Some(segments)),
                Err(reason) => (row(Err(&reason)), None),
            };
            (record, segments.filter(|_| keep), own_flow, passes)
        })
        .collect();
    let mut gallery = BTreeMap::new();
    let mut records = Vec::with_capacity(outcomes.len());
    let mut own_flows = Vec::with_capacity(outcomes.len());
    let mut passes = Vec::new();
    for (record, segments, own_flow, pair_passes) in outcomes {
        if let Some(segments) = segments {
            gallery.insert(record.pair.clone(), segments);
        }
        // A pair that failed, or whose passes were not scored, has none.
        if let (Some(scores), true) = (pair_passes, record.scored()) {
            passes.push(PairPasses { pair: record.pair.clone(), passes: scores });
        }
        records.push(record);
        own_flows.push(own_flow);
    }
    let passes = iterative.map(|_| passes);
    if let Runner::Method(m) = &entry.runner {
        flows.offer(m.name(), &dataset.name, own_flows);
    }
    let meta = RunMeta {
        version: RUNS_VERSION,
        fingerprint: entry.fingerprint_for(&dataset.name),
        dataset: dataset.content_hash.clone(),
        peak_mib: memory::peak_mib(),
        gallery,
    };
    replace_run(&meta_path, &meta, || {
        write_rows(&path, &records)?;
        match &passes {
            Some(passes) => write_passes(&passes_path(&path), passes),
            None => Ok(()),
        }
    })?;
    Ok(RunResult { rows: records, meta, cached: false, passes })
}

/// What a row needs before its pairs run on `dataset`: a segmenter's flow source's flows
/// (computed once per source and dataset), and the runner that predicts (an external row's
/// prediction file read and checked against the dataset first, else the row's own).
pub fn prepare(
    entry: &Entry,
    dataset: &LoadedDataset,
    flows: &FlowCache,
) -> Result<(Option<SourceFlows>, Runner), EvalError> {
    let source_flows = match &entry.runner {
        Runner::Segmenter { flow, .. } => Some(flows.get(flow, dataset)),
        _ => None,
    };
    let runner = match &entry.runner {
        Runner::External(files) => Runner::Method(Arc::new(files.load(&entry.name, dataset)?)),
        runner => runner.clone(),
    };
    Ok((source_flows, runner))
}

/// Replaces a run's files: the old sidecar `meta_path` goes first (new results never sit
/// beside an old fingerprint), then `write` writes the results, then the new sidecar.
pub(crate) fn replace_run(
    meta_path: &Path,
    meta: &RunMeta,
    write: impl FnOnce() -> Result<(), EvalError>,
) -> Result<(), EvalError> {
    if meta_path.exists() {
        std::fs::remove_file(meta_path)
            .map_err(|source| EvalError::Io { path: meta_path.to_path_buf(), source })?;
    }
    write()?;
    let json = serde_json::to_string_pretty(meta).expect("run metadata serialises");
    Ok(replace_bytes(meta_path, json.as_bytes())?)
}
