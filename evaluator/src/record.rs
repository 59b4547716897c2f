//! Per-pair results of one method on one dataset (`reports/runs/<dataset>/<method>.csv`):
//! one row per pair with its scores, or the reason it failed, and its time.

use std::path::Path;

use pairs::metrics::{PCC_STEP, PCC_THRESHOLDS};

use crate::error::EvalError;
use crate::score::PairScore;
use pairs::atomic::replace_file;

/// One pair's outcome for one method.
#[derive(Debug, Clone, PartialEq)]
pub struct PairRecord {
    /// The pair's id.
    pub pair: String,
    /// The pair's object category.
    pub category: String,
    /// The kinds of the pair's true joints, sorted and joined by `+` (`prismatic+revolute`),
    /// or `none`: the per-joint-type breakdown of `leaderboard_by_category.csv`.
    pub joint_types: String,
    /// Milliseconds the method took on the pair (not part of the leaderboards).
    pub ms: f64,
    /// The scores, or why the pair failed.
    pub outcome: Result<PairScore, String>,
}

/// Columns before the PCC curve; the curve follows as `pcc_000` .. `pcc_250` (threshold in
/// thousandths).
const FIXED: [&str; 28] = [
    "pair",
    "category",
    "failed",
    "ms",
    "epe",
    "ri",
    "iou_sum",
    "parts",
    "segments",
    "ri_q",
    "iou_q_sum",
    "parts_q",
    "matched",
    "rotation_sum",
    "translation_sum",
    "rotation_max",
    "has_flow",
    "joint_types",
    "joints",
    "joints_typed",
    "axis_sum",
    "axis_n",
    "line_sum",
    "line_n",
    "state_rev_sum",
    "state_rev_n",
    "state_pri_sum",
    "state_pri_n",
];

/// Index of the `joint_types` column (filled for failed pairs too).
const JOINT_TYPES: usize = 17;

/// The header of a runs file.
pub fn header() -> Vec<String> {
    FIXED.iter().map(|s| s.to_string()).chain((0..PCC_THRESHOLDS).map(pcc_column)).collect()
}

/// Name of the PCC column at threshold index `k`.
pub fn pcc_column(k: usize) -> String {
    format!("pcc_{:03}", (k as f64 * PCC_STEP * 1000.0).round() as u32)
}

/// A number as the shortest text that parses back to the same `f64` (the runs cache's cells).
pub(crate) fn num(v: f64) -> String {
    // Round-trip exact (shortest representation that parses back to the same f64).
    format!("{v:?}")
}

fn opt(v: Option<f64>) -> String {
    v.map(num).unwrap_or_default()
}

impl PairRecord {
    /// The record as a CSV row in [`header`] order.
    pub fn to_row(&self) -> Vec<String> {
        let mut row = vec![self.pair.clone(), self.category.clone()];
        match &self.outcome {
            Err(reason) => {
                row.push(reason.clone());
                row.push(num(self.ms));
                row.resize(FIXED.len() + PCC_THRESHOLDS, String::new());
                row[JOINT_TYPES] = self.joint_types.clone();
            }
            Ok(s) => {
                let sum = |v: &[f64]| v.iter().sum::<f64>();
                let max = s
                    .rotation_deg
                    .iter()
                    .copied()
                    .fold(None, |m: Option<f64>, v| Some(m.map_or(v, |m| m.max(v))));
                row.extend([
                    String::new(),
                    num(self.ms),
                    opt(s.flow.as_ref().map(|f| f.epe)),
                    num(s.p.rand_index),
                    num(s.p.iou_sum),
                    s.parts.to_string(),
                    s.segments.to_string(),
                    opt(s.q.as_ref().map(|q| q.rand_index)),
                    opt(s.q.as_ref().map(|q| q.iou_sum)),
                    s.q.as_ref().map(|q| q.parts.to_string()).unwrap_or_default(),
                    s.rotation_deg.len().to_string(),
                    num(sum(&s.rotation_deg)),
                    num(sum(&s.translation)),
                    opt(max),
                    u8::from(s.flow.is_some()).to_string(),
                    self.joint_types.clone(),
                ]);
                row.extend(joint_cells(&s.joints));
                match &s.flow {
                    Some(f) => row.extend(f.pcc.iter().map(|&v| num(v))),
                    None => row.resize(FIXED.len() + PCC_THRESHOLDS, String::new()),
                }
            }
        }
        row
    }
}

/// The joint columns of a scored pair: joints, joints typed right, then sum and count of
/// the axis errors, line distances, revolute and prismatic state errors.
fn joint_cells(joints: &[pairs::metrics::JointError]) -> Vec<String> {
    let sum_count = |values: Vec<f64>| [num(values.iter().sum()), values.len().to_string()];
    let revolute = |j: &&pairs::metrics::JointError| j.truth == pairs::JointKind::Revolute;
    let mut cells = vec![
        joints.len().to_string(),
        joints.iter().filter(|j| j.type_correct()).count().to_string(),
    ];
    cells.extend(sum_count(joints.iter().filter_map(|j| j.axis_deg).collect()));
    cells.extend(sum_count(joints.iter().filter_map(|j| j.line_distance).collect()));
    cells.extend(sum_count(joints.iter().filter(revolute).filter_map(|j| j.state_error).collect()));
    cells.extend(sum_count(
        joints.iter().filter(|j| !revolute(j)).filter_map(|j| j.state_error).collect(),
    ));
    cells
}

/// The `joint_types` cell of a pair: its true joints' kinds, sorted, deduplicated and joined
/// by `+`, or `none`.
pub fn joint_types(truth: &pairs::GroundTruth) -> String {
    let mut kinds: Vec<&str> = truth.joints.iter().map(|j| j.kind.as_str()).collect();
    kinds.sort_unstable();
    kinds.dedup();
    if kinds.is_empty() {
        "none".into()
    } else {
        kinds.join("+")
    }
}

/// Writes `records` to `path`, replacing an old file only once the new one is complete.
pub fn write_records(path: &Path, records: &[PairRecord]) -> Result<(), EvalError> {
    replace_file(path, |out| {
        let bad =
            |e: csv::Error| EvalError::Csv { path: path.to_path_buf(), message: e.to_string() };
        let mut writer = csv::Writer::from_writer(out);
        writer.write_record(header()).map_err(bad)?;
        for r in records {
            writer.write_record(r.to_row()).map_err(bad)?;
        }
        writer.flush().map_err(|source| EvalError::Io { path: path.to_path_buf(), source })
    })
}

/// A runs file read back as rows of named string cells (the leaderboard parses the numbers).
#[derive(Debug, Clone)]
pub struct RunTable {
    /// Column names.
    pub header: Vec<String>,
    /// Rows, each as long as the header.
    pub rows: Vec<Vec<String>>,
}

/// Reads a runs file, checking that its header is this version's.
pub fn read_records(path: &Path) -> Result<RunTable, EvalError> {
    let bad = |message: String| EvalError::Csv { path: path.to_path_buf(), message };
    let mut reader = csv::Reader::from_path(path).map_err(|e| bad(e.to_string()))?;
    let found: Vec<String> =
        reader.headers().map_err(|e| bad(e.to_string()))?.iter().map(str::to_owned).collect();
    if found != header() {
        return Err(bad("the header is not this evaluator's (rerun the method)".into()));
    }
    let rows = reader
        .records()
        .map(|r| r.map(|r| r.iter().map(str::to_owned).collect()).map_err(|e| bad(e.to_string())))
        .collect::<Result<_, _>>()?;
    Ok(RunTable { header: found, rows })
}
