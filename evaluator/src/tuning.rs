//! Cross-validated baselines: each segmentation baseline's parameters are chosen *per flow
//! source* on the validation split, on the very flow its row is scored on, by the metric the
//! leaderboard ranks (IoU over all ground-truth parts, the Rand index as tie-break), as the
//! paper's baselines were. A [`Grid`] names a row's swept parameters: ordered values per
//! axis, every combination scored; when the best value of an axis (or a value tied with the
//! best) sits on that axis's edge the axis is widened by one more value (up to its bounds)
//! and the new combinations are scored, until the best lies inside, a bound is reached or
//! [`Grid::max_rounds`] widenings were made.
//!
//! Tuning is a cached step: the sweep is written to `<reports>/tuning/<row>.csv` (every
//! candidate with its scores, the chosen one marked) with a sidecar under
//! `<reports>/runs/tuning/` naming the grid, the flow source's fingerprint and the validation
//! sets' content hashes; a sweep is reused while all three match, so new network weights
//! retune the rows on the network's flow by themselves. Only datasets of the validation
//! split reach [`tune`]: a test dataset is refused.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use articulated::categories::Split;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::datasets::LoadedDataset;
use crate::error::EvalError;
use crate::rows::grid::Grid;
use crate::rows::registry::Runner;
use crate::running::run::{predict_pair, FlowCache};
use pairs::atomic::replace_bytes;
use pairs::metrics::score_pair;

/// One scored candidate of a sweep.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Candidate {
    /// The parameter values, in axis order.
    pub values: Vec<f64>,
    /// Widening round that added it (0: the starting grid).
    pub round: usize,
    /// Validation IoU (over all ground-truth parts of all pairs).
    pub iou: f64,
    /// Validation Rand index (mean over pairs).
    pub ri: f64,
    /// Validation pairs it failed on (counted with IoU 0 and RI 0).
    pub failed: usize,
}

/// A finished sweep.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Sweep {
    /// The row it tunes (`seqransac@net-flow`).
    pub row: String,
    /// Axis names.
    pub axes: Vec<String>,
    /// Every candidate, in the order scored.
    pub candidates: Vec<Candidate>,
    /// Index of the chosen one.
    pub chosen: usize,
    /// Validation pairs scored.
    pub pairs: usize,
}

impl Sweep {
    /// The chosen values, as `name=value` pairs joined by spaces.
    pub fn chosen_label(&self) -> String {
        label(&self.axes, &self.candidates[self.chosen].values)
    }
}

/// `name=value` pairs joined by spaces.
pub fn label(axes: &[String], values: &[f64]) -> String {
    axes.iter().zip(values).map(|(a, v)| format!("{a}={v}")).collect::<Vec<_>>().join(" ")
}

/// What a cached sweep was made from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct SweepMeta {
    key: String,
    sweep: Sweep,
}

/// Version of the tuning files; bump it when the selection rule changes.
pub const TUNING_VERSION: u32 = 1;

/// The sweep's CSV under `reports` (`tuning/<row>.csv`).
pub fn sweep_path(reports: &Path, row: &str) -> PathBuf {
    reports.join("tuning").join(format!("{row}.csv"))
}

fn meta_path(reports: &Path, row: &str) -> PathBuf {
    reports.join("runs").join("tuning").join(format!("{row}.json"))
}

/// The cache key of a sweep of `grid` for `row` on `flow_fingerprint`'s flow over
/// `validation`.
pub fn sweep_key(
    row: &str,
    grid: &Grid,
    flow_fingerprint: &str,
    validation: &[&LoadedDataset],
) -> String {
    let sets: Vec<String> =
        validation.iter().map(|d| format!("{}:{}", d.name, d.content_hash)).collect();
    format!(
        "v{TUNING_VERSION} {row} grid {} flow {flow_fingerprint} on {} code {}",
        grid.fingerprint(),
        sets.join(","),
        env!("SOURCE_HASH_SCORING")
    )
}

