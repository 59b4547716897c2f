//! The leaderboards leave failed pairs out of their means: built from hand-made runs in which
//! some pairs failed (and one row failed on every pair), every mean equals the one computed
//! by hand over the scored pairs only, `pairs` counts those and `failed` the others.

use std::collections::BTreeMap;
use std::sync::Arc;

use evaluator::boards::leaderboard::{Leaderboards, Scored};
use evaluator::rows::registry::{Board, Entry, Runner};
use evaluator::running::record::RunRow;
use evaluator::running::run::{RunMeta, RunResult, RUNS_VERSION};
use pairs::metrics::{pcc_auc, PCC_THRESHOLDS};
use pairs::metrics::{FlowScore, PairScore, SegmentScore};
use pairs::{Method, MethodError, PairInput, Prediction};
use polars::prelude::DataFrame;

/// A method that is only a name: the leaderboards read runs, they never predict.
struct Named(&'static str);

impl Method for Named {
    fn name(&self) -> &str {
        self.0
    }

    fn predict(&self, _: &PairInput) -> Result<Prediction, MethodError> {
        Ok(Prediction::default())
    }
}

fn entry(name: &'static str, board: Board) -> Entry {
    let runner = Runner::Method(Arc::new(Named(name)));
    let fingerprint = format!("{name} v1");
    Entry { name: name.into(), runner, board, fingerprint, grid: None, oracle: false }
}

/// Scores of the `i`-th scored pair of a run, all different from one pair to the next (and
/// from one run to the next through `salt`), with a flow if `flow`.
fn score(i: usize, salt: f64, flow: bool) -> PairScore {
    let x = i as f64 + salt;
    let parts = 2 + (i % 3) as u32;
    let matched = 1 + i % 3;
    let flow = flow.then(|| {
        let mut pcc = [0.0; PCC_THRESHOLDS];
        for (k, v) in pcc.iter_mut().enumerate() {
            *v = (k as f64 * (0.013 + 0.007 * x)).min(1.0);
        }
        FlowScore { epe: 0.011 + 0.017 * x + 0.003 * x * x, pcc }
    });
    PairScore {
        flow,
        p: SegmentScore {
            rand_index: 0.41 + 0.09 * (x % 5.0),
            iou_sum: f64::from(parts) * (0.93 - 0.07 * (x % 4.0)),
            parts,
        },
        // Q is segmented on every other pair only.
        q: i.is_multiple_of(2).then(|| SegmentScore {
            rand_index: 0.37 + 0.11 * (x % 3.0),
            iou_sum: 0.8 + 0.05 * x,
            parts: 2,
        }),
        parts,
        // The part count is right on pairs 0, 3, 6, ...
        segments: if i.is_multiple_of(3) { parts } else { parts + 1 },
        rotation_deg: (0..matched).map(|m| 1.5 + 2.25 * x + 0.5 * m as f64).collect(),
        translation: (0..matched).map(|m| 0.02 + 0.003 * x * (m + 1) as f64).collect(),
        joints: Vec::new(),
    }
}

/// A run of `pairs` pairs in which the pairs in `failed` failed; the others get
/// [`score`]s. Failed pairs take long (ms) so that timings would show them.
fn records(pairs: usize, failed: &[usize], salt: f64, flow: bool) -> Vec<PairRecord> {
    let mut scored = 0;
    (0..pairs)
        .map(|k| {
            let outcome = if failed.contains(&k) {
                Err(format!("method failed on pair {k}"))
            } else {
                scored += 1;
                Ok(score(scored - 1, salt, flow))
            };
            let ms = if outcome.is_err() { 1000.0 + k as f64 } else { 10.0 + k as f64 };
            let (pair, category) = (format!("pair-{k}"), "cat".into());
            PairRecord { pair, category, joint_types: "revolute".into(), ms, outcome }
        })
        .collect()
}

/// A pair's outcome as a method run gives it, before it becomes a runs-file row.
struct PairRecord {
    pair: String,
    category: String,
    joint_types: String,
    ms: f64,
    outcome: Result<PairScore, String>,
}

fn result(records: &[PairRecord]) -> RunResult {
    let rows = records
        .iter()
        .map(|r| {
            let outcome = r.outcome.as_ref().map_err(String::as_str);
            RunRow::new(&r.pair, &r.category, &r.joint_types, r.ms, outcome)
        })
        .collect();
    let meta = RunMeta {
        version: RUNS_VERSION,
        fingerprint: "test".into(),
        dataset: "hash".into(),
        peak_mib: None,
        gallery: BTreeMap::new(),
    };
    RunResult { rows, meta, cached: false, passes: None }
}

fn mean(values: &[f64]) -> Option<f64> {
    (!values.is_empty()).then(|| values.iter().sum::<f64>() / values.len() as f64)
}

fn ratio(num: f64, den: f64) -> Option<f64> {
    (den > 0.0).then(|| num / den)
}

/// The flow leaderboard's row of `records`, by hand over the pairs that did not fail.
fn expected_flow(records: &[PairRecord]) -> BTreeMap<&'static str, Option<f64>> {
    let flows: Vec<&FlowScore> =
        records.iter().filter_map(|r| r.outcome.as_ref().ok()?.flow.as_ref()).collect();
    let epe: Vec<f64> = flows.iter().map(|f| f.epe).collect();
    let curve: Option<Vec<f64>> = (0..PCC_THRESHOLDS)
        .map(|k| mean(&flows.iter().map(|f| f.pcc[k]).collect::<Vec<_>>()))
        .collect();
    let auc = curve.as_ref().map(|c| pcc_auc(&c.clone().try_into().expect("51 thresholds")));
    BTreeMap::from([
        ("epe", mean(&epe)),
        ("pcc_0.05", curve.as_ref().map(|c| c[10])),
        ("pcc_0.10", curve.as_ref().map(|c| c[20])),
        ("pcc_auc", auc),
        ("pairs", Some(flows.len() as f64)),
        ("failed", Some(records.iter().filter(|r| r.outcome.is_err()).count() as f64)),
    ])
}

