//! Per-pair results of one method on one dataset (`reports/runs/<dataset>/<method>.csv`):
//! one typed [`RunRow`] per pair with its scores, or the reason it failed, and its time,
//! written and read with serde. The leaderboards build their polars columns from its fields.

use std::path::Path;

use pairs::metrics::{JointError, PCC_STEP, PCC_THRESHOLDS};
use serde::{Deserialize, Serialize};

use crate::error::EvalError;
use pairs::atomic::replace_file;
use pairs::metrics::PairScore;

/// One pair's row of a runs file: what the leaderboards sum. Every score is `None` on a
/// failed pair (whose `failed` holds the reason); `epe` and `pcc` are `None` for a method
/// without flow, the `_q` scores for one without Q's segments. Sums and counts rather than
/// means, so that the boards can average over parts, matches and joints.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct RunRow {
    /// The pair's id.
    pub pair: String,
    /// The pair's object category.
    pub category: String,
    /// Why the pair failed; `None` when it was scored.
    pub failed: Option<String>,
    /// Milliseconds the method took on the pair (not part of the leaderboards).
    pub ms: f64,
    /// End-point error of the flow.
    pub epe: Option<f64>,
    /// Rand index of P's segmentation.
    pub ri: Option<f64>,
    /// Summed IoU of P's matched parts.
    pub iou_sum: Option<f64>,
    /// True parts of P.
    pub parts: Option<u32>,
    /// Predicted segments of P.
    pub segments: Option<u32>,
    /// Rand index of Q's segmentation.
    pub ri_q: Option<f64>,
    /// Summed IoU of Q's matched parts.
    pub iou_q_sum: Option<f64>,
    /// True parts of Q.
    pub parts_q: Option<u32>,
    /// Parts matched to a segment with a motion.
    pub matched: Option<u32>,
    /// Summed rotation error of the matched parts, degrees.
    pub rotation_sum: Option<f64>,
    /// Summed translation error of the matched parts.
    pub translation_sum: Option<f64>,
    /// Largest rotation error of a matched part, degrees.
    pub rotation_max: Option<f64>,
    /// 1 when the method gave a flow, 0 when not.
    pub has_flow: Option<u8>,
    /// The kinds of the pair's true joints, sorted and joined by `+` (`prismatic+revolute`),
    /// or `none`: the per-joint-type breakdown of `leaderboard_by_category.csv` (filled for
    /// failed pairs too).
    pub joint_types: String,
    /// True joints scored.
    pub joints: Option<u32>,
    /// Joints whose type was predicted right.
    pub joints_typed: Option<u32>,
    /// Summed axis error, degrees, and the joints that have one.
    pub axis_sum: Option<f64>,
    /// Joints with an axis error.
    pub axis_n: Option<u32>,
    /// Summed distance of revolute axis lines, and the joints that have one.
    pub line_sum: Option<f64>,
    /// Joints with a line distance.
    pub line_n: Option<u32>,
    /// Summed state error of revolute joints, degrees.
    pub state_rev_sum: Option<f64>,
    /// Revolute joints with a state error.
    pub state_rev_n: Option<u32>,
    /// Summed state error of prismatic joints.
    pub state_pri_sum: Option<f64>,
    /// Prismatic joints with a state error.
    pub state_pri_n: Option<u32>,
    /// The PCC curve at thresholds `0, 0.005, ..., 0.25` (columns `pcc_000` .. `pcc_250`);
    /// `PCC_THRESHOLDS` cells, each `None` without flow.
    pub pcc: Vec<Option<f64>>,
}

/// Columns before the PCC curve: [`RunRow`]'s fields in order.
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

/// The header of a runs file.
pub fn header() -> Vec<String> {
    FIXED.iter().map(|s| s.to_string()).chain((0..PCC_THRESHOLDS).map(pcc_column)).collect()
}

/// Name of the PCC column at threshold index `k`.
pub fn pcc_column(k: usize) -> String {
    format!("pcc_{:03}", (k as f64 * PCC_STEP * 1000.0).round() as u32)
}

/// A number as the shortest text that parses back to the same `f64` (the passes cache's
/// cells).
pub(crate) fn num(v: f64) -> String {
    format!("{v:?}")
}

