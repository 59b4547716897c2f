//! The leaderboards (polars): per-pair results of every row on every dataset, gathered in one
//! DataFrame, summed per (dataset, method, flow source) and turned into
//! `leaderboard_flow.csv`, `leaderboard_seg.csv`, `joints.csv`, `leaderboard_by_category.csv`
//! (every segmentation row per category and per joint-type mix) and `timings.csv`. Means
//! follow docs/METRICS.md: EPE, PCC and RI average over scored pairs, IoU over all
//! ground-truth parts, motion errors over all matched parts (with the matched parts per pair
//! beside them), joint errors over the joints that have each. Failed pairs are left out of
//! the means and counted in `failed`. The `oracle` column marks rows that read the truth.

use std::path::Path;

use pairs::metrics::{pcc_auc, PCC_STEP, PCC_THRESHOLDS};
use polars::prelude::*;

use crate::error::EvalError;
use crate::rows::registry::{Board, Entry};
use crate::running::record::{pcc_column, RunRow};
use crate::running::run::RunResult;
use pairs::atomic::replace_file;

/// One row's run on one dataset, as the leaderboards read it.
pub struct Scored<'a> {
    /// The dataset's name.
    pub dataset: &'a str,
    /// Whether the dataset's pairs are cross-instance (no true flow): its rows stay off the
    /// flow board.
    pub cross_instance: bool,
    /// The row.
    pub entry: &'a Entry,
    /// Its results.
    pub result: &'a RunResult,
}

/// Leaderboard tables, ready to write.
pub struct Leaderboards {
    /// Flow accuracy per (dataset, method, flow source).
    pub flow: DataFrame,
    /// Segmentation accuracy per (dataset, method, flow source).
    pub seg: DataFrame,
    /// Joint estimation per (dataset, method, flow source), for rows that yield motions.
    pub joints: DataFrame,
    /// Segmentation accuracy per row and category, and per row and joint-type mix.
    pub by_category: DataFrame,
    /// Milliseconds per pair and peak memory per (dataset, row).
    pub timings: DataFrame,
    /// The mean PCC curve of every row of the flow leaderboard.
    pub curves: Vec<PccCurve>,
}

/// A row's mean PCC curve on a dataset (thresholds `0, 0.005, ..., 0.25`).
#[derive(Debug, Clone, PartialEq)]
pub struct PccCurve {
    /// The dataset's name.
    pub dataset: String,
    /// The row's name.
    pub method: String,
    /// Mean fraction of points under each threshold.
    pub values: Vec<f64>,
}

fn table_err(what: &str) -> impl Fn(PolarsError) -> EvalError + '_ {
    move |source| EvalError::Table { what: what.to_owned(), source }
}

/// Key columns of the per-pair frame: the row's and the pair's.
const KEYS: [&str; 6] = ["dataset", "method", "flow_source", "oracle", "category", "joint_types"];

/// The keys a row is identified by on the boards.
const ROW_KEYS: [&str; 4] = ["dataset", "method", "flow_source", "oracle"];

/// A per-pair number of a [`RunRow`] (`None` where the row has none).
type Field = fn(&RunRow) -> Option<f64>;

fn count(n: Option<u32>) -> Option<f64> {
    n.map(f64::from)
}

fn flag(b: bool) -> Option<f64> {
    Some(f64::from(u8::from(b)))
}

/// Numeric per-pair columns summed by the leaderboards, each from its [`RunRow`] field.
const SUMMED: [(&str, Field); 25] = [
    ("epe", |r| r.epe),
    ("ri", |r| r.ri),
    ("iou_sum", |r| r.iou_sum),
    ("parts", |r| count(r.parts)),
    ("ri_q", |r| r.ri_q),
    ("iou_q_sum", |r| r.iou_q_sum),
    ("parts_q", |r| count(r.parts_q)),
    ("matched", |r| count(r.matched)),
    ("rotation_sum", |r| r.rotation_sum),
    ("translation_sum", |r| r.translation_sum),
    ("has_flow", |r| r.has_flow.map(f64::from)),
    ("failed", |r| flag(!r.scored())),
    ("scored", |r| flag(r.scored())),
    ("parts_right", |r| r.parts.zip(r.segments).and_then(|(p, s)| flag(p == s))),
    ("joints", |r| count(r.joints)),
    ("joints_typed", |r| count(r.joints_typed)),
    ("axis_sum", |r| r.axis_sum),
    ("axis_n", |r| count(r.axis_n)),
    ("line_sum", |r| r.line_sum),
    ("line_n", |r| count(r.line_n)),
    ("state_rev_sum", |r| r.state_rev_sum),
    ("state_rev_n", |r| count(r.state_rev_n)),
    ("state_pri_sum", |r| r.state_pri_sum),
    ("state_pri_n", |r| count(r.state_pri_n)),
    ("has_q", |r| r.ri_q.and(Some(1.0))),
];