/// The cached sweep for `key`, if its sidecar and CSV are there and match.
pub fn cached_sweep(reports: &Path, row: &str, key: &str) -> Option<Sweep> {
    let text = std::fs::read_to_string(meta_path(reports, row)).ok()?;
    let meta: SweepMeta = serde_json::from_str(&text).ok()?;
    (meta.key == key && sweep_path(reports, row).exists()).then_some(meta.sweep)
}

/// Validation IoU and RI of one runner over the validation pairs (flows from `flows`).
fn score_runner(
    runner: &Runner,
    validation: &[&LoadedDataset],
    flows: &FlowCache,
) -> (f64, f64, usize, usize) {
    let (mut iou, mut parts, mut ri, mut pairs, mut failed) = (0.0, 0u64, 0.0, 0usize, 0usize);
    for dataset in validation {
        let source = match runner {
            Runner::Segmenter { flow, .. } => Some(flows.get(flow, dataset)),
            _ => None,
        };
        let scores: Vec<(f64, u32, f64, bool)> = dataset
            .pairs
            .par_iter()
            .enumerate()
            .map(|(i, pair)| {
                let flow = source.as_ref().map(|f| &f[i]);
                match predict_pair(runner, pair, flow).and_then(|p| {
                    score_pair(&p, pair.input(), pair.truth()).map_err(|e| e.to_string())
                }) {
                    Ok(s) => (s.p.iou_sum, s.p.parts, s.p.rand_index, false),
                    // A failed pair scores 0 on each of its parts.
                    Err(_) => (0.0, distinct(&pair.truth().part_p), 0.0, true),
                }
            })
            .collect();
        for (i, p, r, f) in scores {
            iou += i;
            parts += u64::from(p);
            ri += r;
            pairs += 1;
            failed += usize::from(f);
        }
    }
    (iou / parts.max(1) as f64, ri / pairs.max(1) as f64, pairs, failed)
}

/// Number of distinct part ids.
fn distinct(parts: &[u8]) -> u32 {
    let mut seen = [false; 256];
    parts.iter().for_each(|&p| seen[usize::from(p)] = true);
    seen.iter().filter(|&&s| s).count() as u32
}

/// Whether candidate `a` beats `b`: higher IoU, then higher RI (ties keep the earlier).
fn better(a: &Candidate, b: &Candidate) -> bool {
    a.iou > b.iou || (a.iou == b.iou && a.ri > b.ri)
}

/// Every combination of the axes' values, in row-major order.
fn combinations(axes: &[Vec<f64>]) -> Vec<Vec<f64>> {
    axes.iter().fold(vec![Vec::new()], |acc, values| {
        acc.iter()
            .flat_map(|prefix| {
                values.iter().map(move |v| {
                    let mut point = prefix.clone();
                    point.push(*v);
                    point
                })
            })
            .collect()
    })
}

