//! The set board (`leaderboard_sets.csv`): every segmentation row on every set dataset, its
//! per-set scores (`crate::running::sets`) averaged over the scored sets: multi-scan and
//! per-scan mIoU and Rand index in MultiBodySync's conventions, and the mean rotation and
//! translation errors of the matched parts' motions to every view (docs/METRICS.md, "Sets").
//! A failed set is left out of the means and counted in `failed`, as a failed pair is on
//! the pair boards.

use std::io::Write as _;
use std::path::Path;

use pairs::atomic::replace_file;

use crate::error::EvalError;
use crate::rows::registry::Entry;
use crate::running::sets::SetRow;

/// The file of the set board under the reports folder.
pub const SET_BOARD_FILE: &str = "leaderboard_sets.csv";

/// One row's results on one set dataset, as the board holds them.
pub struct ScoredSets<'a> {
    /// The set dataset's name.
    pub dataset: &'a str,
    /// The row.
    pub entry: &'a Entry,
    /// One row per set.
    pub rows: &'a [SetRow],
}

/// One line of the set board.
#[derive(Debug, Clone, PartialEq)]
pub struct SetBoardRow {
    /// The set dataset.
    pub dataset: String,
    /// The row's name (`seqransac@net-flow`).
    pub row: String,
    /// The method (the row's name without its `@flow`).
    pub method: String,
    /// The flow source (`own` for a whole method).
    pub flow_source: String,
    /// Whether the row reads the truth.
    pub oracle: bool,
    /// Views per set (the largest K of the dataset's sets).
    pub views: u32,
    /// Mean multi-scan mIoU over the scored sets (NaN when none was).
    pub multi_scan_miou: f64,
    /// Mean per-scan mIoU.
    pub per_scan_miou: f64,
    /// Mean multi-scan Rand index.
    pub multi_scan_ri: f64,
    /// Mean per-scan Rand index.
    pub per_scan_ri: f64,
    /// Mean rotation error (degrees) of the matched parts' motions to every view k >= 1,
    /// over all of them (NaN when there is none: the row estimates no motion).
    pub rotation_deg: f64,
    /// Mean translation error of the same motions.
    pub translation: f64,
    /// Sets of the dataset.
    pub sets: usize,
    /// Sets the row failed on.
    pub failed: usize,
}

/// The board's lines, in the order of `scored` (datasets, then rows in registry order).
pub fn set_board(scored: &[ScoredSets]) -> Vec<SetBoardRow> {
    scored
        .iter()
        .map(|s| {
            let ok: Vec<&SetRow> = s.rows.iter().filter(|r| r.scored()).collect();
            let mean = |f: fn(&SetRow) -> Option<f64>| {
                let values: Vec<f64> = ok.iter().filter_map(|r| f(r)).collect();
                if values.is_empty() {
                    f64::NAN
                } else {
                    values.iter().sum::<f64>() / values.len() as f64
                }
            };
            SetBoardRow {
                dataset: s.dataset.to_owned(),
                row: s.entry.name.clone(),
                method: s.entry.method().to_owned(),
                flow_source: s.entry.flow_source(),
                oracle: s.entry.oracle,
                views: s.rows.iter().map(|r| r.views).max().unwrap_or(0),
                multi_scan_miou: mean(|r| r.multi_scan_iou),
                per_scan_miou: mean(|r| r.per_scan_iou),
                multi_scan_ri: mean(|r| r.multi_scan_ri),
                per_scan_ri: mean(|r| r.per_scan_ri),
                rotation_deg: ratio(&ok, |r| r.rotation_sum),
                translation: ratio(&ok, |r| r.translation_sum),
                sets: s.rows.len(),
                failed: s.rows.len() - ok.len(),
            }
        })
        .collect()
}

/// A sum over sets divided by their matched motions (NaN without any).
fn ratio(rows: &[&SetRow], sum: fn(&SetRow) -> Option<f64>) -> f64 {
    let matched: u32 = rows.iter().filter_map(|r| r.matched).sum();
    if matched == 0 {
        return f64::NAN;
    }
    rows.iter().filter_map(|r| sum(r)).sum::<f64>() / f64::from(matched)
}