/// The per-pair frame of the runs that `keep` selects.
fn pairs_frame(runs: &[Scored], keep: impl Fn(&Scored) -> bool) -> Result<DataFrame, EvalError> {
    let runs: Vec<&Scored> = runs.iter().filter(|r| keep(r)).collect();
    let mut keys: [Vec<String>; 6] = Default::default();
    let mut columns: Vec<Vec<Option<f64>>> = vec![Vec::new(); SUMMED.len() + PCC_THRESHOLDS];
    for run in runs {
        let rows = &run.result.rows;
        let n = rows.len();
        keys[0].extend(std::iter::repeat_n(run.dataset.to_owned(), n));
        keys[1].extend(std::iter::repeat_n(run.entry.name.clone(), n));
        keys[2].extend(std::iter::repeat_n(run.entry.flow_source(), n));
        keys[3].extend(std::iter::repeat_n(run.entry.oracle.to_string(), n));
        keys[4].extend(rows.iter().map(|r| r.category.clone()));
        keys[5].extend(rows.iter().map(|r| r.joint_types.clone()));
        for (column, (_, field)) in columns.iter_mut().zip(SUMMED) {
            column.extend(rows.iter().map(field));
        }
        for k in 0..PCC_THRESHOLDS {
            columns[SUMMED.len() + k].extend(rows.iter().map(|r| r.pcc.get(k).copied().flatten()));
        }
    }
    let names =
        SUMMED.iter().map(|(name, _)| name.to_string()).chain((0..PCC_THRESHOLDS).map(pcc_column));
    let mut frame: Vec<Column> =
        KEYS.iter().zip(keys).map(|(name, values)| Column::new((*name).into(), values)).collect();
    frame.extend(names.zip(columns).map(|(name, values)| Column::new(name.into(), values)));
    DataFrame::new_infer_height(frame).map_err(table_err("per-pair results"))
}

/// Sums every numeric column per `by` (key columns), in first-seen order.
#[allow(deprecated)] // The eager aggregations: polars' lazy engine would double the build.
fn summed_by(frame: &DataFrame, by: &[&str]) -> Result<DataFrame, EvalError> {
    let numeric: Vec<String> =
        frame.get_column_names().iter().skip(KEYS.len()).map(|s| s.to_string()).collect();
    frame
        .group_by_stable(by.iter().copied())
        .and_then(|g| g.select(numeric).sum())
        .map_err(table_err("leaderboard sums"))
}

/// Sums per row (dataset, method, flow source, oracle).
fn summed(frame: &DataFrame) -> Result<DataFrame, EvalError> {
    summed_by(frame, &ROW_KEYS)
}

fn column(frame: &DataFrame, name: &str) -> Result<Vec<f64>, EvalError> {
    let col = frame.column(&format!("{name}_sum")).map_err(table_err(name))?;
    let values = col.f64().map_err(table_err(name))?;
    Ok(values.iter().map(|v| v.unwrap_or(0.0)).collect())
}

fn ratio(num: &[f64], den: &[f64]) -> Vec<Option<f64>> {
    num.iter().zip(den).map(|(n, d)| (*d > 0.0).then(|| n / d)).collect()
}

fn keys(frame: &DataFrame) -> Result<Vec<Column>, EvalError> {
    ROW_KEYS.iter().map(|k| frame.column(k).cloned().map_err(table_err(k))).collect()
}

fn counts(name: &str, values: &[f64]) -> Column {
    Column::new(name.into(), values.iter().map(|&v| v.round() as u32).collect::<Vec<_>>())
}

fn strings(frame: &DataFrame, name: &str) -> Result<Vec<String>, EvalError> {
    let col = frame.column(name).map_err(table_err(name))?;
    let values = col.str().map_err(table_err(name))?;
    Ok(values.iter().map(|v| v.unwrap_or_default().to_owned()).collect())
}

