//! Prediction files scored as external rows (`evaluator score`): a built-in row's predictions
//! written with `predict` and scored back reproduce its per-pair scores exactly; the ground
//! truth as a file scores perfectly; a file that does not fit the dataset is refused by name
//! and changes no report; a bad pair fails alone with its reason; external rows stay on the
//! boards of later runs.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use baselines::SeqRansac;
use evaluator::commands::files::{
    add_remembered_rows, score_predictions, write_predictions, CommandOptions, PredictRequest,
};
use evaluator::commands::pipeline::{evaluate, NoProgress, Options};
use evaluator::datasets::DatasetSpec;
use evaluator::rows::external::file_sha256;
use evaluator::rows::registry::{FlowSource, Registry};
use generator::config::GeneratorConfig;
use pairs::predictions::{read_predictions, PredictionHeader, PredictionRecord, PredictionWriter};

fn spec() -> DatasetSpec {
    let config = GeneratorConfig {
        objects: 2,
        states_per_object: 3,
        pairs_per_object: 2,
        points: 96,
        min_part_points: 4,
        ..GeneratorConfig::default()
    };
    DatasetSpec::generated("tiny", config)
}

fn registry() -> Registry {
    let mut registry = Registry::new();
    registry.oracle();
    registry.combine(Arc::new(SeqRansac::default()), FlowSource::GroundTruth, "seqransac v1", None);
    registry
}

fn setup(root: &Path) -> CommandOptions {
    CommandOptions {
        datasets_root: root.join("datasets"),
        reports: root.join("reports"),
        gallery_pairs: 1,
    }
}

/// Every built-in row on the tiny dataset (made on the way).
fn evaluate_all(root: &Path, registry: &Registry) -> evaluator::commands::pipeline::Summary {
    let options = Options {
        datasets: Vec::new(),
        methods: Vec::new(),
        limit: None,
        datasets_root: root.join("datasets"),
        reports: root.join("reports"),
        force: false,
        gallery_pairs: 1,
        validation: Vec::new(),
    };
    evaluate(registry, &[spec()], &options, &NoProgress).expect("the evaluation runs")
}

fn predict(root: &Path, registry: &Registry, row: &str) -> PathBuf {
    let out = root.join(format!("{row}.mcap"));
    let request =
        PredictRequest { dataset: "tiny".into(), row: row.into(), out: out.clone(), limit: None };
    write_predictions(registry, &[spec()], &request, &setup(root), &NoProgress)
        .expect("predictions are written");
    out
}

fn score(
    root: &Path,
    registry: &Registry,
    file: &Path,
    name: &str,
) -> Result<(String, evaluator::commands::pipeline::Summary), evaluator::EvalError> {
    score_predictions(registry, &[spec()], "tiny", file, Some(name), &setup(root), &NoProgress)
}

/// A CSV's rows as maps from column name to cell.
fn rows(path: &Path) -> Vec<HashMap<String, String>> {
    let mut reader = csv::Reader::from_path(path).expect("the table reads");
    let header = reader.headers().expect("a header").clone();
    reader
        .records()
        .map(|r| {
            let r = r.expect("a row");
            header.iter().map(str::to_owned).zip(r.iter().map(str::to_owned)).collect()
        })
        .collect()
}

fn row(path: &Path, method: &str) -> HashMap<String, String> {
    let rows = rows(path);
    let methods: Vec<&String> = rows.iter().map(|r| &r["method"]).collect();
    let found = rows.iter().find(|r| r["method"] == method).cloned();
    found.unwrap_or_else(|| panic!("no row {method} in {}: {methods:?}", path.display()))
}

/// Every file under the reports folder with its bytes.
fn snapshot(reports: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let mut files = Vec::new();
    let mut stack = vec![reports.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).expect("readable") {
            let path = entry.expect("an entry").path();
            if path.is_dir() {
                stack.push(path);
            } else {
                files.push((path.clone(), std::fs::read(&path).expect("readable")));
            }
        }
    }
    files.sort();
    files
}

#[test]
fn a_predicted_row_scored_from_its_file_reproduces_the_builtin_row() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let (root, registry) = (dir.path(), registry());
    evaluate_all(root, &registry);
    let file = predict(root, &registry, "seqransac@gt-flow");
    let (name, _) = score(root, &registry, &file, "mine").expect("the file scores");
    assert_eq!(name, "mine");
    let runs = root.join("reports/runs/tiny");
    let (builtin, external) =
        (rows(&runs.join("seqransac@gt-flow.csv")), rows(&runs.join("mine.csv")));
    assert_eq!(builtin.len(), 4);
    for (mut b, mut e) in builtin.into_iter().zip(external) {
        b.remove("ms");
        e.remove("ms");
        assert_eq!(b, e);
    }
    let seg = root.join("reports/leaderboard_seg.csv");
    let (b, e) = (row(&seg, "seqransac@gt-flow"), row(&seg, "mine"));
    assert_eq!(b["flow_source"], "gt-flow");
    assert_eq!(e["flow_source"], "external");
    for column in ["ri", "iou", "rotation_deg", "translation", "ri_q", "iou_q", "failed"] {
        assert_eq!(b[column], e[column], "{column}");
    }
    // The built-in rows stay, the report says what external rows are, and a later plain run
    // keeps the external row from the cache.
    assert_eq!(row(&seg, "gt")["iou"], "1.0000");
    let report = std::fs::read_to_string(root.join("reports/LEADERBOARD.md")).expect("written");
    assert!(report.contains("| tiny | mine | external |"), "{report}");
    assert!(report.contains("scored from prediction files"));
    let mut remembered = registry.clone();
    add_remembered_rows(&mut remembered, &root.join("reports")).expect("readable");
    // (An unnamed external row is taken from the cache and not counted as run.)
    let summary = evaluate_all(root, &remembered);
    assert_eq!((summary.fresh, summary.cached), (0, 2));
    assert_eq!(row(&seg, "mine")["iou"], e["iou"]);

    // The file changes under the same name: its cached run no longer matches, and a plain
    // run does not score it again (only `score`, or `--methods mine`, does), so the row
    // leaves the boards instead of showing the old file's numbers.
    let truth = predict(root, &registry, "gt");
    std::fs::copy(&truth, &file).expect("copied");
    let mut remembered = registry.clone();
    add_remembered_rows(&mut remembered, &root.join("reports")).expect("readable");
    let summary = evaluate_all(root, &remembered);
    assert_eq!((summary.fresh, summary.cached), (0, 2));
    assert!(!rows(&seg).iter().any(|r| r["method"] == "mine"));
}