impl RunRow {
    /// The row of a pair: its scores, or why it failed.
    pub fn new(
        pair: &str,
        category: &str,
        joint_types: &str,
        ms: f64,
        outcome: Result<&PairScore, &str>,
    ) -> Self {
        let mut row = Self {
            pair: pair.to_owned(),
            category: category.to_owned(),
            ms,
            joint_types: joint_types.to_owned(),
            pcc: vec![None; PCC_THRESHOLDS],
            ..Self::default()
        };
        let s = match outcome {
            Err(reason) => {
                // An empty cell reads back as scored: a failure always says something.
                let reason = if reason.is_empty() { "failed without a reason" } else { reason };
                row.failed = Some(reason.to_owned());
                return row;
            }
            Ok(s) => s,
        };
        let count = |n: usize| Some(n as u32);
        row.epe = s.flow.as_ref().map(|f| f.epe);
        row.ri = Some(s.p.rand_index);
        row.iou_sum = Some(s.p.iou_sum);
        row.parts = Some(s.parts);
        row.segments = Some(s.segments);
        row.ri_q = s.q.as_ref().map(|q| q.rand_index);
        row.iou_q_sum = s.q.as_ref().map(|q| q.iou_sum);
        row.parts_q = s.q.as_ref().map(|q| q.parts);
        row.matched = count(s.rotation_deg.len());
        row.rotation_sum = Some(s.rotation_deg.iter().sum());
        row.translation_sum = Some(s.translation.iter().sum());
        row.rotation_max = s.rotation_deg.iter().copied().reduce(f64::max);
        row.has_flow = Some(u8::from(s.flow.is_some()));
        row.joints = count(s.joints.len());
        row.joints_typed = count(s.joints.iter().filter(|j| j.type_correct()).count());
        let sum_count = |values: Vec<f64>| (Some(values.iter().sum()), count(values.len()));
        let revolute = |j: &&JointError| j.truth == pairs::JointKind::Revolute;
        let joints = &s.joints;
        (row.axis_sum, row.axis_n) = sum_count(joints.iter().filter_map(|j| j.axis_deg).collect());
        (row.line_sum, row.line_n) =
            sum_count(joints.iter().filter_map(|j| j.line_distance).collect());
        (row.state_rev_sum, row.state_rev_n) =
            sum_count(joints.iter().filter(revolute).filter_map(|j| j.state_error).collect());
        (row.state_pri_sum, row.state_pri_n) = sum_count(
            joints.iter().filter(|j| !revolute(j)).filter_map(|j| j.state_error).collect(),
        );
        if let Some(f) = &s.flow {
            row.pcc = f.pcc.iter().map(|&v| Some(v)).collect();
        }
        row
    }

