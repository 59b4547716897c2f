//! The paper's Table 4, a board written from the per-pass scores that the iterative row's
//! run keeps in the runs cache ([`crate::running::passes`]): the iterative network (`net-iter`)
//! scored after every pass, as
//! `iterations.csv` (one row per dataset and iteration: EPE, RI, IoU, and how many pairs
//! were still changing) and `iterations.svg`/`.png` (the three curves); and `iterations_joints.csv`,
//! the joints estimated from its first and last passes (`pairs::metrics::JointScores`). A pair that
//! converged before iteration t keeps its last pass's prediction at t, as the procedure
//! stops there. Averages follow the leaderboards: EPE and RI over pairs, IoU over all
//! ground-truth parts of all pairs.

use std::io::Write;
use std::path::{Path, PathBuf};

use plotters::prelude::*;

use crate::boards::plots::PALETTE;
use crate::error::EvalError;
use crate::running::passes::{PairPasses, PassScore};
use pairs::atomic::replace_file;
use pairs::metrics::JointScores;

pub use crate::rows::standard::ITERATIVE_ROW;

/// The scores of one iteration on one dataset.
#[derive(Debug, Clone, PartialEq)]
pub struct IterationRow {
    /// Dataset name.
    pub dataset: String,
    /// Iteration, from 1 (the single pass).
    pub iteration: usize,
    /// Pairs scored.
    pub pairs: usize,
    /// Pairs whose procedure was still running at this iteration.
    pub running: usize,
    /// Mean end-point error.
    pub epe: f64,
    /// Mean Rand index.
    pub rand_index: f64,
    /// IoU over all ground-truth parts.
    pub iou: f64,
}

/// The joint scores of the first pass (`net`) and of the last (`net-iter`) on one dataset.
#[derive(Debug, Clone, PartialEq)]
pub struct JointRow {
    /// Dataset name.
    pub dataset: String,
    /// `net` (the first pass) or `net-iter` (the last).
    pub method: String,
    /// The scores.
    pub scores: JointScores,
}

/// The iteration table of one dataset and the joint scores of the first and last passes,
/// from the per-pass scores of the iterative row's run ([`crate::running::passes`], in pair order;
/// pairs that failed have none).
pub fn iteration_table(dataset: &str, scored: &[PairPasses]) -> (Vec<IterationRow>, Vec<JointRow>) {
    let scored: Vec<&[PassScore]> =
        scored.iter().map(|p| p.passes.as_slice()).filter(|p| !p.is_empty()).collect();
    let mut joints = [JointScores::default(), JointScores::default()];
    for passes in &scored {
        if let (Some(first), Some(last)) = (passes.first(), passes.last()) {
            joints[0].merge(first.joints.clone());
            joints[1].merge(last.joints.clone());
        }
    }
    let most = scored.iter().map(|s| s.len()).max().unwrap_or(0);
    let [first, last] = joints;
    let joint_rows = [("net", first), ("net-iter", last)]
        .into_iter()
        .map(|(m, scores)| JointRow { dataset: dataset.to_owned(), method: m.to_owned(), scores })
        .collect();
    let rows = (0..most)
        .map(|t| {
            let at: Vec<&PassScore> = scored.iter().map(|s| &s[t.min(s.len() - 1)]).collect();
            let n = at.len().max(1) as f64;
            let parts: usize = at.iter().map(|s| s.parts).sum();
            IterationRow {
                dataset: dataset.to_owned(),
                iteration: t + 1,
                pairs: at.len(),
                running: scored.iter().filter(|s| s.len() > t).count(),
                epe: at.iter().map(|s| s.epe).sum::<f64>() / n,
                rand_index: at.iter().map(|s| s.rand_index).sum::<f64>() / n,
                iou: at.iter().map(|s| s.iou_sum).sum::<f64>() / parts.max(1) as f64,
            }
        })
        .collect();
    (rows, joint_rows)
}

