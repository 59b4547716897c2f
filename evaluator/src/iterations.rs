//! The paper's Table 4: the iterative network (`net-iter`) scored after every pass, as
//! `iterations.csv` (one row per dataset and iteration: EPE, RI, IoU, and how many pairs
//! were still changing) and `iterations.svg`/`.png` (the three curves); and `iterations_joints.csv`,
//! the joints estimated from its first and last passes ([`crate::joints`]). A pair that
//! converged before iteration t keeps its last pass's prediction at t, as the procedure
//! stops there. Averages follow the leaderboards: EPE and RI over pairs, IoU over all
//! ground-truth parts of all pairs.

use std::io::Write;
use std::path::{Path, PathBuf};

use model::method::NetworkMethod;
use pairs::metrics::{epe, matched_iou, rand_index};
use pairs::Pair;
use plotters::prelude::*;
use rayon::prelude::*;

use crate::error::EvalError;
use crate::joints::{median, JointScores};
use crate::plots::PALETTE;
use pairs::atomic::replace_file;

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

/// Per pair and iteration: EPE, RI, the summed IoU and the part count; pairs that failed
/// are skipped (with a warning) so one bad pair does not hide the table.
type PairScores = Vec<(f64, f64, f64, usize)>;

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

/// One pair's scores per iteration and the joint scores of its first and last passes.
fn score_pair(
    method: &NetworkMethod,
    pair: &Pair,
) -> Result<(PairScores, [JointScores; 2]), String> {
    let inference = method.infer(pair.input()).map_err(|e| e.to_string())?;
    let mut joints = [JointScores::default(), JointScores::default()];
    if let (Some(first), Some(last)) = (inference.iterations.first(), inference.iterations.last()) {
        joints[0].add(pair, &first.prediction);
        joints[1].add(pair, &last.prediction);
    }
    let truth = pair.truth();
    inference
        .iterations
        .iter()
        .map(|it| {
            let p = &it.prediction;
            let flow = p.flow.as_deref().unwrap_or_default();
            let e = epe(flow, &truth.flow).map_err(|e| e.to_string())?;
            let ri = rand_index(&p.segments_p, &truth.part_p).map_err(|e| e.to_string())?;
            let m = matched_iou(&p.segments_p, &truth.part_p).map_err(|e| e.to_string())?;
            Ok((e, ri, m.iou.iter().sum(), m.iou.len()))
        })
        .collect::<Result<PairScores, String>>()
        .map(|scores| (scores, joints))
}

/// Scores every iteration of `method` on `pairs`, and the joints of its first and last
/// passes; `tick` is called after each pair. Pairs run in parallel; the results are
/// gathered in pair order, so the table does not depend on the thread count.
pub fn iteration_table(
    method: &NetworkMethod,
    dataset: &str,
    pairs: &[Pair],
    tick: impl Fn() + Sync,
) -> (Vec<IterationRow>, Vec<JointRow>) {
    let results: Vec<_> = pairs
        .par_iter()
        .map(|pair| {
            let result = score_pair(method, pair);
            tick();
            result
        })
        .collect();
    let mut scored: Vec<PairScores> = Vec::with_capacity(pairs.len());
    let mut joints = [JointScores::default(), JointScores::default()];
    for (pair, result) in pairs.iter().zip(results) {
        match result {
            Ok((s, pair_joints)) if !s.is_empty() => {
                scored.push(s);
                for (total, one) in joints.iter_mut().zip(pair_joints) {
                    total.merge(one);
                }
            }
            Ok(_) => {}
            Err(e) => tracing::warn!("{dataset} pair {}: {e}", pair.id()),
        }
    }
    let most = scored.iter().map(Vec::len).max().unwrap_or(0);
    let [first, last] = joints;
    let joint_rows = [("net", first), ("net-iter", last)]
        .into_iter()
        .map(|(m, scores)| JointRow { dataset: dataset.to_owned(), method: m.to_owned(), scores })
        .collect();
    let rows = (0..most)
        .map(|t| {
            let at: Vec<&(f64, f64, f64, usize)> =
                scored.iter().map(|s| &s[t.min(s.len() - 1)]).collect();
            let n = at.len().max(1) as f64;
            let parts: usize = at.iter().map(|s| s.3).sum();
            IterationRow {
                dataset: dataset.to_owned(),
                iteration: t + 1,
                pairs: at.len(),
                running: scored.iter().filter(|s| s.len() > t).count(),
                epe: at.iter().map(|s| s.0).sum::<f64>() / n,
                rand_index: at.iter().map(|s| s.1).sum::<f64>() / n,
                iou: at.iter().map(|s| s.2).sum::<f64>() / parts.max(1) as f64,
            }
        })
        .collect();
    (rows, joint_rows)
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

#[cfg(test)]
mod tests {
    use super::*;
    use burn::prelude::Device;
    use model::config::TrainConfig;
    use model::inference::InferenceParams;
    use model::network::PartNet;
    use pairs::synthetic::hinge_pair;

    #[test]
    fn the_table_does_not_depend_on_the_thread_count() {
        let config = TrainConfig::built_in("tiny");
        let pairs: Vec<Pair> =
            (0..3).map(|k| hinge_pair(&format!("h{k}"), 12, 0.3 + 0.3 * k as f32)).collect();
        let table = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("pool");
            pool.install(|| {
                let net = PartNet::seeded(&config.network, &Device::flex(), 5);
                let params = InferenceParams { max_iterations: 3, ..InferenceParams::iterative() };
                let method = NetworkMethod::with_params("net-iter", net, params);
                iteration_table(&method, "hinges", &pairs, || {})
            })
        };
        let (rows, joints) = table(1);
        assert!((1..=3).contains(&rows.len()));
        assert!(rows.iter().all(|r| r.pairs == 3 && r.epe.is_finite()));
        assert_eq!(rows[0].running, 3);
        assert_eq!(joints.len(), 2);
        assert_eq!(joints[0].scores.joints, 3, "one hinge per pair");
        assert_eq!(table(2), (rows, joints));
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