/// The flow leaderboard and its PCC curves from summed per-pair results.
fn flow_board(sums: &DataFrame) -> Result<(DataFrame, Vec<PccCurve>), EvalError> {
    let pairs = column(sums, "has_flow")?;
    let curve: Vec<Vec<Option<f64>>> = (0..PCC_THRESHOLDS)
        .map(|k| column(sums, &pcc_column(k)).map(|c| ratio(&c, &pairs)))
        .collect::<Result<_, _>>()?;
    let at = |t: f64| curve[(t / PCC_STEP).round() as usize].clone();
    let auc: Vec<Option<f64>> = (0..pairs.len())
        .map(|row| {
            let mut values = [0.0; PCC_THRESHOLDS];
            for (value, c) in values.iter_mut().zip(&curve) {
                *value = c[row]?;
            }
            Some(pcc_auc(&values))
        })
        .collect();
    let (datasets, methods) = (strings(sums, "dataset")?, strings(sums, "method")?);
    let curves = (0..pairs.len())
        .filter_map(|row| {
            let values: Option<Vec<f64>> = curve.iter().map(|c| c[row]).collect();
            let (dataset, method) = (datasets[row].clone(), methods[row].clone());
            values.map(|values| PccCurve { dataset, method, values })
        })
        .collect();
    let mut columns = keys(sums)?;
    columns.extend([
        Column::new("epe".into(), ratio(&column(sums, "epe")?, &pairs)),
        Column::new("pcc_0.05".into(), at(0.05)),
        Column::new("pcc_0.10".into(), at(0.10)),
        Column::new("pcc_auc".into(), auc),
        counts("pairs", &pairs),
        counts("failed", &column(sums, "failed")?),
    ]);
    let frame = DataFrame::new_infer_height(columns).map_err(table_err("flow leaderboard"))?;
    Ok((frame, curves))
}

/// The segmentation leaderboard from summed per-pair results.
fn seg_board(sums: &DataFrame) -> Result<DataFrame, EvalError> {
    let scored = column(sums, "scored")?;
    let matched = column(sums, "matched")?;
    let mut columns = keys(sums)?;
    columns.extend([
        Column::new("ri".into(), ratio(&column(sums, "ri")?, &scored)),
        Column::new("iou".into(), ratio(&column(sums, "iou_sum")?, &column(sums, "parts")?)),
        Column::new("rotation_deg".into(), ratio(&column(sums, "rotation_sum")?, &matched)),
        Column::new("translation".into(), ratio(&column(sums, "translation_sum")?, &matched)),
        Column::new("matched_per_pair".into(), ratio(&matched, &scored)),
        Column::new("part_count_acc".into(), ratio(&column(sums, "parts_right")?, &scored)),
        Column::new("ri_q".into(), ratio(&column(sums, "ri_q")?, &column(sums, "has_q")?)),
        Column::new("iou_q".into(), ratio(&column(sums, "iou_q_sum")?, &column(sums, "parts_q")?)),
        counts("pairs", &scored),
        counts("failed", &column(sums, "failed")?),
    ]);
    DataFrame::new_infer_height(columns).map_err(table_err("segmentation leaderboard"))
}

/// The joints board from summed per-pair results: rows whose predictions carry motions.
fn joints_board(sums: &DataFrame) -> Result<DataFrame, EvalError> {
    let joints = column(sums, "joints")?;
    let keep: Vec<bool> = joints.iter().map(|&j| j > 0.0).collect();
    let mut columns = keys(sums)?;
    columns.extend([
        counts("joints", &joints),
        Column::new("type_acc".into(), ratio(&column(sums, "joints_typed")?, &joints)),
        Column::new("axis_deg".into(), ratio(&column(sums, "axis_sum")?, &column(sums, "axis_n")?)),
        Column::new(
            "axis_line_dist".into(),
            ratio(&column(sums, "line_sum")?, &column(sums, "line_n")?),
        ),
        Column::new(
            "state_revolute_deg".into(),
            ratio(&column(sums, "state_rev_sum")?, &column(sums, "state_rev_n")?),
        ),
        Column::new(
            "state_prismatic".into(),
            ratio(&column(sums, "state_pri_sum")?, &column(sums, "state_pri_n")?),
        ),
        counts("pairs", &column(sums, "scored")?),
        counts("failed", &column(sums, "failed")?),
    ]);
    let frame = DataFrame::new_infer_height(columns).map_err(table_err("joints board"))?;
    let mask = BooleanChunked::from_slice("keep".into(), &keep);
    frame.filter(&mask).map_err(table_err("joints board"))
}

/// Segmentation (and, where a row has one, flow) accuracy per row and `breakdown` value.
fn breakdown_board(frame: &DataFrame, breakdown: &str) -> Result<DataFrame, EvalError> {
    let mut by = ROW_KEYS.to_vec();
    by.push(breakdown);
    let sums = summed_by(frame, &by)?;
    let scored = column(&sums, "scored")?;
    let value = sums.column(breakdown).map_err(table_err(breakdown))?.clone();
    let mut columns = keys(&sums)?;
    columns.extend([
        Column::new("breakdown".into(), vec![breakdown.trim_end_matches('s'); sums.height()]),
        value.with_name("value".into()),
        Column::new("epe".into(), ratio(&column(&sums, "epe")?, &column(&sums, "has_flow")?)),
        Column::new("ri".into(), ratio(&column(&sums, "ri")?, &scored)),
        Column::new("iou".into(), ratio(&column(&sums, "iou_sum")?, &column(&sums, "parts")?)),
        Column::new("part_count_acc".into(), ratio(&column(&sums, "parts_right")?, &scored)),
        counts("pairs", &scored),
        counts("failed", &column(&sums, "failed")?),
    ]);
    DataFrame::new_infer_height(columns).map_err(table_err("per-category board"))
}