/// The iteration board as text, one line per dataset and iteration, then per dataset the
/// joints of the first and last passes (what `evaluator` prints at the end).
pub fn summary_lines(rows: &[IterationRow], joint_rows: &[JointRow]) -> Vec<String> {
    let iterations = rows.iter().map(|r| {
        format!(
            "{} iteration {:2}: EPE {:.4} RI {:.4} IoU {:.4} ({} of {} pairs still running)",
            r.dataset, r.iteration, r.epe, r.rand_index, r.iou, r.running, r.pairs
        )
    });
    let joints = joint_rows.iter().map(|r| {
        let s = &r.scores;
        format!(
            "{} {} joints: {} of {} typed right, median axis error {:.1}°, median pivot distance {:.3}",
            r.dataset,
            r.method,
            s.type_correct,
            s.joints,
            median(&s.axis_errors),
            median(&s.pivot_distances)
        )
    });
    iterations.chain(joints).collect()
}

/// Writes `iterations.csv`, the plot and `iterations_joints.csv` into `dir`; returns the files written.
pub fn write_iterations(
    dir: &Path,
    rows: &[IterationRow],
    joint_rows: &[JointRow],
) -> Result<Vec<PathBuf>, EvalError> {
    let csv = dir.join("iterations.csv");
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |source| EvalError::Io { path, source }
    };
    replace_file(&csv, |w| -> Result<(), EvalError> {
        writeln!(w, "dataset,iteration,pairs,running,epe,rand_index,iou").map_err(io(&csv))?;
        for r in rows {
            writeln!(
                w,
                "{},{},{},{},{:.6},{:.6},{:.6}",
                r.dataset, r.iteration, r.pairs, r.running, r.epe, r.rand_index, r.iou
            )
            .map_err(io(&csv))?;
        }
        Ok(())
    })?;
    let joints_csv = dir.join("iterations_joints.csv");
    replace_file(&joints_csv, |w| -> Result<(), EvalError> {
        writeln!(w, "dataset,method,joints,type_accuracy,estimated,median_axis_error_deg,median_pivot_distance")
            .map_err(io(&joints_csv))?;
        for r in joint_rows {
            let s = &r.scores;
            writeln!(
                w,
                "{},{},{},{:.4},{},{:.3},{:.4}",
                r.dataset,
                r.method,
                s.joints,
                s.type_accuracy(),
                s.axis_errors.len(),
                median(&s.axis_errors),
                median(&s.pivot_distances)
            )
            .map_err(io(&joints_csv))?;
        }
        Ok(())
    })?;
    let mut written = vec![csv, joints_csv];
    for (path, text) in [(dir.join("iterations.svg"), true), (dir.join("iterations.png"), false)] {
        let message = |e: String| EvalError::Plot { path: path.clone(), message: e };
        if text {
            draw(SVGBackend::new(&path, (800, 500)).into_drawing_area(), rows, true)
        } else {
            draw(BitMapBackend::new(&path, (800, 500)).into_drawing_area(), rows, false)
        }
        .map_err(message)?;
        written.push(path);
    }
    Ok(written)
}

/// Three lines per dataset over the iterations: RI (blue), IoU (orange) and 1 - EPE / 0.2
/// (green, so that all three rise as the flow improves and share the unit interval).
fn draw<DB: DrawingBackend>(
    root: DrawingArea<DB, plotters::coord::Shift>,
    rows: &[IterationRow],
    text: bool,
) -> Result<(), String> {
    let fail = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(fail)?;
    let last = rows.iter().map(|r| r.iteration).max().unwrap_or(1).max(2);
    let mut builder = ChartBuilder::on(&root);
    builder.margin(20);
    if text {
        builder
            .caption("net-iter: scores per iteration", ("sans-serif", 22))
            .x_label_area_size(40)
            .y_label_area_size(50);
    }
    // A float x axis: plotters' integer ranges loop forever computing key points when the
    // label count is 0 (the PNG, which has no text).
    let mut chart = builder.build_cartesian_2d(1.0..last as f64, 0.0..1.0).map_err(fail)?;
    let mut mesh = chart.configure_mesh();
    if text {
        mesh.x_desc("iteration").y_desc("RI, IoU, 1 - EPE/0.2");
    } else {
        mesh.x_labels(0).y_labels(0);
    }
    mesh.draw().map_err(fail)?;
    let mut datasets: Vec<&str> = rows.iter().map(|r| r.dataset.as_str()).collect();
    datasets.dedup();
    type Metric = fn(&IterationRow) -> f64;
    let metrics: [(&str, Metric); 3] =
        [("RI", |r| r.rand_index), ("IoU", |r| r.iou), ("1 - EPE/0.2", |r| 1.0 - r.epe / 0.2)];
    for (d, dataset) in datasets.iter().enumerate() {
        for (k, (name, metric)) in metrics.iter().enumerate() {
            let colour = PALETTE[(d * 3 + k) % PALETTE.len()];
            let points = rows
                .iter()
                .filter(|r| r.dataset == *dataset)
                .map(|r| (r.iteration as f64, metric(r)));
            let series =
                chart.draw_series(LineSeries::new(points, colour.stroke_width(2))).map_err(fail)?;
            if text {
                series.label(format!("{name} {dataset}")).legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
                });
            }
        }
    }
    if text {
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::LowerRight)
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .draw()
            .map_err(fail)?;
    }
    root.present().map_err(fail)
}