/// The segmentation leaderboard's row of `records`, by hand over the pairs that did not
/// fail: RI and part-count accuracy over scored pairs, IoU over their parts, motion errors
/// over their matched parts, Q's scores over the pairs that segment Q.
fn expected_seg(records: &[PairRecord]) -> BTreeMap<&'static str, Option<f64>> {
    let scored: Vec<&PairScore> = records.iter().filter_map(|r| r.outcome.as_ref().ok()).collect();
    let sum = |f: &dyn Fn(&PairScore) -> f64| scored.iter().map(|s| f(s)).sum::<f64>();
    let with_q: Vec<&SegmentScore> = scored.iter().filter_map(|s| s.q.as_ref()).collect();
    let matched = sum(&|s| s.rotation_deg.len() as f64);
    BTreeMap::from([
        ("ri", mean(&scored.iter().map(|s| s.p.rand_index).collect::<Vec<_>>())),
        ("iou", ratio(sum(&|s| s.p.iou_sum), sum(&|s| f64::from(s.p.parts)))),
        ("rotation_deg", ratio(sum(&|s| s.rotation_deg.iter().sum()), matched)),
        ("translation", ratio(sum(&|s| s.translation.iter().sum()), matched)),
        ("matched_per_pair", ratio(matched, scored.len() as f64)),
        (
            "part_count_acc",
            mean(
                &scored
                    .iter()
                    .map(|s| f64::from(u8::from(s.parts == s.segments)))
                    .collect::<Vec<_>>(),
            ),
        ),
        ("ri_q", mean(&with_q.iter().map(|q| q.rand_index).collect::<Vec<_>>())),
        (
            "iou_q",
            ratio(
                with_q.iter().map(|q| q.iou_sum).sum(),
                with_q.iter().map(|q| f64::from(q.parts)).sum(),
            ),
        ),
        ("pairs", Some(scored.len() as f64)),
        ("failed", Some(records.iter().filter(|r| r.outcome.is_err()).count() as f64)),
    ])
}

/// The (dataset, method) keys of a leaderboard's rows, in order.
fn keys(frame: &DataFrame) -> Vec<(String, String)> {
    let text = |name: &str| -> Vec<String> {
        let column = frame.column(name).expect("a key column");
        let values = column.str().expect("strings");
        values.iter().map(|v| v.expect("a key").to_owned()).collect()
    };
    text("dataset").into_iter().zip(text("method")).collect()
}

/// The value in column `name` of row `row` (counts are read as numbers too).
fn value(frame: &DataFrame, row: usize, name: &str) -> Option<f64> {
    let column = frame.column(name).unwrap_or_else(|e| panic!("column {name}: {e}"));
    match column.f64() {
        Ok(values) => values.get(row),
        Err(_) => column.u32().expect("a count").get(row).map(f64::from),
    }
}