/// Milliseconds per pair (mean over all pairs, failed ones included) and peak memory.
fn timings(runs: &[Scored]) -> Result<DataFrame, EvalError> {
    let mut cols: [Vec<String>; 2] = Default::default();
    let (mut ms, mut peak) = (Vec::new(), Vec::new());
    for run in runs {
        cols[0].push(run.dataset.to_owned());
        cols[1].push(run.entry.name.clone());
        let times: Vec<f64> = run.result.rows.iter().map(|r| r.ms).collect();
        ms.push((!times.is_empty()).then(|| times.iter().sum::<f64>() / times.len() as f64));
        peak.push(run.result.meta.peak_mib);
    }
    let [dataset, method] = cols;
    DataFrame::new_infer_height(vec![
        Column::new("dataset".into(), dataset),
        Column::new("method".into(), method),
        Column::new("ms_per_pair".into(), ms),
        Column::new("peak_mib".into(), peak),
    ])
    .map_err(table_err("timings"))
}

/// A row's lines of the written flow and segmentation boards in `reports`, one per dataset
/// (`net: dataset sf2f, epe 0.057, ...`); none where a board is missing or lacks the row.
pub fn row_lines(reports: &Path, row: &str) -> Vec<String> {
    let mut lines = Vec::new();
    for (board, columns) in [
        ("leaderboard_flow.csv", &["epe", "pcc_0.05", "pcc_0.10"][..]),
        ("leaderboard_seg.csv", &["ri", "iou", "pairs", "failed"][..]),
    ] {
        let Ok(mut reader) = csv::Reader::from_path(reports.join(board)) else { continue };
        let Ok(header) = reader.headers().cloned() else { continue };
        let at = |name: &str| header.iter().position(|h| h == name);
        for record in reader.records().flatten() {
            if at("method").and_then(|i| record.get(i)) != Some(row) {
                continue;
            }
            let cells: Vec<String> = std::iter::once("dataset")
                .chain(columns.iter().copied())
                .filter_map(|c| Some(format!("{c} {}", record.get(at(c)?)?)))
                .collect();
            lines.push(format!("{row}: {}", cells.join(", ")));
        }
    }
    lines
}

impl Leaderboards {
    /// Builds the three tables from every run.
    pub fn build(runs: &[Scored]) -> Result<Self, EvalError> {
        let flow = summed(&pairs_frame(runs, |r| {
            r.entry.board != Board::Segmentation && !r.cross_instance
        })?)?;
        let seg_pairs = pairs_frame(runs, |r| r.entry.board != Board::Flow)?;
        let seg = summed(&seg_pairs)?;
        let (flow, curves) = flow_board(&flow)?;
        let mut by_category = breakdown_board(&seg_pairs, "category")?;
        by_category
            .vstack_mut(&breakdown_board(&seg_pairs, "joint_types")?)
            .map_err(table_err("per-category board"))?;
        Ok(Self {
            flow,
            seg: seg_board(&seg)?,
            joints: joints_board(&seg)?,
            by_category,
            timings: timings(runs)?,
            curves,
        })
    }

    /// Writes `leaderboard_flow.csv`, `leaderboard_seg.csv` and `timings.csv` into `dir`.
    pub fn write(&mut self, dir: &Path) -> Result<(), EvalError> {
        for (name, frame) in [
            ("leaderboard_flow.csv", &mut self.flow),
            ("leaderboard_seg.csv", &mut self.seg),
            ("joints.csv", &mut self.joints),
            ("leaderboard_by_category.csv", &mut self.by_category),
            ("timings.csv", &mut self.timings),
        ] {
            write_csv(&dir.join(name), frame)?;
        }
        Ok(())
    }
}

/// Writes `frame` as CSV with four decimals (fixed, so reruns are byte-identical).
pub fn write_csv(path: &Path, frame: &mut DataFrame) -> Result<(), EvalError> {
    replace_file(path, |out| {
        CsvWriter::new(out)
            .include_header(true)
            .with_float_precision(Some(4))
            .finish(frame)
            .map_err(|source| EvalError::Table { what: path.display().to_string(), source })
    })
}