/// The median of `values` (NaN when empty).
fn median(values: &[f64]) -> f64 {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    match v.len() {
        0 => f64::NAN,
        n if n % 2 == 1 => v[n / 2],
        n => (v[n / 2 - 1] + v[n / 2]) / 2.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pass(epe: f64, iou_sum: f64, parts: usize, typed: usize) -> PassScore {
        let joints = JointScores {
            joints: 1,
            type_correct: typed,
            axis_errors: vec![epe],
            pivot_distances: vec![],
        };
        PassScore { epe, rand_index: 1.0 - epe, iou_sum, parts, joints }
    }

    #[test]
    fn a_converged_pair_keeps_its_last_pass_and_iou_averages_over_parts() {
        let scored = [
            PairPasses {
                pair: "a".into(),
                passes: vec![pass(0.1, 1.0, 2, 0), pass(0.05, 2.0, 2, 1)],
            },
            PairPasses { pair: "b".into(), passes: vec![pass(0.3, 1.0, 3, 1)] },
            PairPasses { pair: "c".into(), passes: vec![] },
        ];
        let (rows, joints) = iteration_table("d", &scored);
        let close = |a: f64, b: f64| (a - b).abs() < 1e-12;
        assert_eq!(rows.len(), 2);
        assert_eq!((rows[0].pairs, rows[0].running, rows[1].running), (2, 2, 1));
        assert!(close(rows[0].epe, 0.2) && close(rows[1].epe, 0.175));
        assert!(close(rows[0].iou, 2.0 / 5.0) && close(rows[1].iou, 3.0 / 5.0));
        assert!(close(rows[1].rand_index, 1.0 - 0.175));
        assert_eq!((joints[0].method.as_str(), joints[1].method.as_str()), ("net", "net-iter"));
        assert_eq!((joints[0].scores.joints, joints[0].scores.type_correct), (2, 1));
        assert_eq!((joints[1].scores.joints, joints[1].scores.type_correct), (2, 2));
        assert_eq!(joints[1].scores.axis_errors, vec![0.05, 0.3]);
    }

    #[test]
    fn median_of_odd_even_and_empty_lists() {
        assert_eq!(median(&[3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&[4.0, 1.0, 2.0, 3.0]), 2.5);
        assert!(median(&[]).is_nan());
    }

    #[test]
    fn writes_the_table_the_joints_and_both_plots() {
        let dir = tempfile::tempdir().expect("a temp dir");
        let row = |iteration, epe| IterationRow {
            dataset: "sf2f".into(),
            iteration,
            pairs: 2,
            running: 2,
            epe,
            rand_index: 0.6,
            iou: 0.4,
        };
        let joints = [JointRow {
            dataset: "sf2f".into(),
            method: "net-iter".into(),
            scores: JointScores { joints: 2, type_correct: 1, ..JointScores::default() },
        }];
        let files =
            write_iterations(dir.path(), &[row(1, 0.07), row(2, 0.06)], &joints).expect("written");
        assert_eq!(files.len(), 4);
        assert!(files.iter().all(|f| f.exists()));
        let csv = std::fs::read_to_string(dir.path().join("iterations.csv")).expect("read");
        assert_eq!(csv.lines().nth(2), Some("sf2f,2,2,2,0.060000,0.600000,0.400000"));
        let joints_csv =
            std::fs::read_to_string(dir.path().join("iterations_joints.csv")).expect("read");
        assert!(joints_csv.lines().nth(1).expect("a row").starts_with("sf2f,net-iter,2,0.5000,0,"));
    }
}