#[test]
fn the_truth_as_a_file_scores_perfectly_and_bad_pairs_fail_alone() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let (root, registry) = (dir.path(), registry());
    evaluate_all(root, &registry);
    let truth = predict(root, &registry, "gt");
    score(root, &registry, &truth, "truth").expect("the file scores");
    let flow = row(&root.join("reports/leaderboard_flow.csv"), "truth");
    let seg = row(&root.join("reports/leaderboard_seg.csv"), "truth");
    assert_eq!((flow["epe"].as_str(), flow["flow_source"].as_str()), ("0.0000", "external"));
    assert_eq!(
        (seg["ri"].as_str(), seg["iou"].as_str(), seg["failed"].as_str()),
        ("1.0000", "1.0000", "0")
    );

    // The same file with one pair left out, one short, one with a NaN flow, one a failure.
    let (header, records) = read_predictions(&truth).expect("reads back");
    let broken = root.join("broken.mcap");
    let mut writer = PredictionWriter::create(&broken, &header).expect("created");
    for (i, (id, prediction)) in records.iter().enumerate() {
        let mut p = prediction.clone().expect("the truth is valid");
        match i {
            0 => continue,
            1 => {
                p.segments_p.pop();
            }
            2 => p.flow.as_mut().expect("a flow")[3].y = f32::NAN,
            _ => {
                writer.write(&PredictionRecord::failure(id, "out of memory")).expect("written");
                continue;
            }
        }
        writer.write(&PredictionRecord::from_prediction(id, &p)).expect("written");
    }
    writer.finish().expect("finished");
    score(root, &registry, &broken, "broken").expect("the file scores");
    let seg = row(&root.join("reports/leaderboard_seg.csv"), "broken");
    assert_eq!((seg["pairs"].as_str(), seg["failed"].as_str()), ("0", "4"));
    let runs = std::fs::read_to_string(root.join("reports/runs/tiny/broken.csv")).expect("a run");
    for reason in [
        "no prediction for this pair in",
        "segments_p has 95 entries, expected 96",
        "flow[3] is not finite",
        "the method failed: out of memory",
    ] {
        assert!(runs.contains(reason), "{reason:?} missing from {runs}");
    }
}

#[test]
fn files_that_do_not_fit_the_dataset_are_refused_and_change_no_report() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let (root, registry) = (dir.path(), registry());
    evaluate_all(root, &registry);
    let truth = predict(root, &registry, "gt");
    let (header, records) = read_predictions(&truth).expect("reads back");
    let before = snapshot(&root.join("reports"));
    let write = |name: &str, header: &PredictionHeader, records: &[PredictionRecord]| {
        let path = root.join(name);
        let mut writer = PredictionWriter::create(&path, header).expect("created");
        for r in records {
            writer.write(r).expect("written");
        }
        writer.finish().expect("finished")
    };
    let valid: Vec<PredictionRecord> = records
        .iter()
        .map(|(id, p)| PredictionRecord::from_prediction(id, p.as_ref().expect("valid")))
        .collect();
    let other_dataset = PredictionHeader { dataset: "0".repeat(64), ..header.clone() };
    let mut stranger = valid.clone();
    stranger[1].id = "sf2f-00099-0".into();
    let mut twice = valid.clone();
    twice[1].id = twice[0].id.clone();
    let good = std::fs::read(&truth).expect("readable");
    let truncated = root.join("truncated.mcap");
    std::fs::write(&truncated, &good[..good.len() / 2]).expect("written");
    let cases: Vec<(PathBuf, &str, &str)> = vec![
        (
            write("other.mcap", &other_dataset, &valid),
            "mine",
            "made for the dataset with content hash",
        ),
        (
            write("stranger.mcap", &header, &stranger),
            "mine",
            "pair sf2f-00099-0 is not a pair of dataset tiny",
        ),
        (write("twice.mcap", &header, &twice), "mine", "has two predictions"),
        (truncated, "mine", "not a readable MCAP file"),
        (truth.clone(), "gt", "gt is a built-in row's name"),
        (truth.clone(), "GT", "GT is a built-in row's name"),
        (truth.clone(), "a/b", "cannot name a row"),
        (truth.clone(), "a|b", "cannot name a row"),
    ];
    for (file, name, message) in cases {
        let err = score(root, &registry, &file, name).err().unwrap_or_else(|| panic!("{message}"));
        let text = format!("{err}");
        assert!(text.contains(message), "{text:?} should say {message:?}");
        assert_eq!(snapshot(&root.join("reports")), before, "{message}: the reports changed");
    }
    assert!(file_sha256(&truth).expect("hashes").len() == 64);
}