/// Checks every expected column of `frame`'s row for (`dataset`, `method`).
fn check_row(
    board: &str,
    frame: &DataFrame,
    dataset: &str,
    method: &str,
    expected: &BTreeMap<&'static str, Option<f64>>,
) {
    let row = keys(frame)
        .iter()
        .position(|(d, m)| d == dataset && m == method)
        .unwrap_or_else(|| panic!("{board}: no row for {method} on {dataset}"));
    for (&name, &want) in expected {
        let got = value(frame, row, name);
        let case = format!("{board} {dataset}/{method} {name}: got {got:?}, expected {want:?}");
        match (got, want) {
            (Some(got), Some(want)) => assert!((got - want).abs() < 1e-12, "{case}"),
            (got, want) => assert_eq!(got, want, "{case}"),
        }
    }
}

#[test]
fn means_leave_failed_pairs_out_and_failed_counts_them() {
    let whole = entry("whole", Board::Both);
    let flow_only = entry("flow-only", Board::Flow);
    let seg_only = entry("seg-only", Board::Segmentation);
    let dead = entry("dead", Board::Both);
    let runs: Vec<(&str, &Entry, Vec<PairRecord>)> = vec![
        ("alpha", &whole, records(7, &[1, 4, 5], 0.0, true)),
        ("alpha", &flow_only, records(5, &[0], 0.3, true)),
        ("alpha", &seg_only, records(6, &[2, 3], 0.6, false)),
        ("alpha", &dead, records(3, &[0, 1, 2], 0.9, true)),
        // The same row on another dataset: its own means, not pooled with alpha's.
        ("beta", &whole, records(4, &[3], 1.7, true)),
    ];
    let results: Vec<RunResult> = runs.iter().map(|(_, _, r)| result(r)).collect();
    let scored: Vec<Scored> = runs
        .iter()
        .zip(&results)
        .map(|((dataset, entry, _), result)| Scored {
            dataset,
            cross_instance: false,
            entry,
            result,
        })
        .collect();
    let boards = Leaderboards::build(&scored).expect("the leaderboards build");

    let key = |d: &str, m: &str| (d.to_owned(), m.to_owned());
    assert_eq!(
        keys(&boards.flow),
        [
            key("alpha", "whole"),
            key("alpha", "flow-only"),
            key("alpha", "dead"),
            key("beta", "whole")
        ]
    );
    assert_eq!(
        keys(&boards.seg),
        [
            key("alpha", "whole"),
            key("alpha", "seg-only"),
            key("alpha", "dead"),
            key("beta", "whole")
        ]
    );
    for (dataset, entry, records) in &runs {
        if entry.board != Board::Segmentation {
            check_row("flow", &boards.flow, dataset, &entry.name, &expected_flow(records));
        }
        if entry.board != Board::Flow {
            check_row("seg", &boards.seg, dataset, &entry.name, &expected_seg(records));
        }
    }
    // A row that failed everywhere has no means at all, only its failures.
    let dead_flow = expected_flow(&runs[3].2);
    assert_eq!(
        (dead_flow["epe"], dead_flow["pairs"], dead_flow["failed"]),
        (None, Some(0.0), Some(3.0))
    );

    // Only the PCC curves of rows with a scored flow are drawn, each the mean over them.
    let curves: Vec<(&str, &str)> =
        boards.curves.iter().map(|c| (c.dataset.as_str(), c.method.as_str())).collect();
    assert_eq!(curves, [("alpha", "whole"), ("alpha", "flow-only"), ("beta", "whole")]);
    let flows: Vec<&FlowScore> =
        runs[0].2.iter().filter_map(|r| r.outcome.as_ref().ok()?.flow.as_ref()).collect();
    for (k, &v) in boards.curves[0].values.iter().enumerate() {
        let want = flows.iter().map(|f| f.pcc[k]).sum::<f64>() / flows.len() as f64;
        assert!((v - want).abs() < 1e-12, "curve at {k}: {v} vs {want}");
    }

    // Timings, unlike the scores, average over every pair, failed ones included.
    for (row, (_, _, records)) in runs.iter().enumerate() {
        let want = records.iter().map(|r| r.ms).sum::<f64>() / records.len() as f64;
        let got = value(&boards.timings, row, "ms_per_pair").expect("a time");
        assert!((got - want).abs() < 1e-9, "timings row {row}: {got} vs {want}");
    }
}