/// A board cell: four decimals, as the pair boards write them; empty for NaN.
fn cell(v: f64) -> String {
    if v.is_finite() {
        format!("{v:.4}")
    } else {
        String::new()
    }
}

/// Writes the set board into `reports` (replacing an old one only once the new one is
/// complete); nothing when there is no line.
pub fn write_set_board(reports: &Path, rows: &[SetBoardRow]) -> Result<(), EvalError> {
    if rows.is_empty() {
        return Ok(());
    }
    let path = reports.join(SET_BOARD_FILE);
    let io = |source| EvalError::Io { path: path.clone(), source };
    replace_file(&path, |w| -> Result<(), EvalError> {
        writeln!(
            w,
            "dataset,method,flow_source,oracle,views,multi_scan_miou,per_scan_miou,\
             multi_scan_ri,per_scan_ri,rotation_deg,translation,sets,failed"
        )
        .map_err(io)?;
        for r in rows {
            writeln!(
                w,
                "{},{},{},{},{},{},{},{},{},{},{},{},{}",
                r.dataset,
                r.method,
                r.flow_source,
                r.oracle,
                r.views,
                cell(r.multi_scan_miou),
                cell(r.per_scan_miou),
                cell(r.multi_scan_ri),
                cell(r.per_scan_ri),
                cell(r.rotation_deg),
                cell(r.translation),
                r.sets,
                r.failed
            )
            .map_err(io)?;
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rows::registry::Registry;
    use std::sync::Arc;

    fn row(set: &str, scores: Option<[f64; 4]>) -> SetRow {
        let mut r = SetRow { set: set.into(), views: 4, ..SetRow::default() };
        match scores {
            Some([a, b, c, d]) => {
                (r.multi_scan_iou, r.per_scan_iou) = (Some(a), Some(b));
                (r.multi_scan_ri, r.per_scan_ri) = (Some(c), Some(d));
                (r.matched, r.rotation_sum, r.translation_sum) = (Some(2), Some(3.0), Some(0.5));
            }
            None => r.failed = Some("no".into()),
        }
        r
    }

    #[test]
    fn means_leave_failed_sets_out_and_count_them() {
        let mut registry = Registry::new();
        registry.oracle().combine(
            Arc::new(crate::rows::reference::OnePart),
            crate::rows::registry::FlowSource::GroundTruth,
            "v1",
            None,
        );
        let entry = &registry.entries()[1];
        let rows = [
            row("a", Some([1.0, 0.5, 1.0, 0.75])),
            row("b", Some([0.5, 0.25, 0.5, 0.25])),
            row("c", None),
        ];
        let board = set_board(&[ScoredSets { dataset: "s", entry, rows: &rows }]);
        assert_eq!(board.len(), 1);
        let b = &board[0];
        assert_eq!((b.method.as_str(), b.flow_source.as_str()), ("one-part", "gt-flow"));
        assert_eq!((b.multi_scan_miou, b.per_scan_miou), (0.75, 0.375));
        assert_eq!((b.multi_scan_ri, b.per_scan_ri), (0.75, 0.5));
        assert_eq!((b.sets, b.failed, b.views), (3, 1, 4));
        // Motion errors average over the matched motions of the scored sets: 6° / 4, 1 / 4.
        assert_eq!((b.rotation_deg, b.translation), (1.5, 0.25));
        let dir = tempfile::tempdir().expect("a temporary folder");
        write_set_board(dir.path(), &board).expect("written");
        let text = std::fs::read_to_string(dir.path().join(SET_BOARD_FILE)).expect("read");
        assert_eq!(
            text.lines().nth(1),
            Some("s,one-part,gt-flow,true,4,0.7500,0.3750,0.7500,0.5000,1.5000,0.2500,3,1")
        );
    }
}