    /// Whether the pair was scored (did not fail).
    pub fn scored(&self) -> bool {
        self.failed.is_none()
    }
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

/// Writes `rows` to `path`, replacing an old file only once the new one is complete.
pub fn write_rows(path: &Path, rows: &[RunRow]) -> Result<(), EvalError> {
    let bad = |e: csv::Error| EvalError::Csv { path: path.to_path_buf(), message: e.to_string() };
    replace_file(path, |out| {
        // The header by hand: serde names no column of the PCC curve's sequence.
        let mut writer = csv::WriterBuilder::new().has_headers(false).from_writer(out);
        writer.write_record(header()).map_err(bad)?;
        for row in rows {
            if row.pcc.len() != PCC_THRESHOLDS {
                let (pair, n) = (&row.pair, row.pcc.len());
                let message = format!("pair {pair}: {n} PCC values, expected {PCC_THRESHOLDS}");
                return Err(EvalError::Csv { path: path.to_path_buf(), message });
            }
            writer.serialize(row).map_err(bad)?;
        }
        writer.flush().map_err(|source| EvalError::Io { path: path.to_path_buf(), source })
    })
}

/// The rows of a cache CSV (`header` checked, each row deserialised by position, so a
/// sequence may end it), each with its line in the file. Errors name the file, the line
/// (a quoted cell spanning lines moves later rows past `i + 2`) and the column.
pub(crate) fn read_csv<T: serde::de::DeserializeOwned>(
    path: &Path,
    header: &[String],
) -> Result<Vec<(u64, T)>, EvalError> {
    let bad = |message: String| EvalError::Csv { path: path.to_path_buf(), message };
    let mut reader = csv::Reader::from_path(path).map_err(|e| bad(e.to_string()))?;
    let found = reader.headers().map_err(|e| bad(e.to_string()))?;
    if found.iter().ne(header.iter().map(String::as_str)) {
        return Err(bad("the header is not this evaluator's (rerun the row)".into()));
    }
    reader
        .records()
        .enumerate()
        .map(|(i, record)| {
            let record = record.map_err(|e| bad(read_error(&e)))?;
            let line = record.position().map_or(i as u64 + 2, csv::Position::line);
            let row = record
                .deserialize(None)
                .map_err(|e| bad(format!("line {line}: {}", cell_error(&e, header))))?;
            Ok((line, row))
        })
        .collect()
}

/// A CSV error reading a row, prefixed with the row's line in the file where it is known.
fn read_error(error: &csv::Error) -> String {
    match error.kind() {
        csv::ErrorKind::UnequalLengths { pos: Some(pos), expected_len, len } => {
            format!("line {}: {len} fields, the header has {expected_len}", pos.line())
        }
        _ => match error.position() {
            Some(pos) => format!("line {}: {error}", pos.line()),
            None => error.to_string(),
        },
    }
}

/// A CSV error of one row, naming the column of the cell that failed to deserialise.
fn cell_error(error: &csv::Error, header: &[String]) -> String {
    match error.kind() {
        csv::ErrorKind::Deserialize { err, .. } => {
            match err.field().and_then(|f| header.get(f as usize)) {
                Some(name) => format!("column {name}: {}", err.kind()),
                None => err.to_string(),
            }
        }
        _ => error.to_string(),
    }
}

/// Reads a runs file, checking that its header is this version's and every row is whole.
pub fn read_rows(path: &Path) -> Result<Vec<RunRow>, EvalError> {
    Ok(read_csv(path, &header())?.into_iter().map(|(_, row)| row).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use pairs::metrics::{FlowScore, SegmentScore};

    fn score(flow: bool) -> PairScore {
        let pcc = std::array::from_fn(|k| (k as f64 / 60.0).min(1.0));
        PairScore {
            flow: flow.then_some(FlowScore { epe: 0.1 + 1e-17, pcc }),
            p: SegmentScore { rand_index: 2.0 / 3.0, iou_sum: 1.75, parts: 2 },
            q: flow.then_some(SegmentScore { rand_index: 0.5, iou_sum: 1.0, parts: 3 }),
            parts: 2,
            segments: 3,
            rotation_deg: vec![1.5, 7.25],
            translation: vec![0.125, 1e-300],
            joints: Vec::new(),
        }
    }

    #[test]
    fn rows_round_trip_through_the_runs_file() {
        let rows = vec![
            RunRow::new("a", "laptop", "revolute", 12.5, Ok(&score(true))),
            RunRow::new("b", "oven", "none", 0.1, Ok(&score(false))),
            RunRow::new("c", "fan", "prismatic+revolute", 3.0, Err("no consensus, at all")),
        ];
        assert_eq!(rows[0].rotation_max, Some(7.25));
        assert_eq!((rows[1].has_flow, rows[1].epe, rows[1].pcc[3]), (Some(0), None, None));
        assert_eq!((rows[2].ri, rows[2].joint_types.as_str()), (None, "prismatic+revolute"));
        let dir = tempfile::tempdir().expect("a temp dir");
        let path = dir.path().join("m.csv");
        write_rows(&path, &rows).expect("written");
        assert_eq!(read_rows(&path).expect("read"), rows);
        let text = std::fs::read_to_string(&path).expect("read");
        assert!(text.starts_with(&header().join(",")));
        assert!(text.contains("\"no consensus, at all\""));
    }

    #[test]
    fn malformed_runs_files_are_errors_naming_the_line() {
        let dir = tempfile::tempdir().expect("a temp dir");
        let path = dir.path().join("m.csv");
        let good = RunRow::new("a", "laptop", "revolute", 12.5, Ok(&score(true)));
        write_rows(&path, &[good.clone(), good]).expect("written");
        let text = std::fs::read_to_string(&path).expect("read");
        let lines: Vec<&str> = text.lines().collect();
        let cases = [
            (
                format!("{}\n{}\n", lines[0], lines[1].replacen("12.5", "fast", 1)),
                "line 2: column ms",
            ),
            (format!("{}\n{}\n{}\n", lines[0], lines[1], "a,laptop"), "line 3"),
            (format!("pair,category\n{}\n", lines[1]), "header"),
        ];
        for (text, expected) in cases {
            std::fs::write(&path, text).expect("written");
            let err = read_rows(&path).expect_err(expected).to_string();
            assert!(err.contains(expected) && err.contains("m.csv"), "{err}");
        }
        // A reason over two lines: the next row's error names its line in the file, 4.
        let panicked = RunRow::new("p", "c", "none", 1.0, Err("assertion failed\nleft: 1"));
        let good = RunRow::new("a", "laptop", "revolute", 12.5, Ok(&score(true)));
        write_rows(&path, &[panicked, good]).expect("written");
        let text = std::fs::read_to_string(&path).expect("read").replacen(",12.5,", ",fast,", 1);
        std::fs::write(&path, text).expect("written");
        let err = read_rows(&path).expect_err("not a number").to_string();
        assert!(err.contains("line 4: column ms"), "{err}");
        // An empty reason would read back as a scored pair.
        let silent = RunRow::new("s", "c", "none", 1.0, Err(""));
        write_rows(&path, std::slice::from_ref(&silent)).expect("written");
        assert!(!read_rows(&path).expect("read")[0].scored());
        let short = RunRow { pcc: vec![None; 3], ..RunRow::new("z", "c", "none", 1.0, Err("x")) };
        let err = write_rows(&path, &[short]).expect_err("a short curve").to_string();
        assert!(err.contains("3 PCC values"), "{err}");
    }
}