/// Runs the sweep of `grid` for `row` on the validation datasets (computing the flow
/// source's validation flows through `flows`), reusing a cached one for the same key.
/// Writes the sweep's CSV and sidecar under `reports`. Refuses any dataset that is not of
/// the validation split.
pub fn tune(
    row: &str,
    grid: &Grid,
    flow_fingerprint: &str,
    validation: &[&LoadedDataset],
    flows: &FlowCache,
    reports: &Path,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<Sweep, EvalError> {
    if let Some(bad) = validation.iter().find(|d| d.split != Some(Split::Validation)) {
        return Err(EvalError::NotValidation {
            name: bad.name.clone(),
            split: bad.split.map_or("unknown", Split::as_str).to_owned(),
        });
    }
    let key = sweep_key(row, grid, flow_fingerprint, validation);
    if let Some(sweep) = cached_sweep(reports, row, &key) {
        return Ok(sweep);
    }
    let axes_names: Vec<String> = grid.axes.iter().map(|a| a.name.to_owned()).collect();
    let mut values: Vec<Vec<f64>> = grid.axes.iter().map(|a| a.values.clone()).collect();
    let mut candidates: Vec<Candidate> = Vec::new();
    let mut pairs = 0;
    for round in 0..=grid.max_rounds {
        for point in combinations(&values) {
            if candidates.iter().any(|c| c.values == point) {
                continue;
            }
            let (runner, _) = (grid.build)(&point);
            let (iou, ri, n, failed) = score_runner(&runner, validation, flows);
            pairs = n;
            candidates.push(Candidate { values: point, round, iou, ri, failed });
            progress(candidates.len());
        }
        // The best and every candidate tied with it: a plateau that reaches an edge may
        // go on past it.
        let best = &candidates[best_index(&candidates)];
        let tied: Vec<&Candidate> =
            candidates.iter().filter(|c| c.iou == best.iou && c.ri == best.ri).collect();
        let mut widened = false;
        for (a, axis) in grid.axes.iter().enumerate() {
            let list = &mut values[a];
            if list.len() < 2 {
                continue;
            }
            let (low, high) = (list[0], list[list.len() - 1]);
            if tied.iter().any(|c| c.values[a] == low) && low / axis.factor >= axis.lower {
                list.insert(0, low / axis.factor);
                widened = true;
            }
            if tied.iter().any(|c| c.values[a] == high) && high * axis.factor <= axis.upper {
                list.push(high * axis.factor);
                widened = true;
            }
        }
        if !widened || round == grid.max_rounds {
            break;
        }
    }
    let chosen = best_index(&candidates);
    let sweep = Sweep { row: row.to_owned(), axes: axes_names, candidates, chosen, pairs };
    write_sweep(reports, &sweep)?;
    let meta_path = meta_path(reports, row);
    let json = serde_json::to_string_pretty(&SweepMeta { key, sweep: sweep.clone() })
        .expect("a sweep serialises");
    replace_bytes(&meta_path, json.as_bytes())?;
    Ok(sweep)
}

/// Index of the best candidate (first of equals).
fn best_index(candidates: &[Candidate]) -> usize {
    let mut best = 0;
    for (i, c) in candidates.iter().enumerate() {
        if better(c, &candidates[best]) {
            best = i;
        }
    }
    best
}

/// Writes `<reports>/tuning/<row>.csv`: one line per candidate, in the order scored.
pub fn write_sweep(reports: &Path, sweep: &Sweep) -> Result<(), EvalError> {
    let path = sweep_path(reports, &sweep.row);
    let mut text = String::new();
    let _ = writeln!(text, "{},round,pairs,failed,iou,ri,chosen", sweep.axes.join(","));
    for (i, c) in sweep.candidates.iter().enumerate() {
        let values: Vec<String> = c.values.iter().map(|v| format!("{v}")).collect();
        let _ = writeln!(
            text,
            "{},{},{},{},{:.4},{:.4},{}",
            values.join(","),
            c.round,
            sweep.pairs,
            c.failed,
            c.iou,
            c.ri,
            i == sweep.chosen
        );
    }
    Ok(replace_bytes(&path, text.as_bytes())?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn combinations_are_row_major() {
        let c = combinations(&[vec![1.0, 2.0], vec![10.0, 20.0, 30.0]]);
        assert_eq!(c.len(), 6);
        assert_eq!(c[0], [1.0, 10.0]);
        assert_eq!(c[2], [1.0, 30.0]);
        assert_eq!(c[5], [2.0, 30.0]);
    }

    #[test]
    fn iou_ranks_then_ri() {
        let c = |iou, ri| Candidate { values: vec![], round: 0, iou, ri, failed: 0 };
        assert_eq!(best_index(&[c(0.5, 0.9), c(0.6, 0.1), c(0.6, 0.2), c(0.6, 0.2)]), 2);
    }
}
