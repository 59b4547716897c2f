//! End-to-end evaluation on a tiny generated dataset: the oracle scores perfectly, broken
//! methods are reported as failed without stopping the run, reruns are byte-identical and
//! reuse their cached runs, and a changed fingerprint recomputes.

use std::path::Path;
use std::sync::Arc;

use evaluator::commands::files::{score_predictions, CommandOptions};
use evaluator::commands::pipeline::{evaluate, NoProgress, Options, Summary};
use evaluator::datasets::DatasetSpec;
use evaluator::rows::reference::OnePart;
use evaluator::rows::registry::{Board, FlowSource, Registry};
use generator::config::GeneratorConfig;
use pairs::math::Vector3;
use pairs::predictions::{PredictionHeader, PredictionRecord, PredictionWriter};
use pairs::{Method, MethodError, PairInput, Prediction};

/// Fails in three ways, by pair: a short segmentation, a NaN flow, a panic; else one part.
struct Broken;

impl Method for Broken {
    fn name(&self) -> &str {
        "broken"
    }

    fn predict(&self, input: &PairInput) -> Result<Prediction, MethodError> {
        let n = input.p.len();
        // Ids are `<kind>-<object:05>-<pair>`: objects 0 and 1, pairs 0 and 1 give modes 0..3.
        let id = input.id.as_bytes();
        let digit = |from_end: usize| u32::from(id[id.len() - from_end].wrapping_sub(b'0'));
        let mode = digit(3) * 2 + digit(1);
        let mut prediction = Prediction {
            flow: Some(vec![Vector3::zeros(); n]),
            segments_p: vec![0; n],
            ..Prediction::default()
        };
        match mode {
            0 => prediction.segments_p.pop().map(|_| ()).unwrap_or(()),
            1 => prediction.flow.as_mut().expect("set above")[n / 2].x = f32::NAN,
            2 => panic!("broken on purpose"),
            _ => {}
        }
        Ok(prediction)
    }
}

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

fn registry(one_part_fingerprint: &str) -> Registry {
    let mut registry = Registry::new();
    registry.oracle();
    registry.combine(Arc::new(OnePart), FlowSource::GroundTruth, one_part_fingerprint, None);
    registry.method(Arc::new(Broken), Board::Both, "broken v1");
    registry
}

fn run(root: &Path, registry: &Registry) -> Summary {
    run_narrowed(root, registry, &[], None)
}

fn run_narrowed(
    root: &Path,
    registry: &Registry,
    methods: &[&str],
    limit: Option<usize>,
) -> Summary {
    let options = Options {
        datasets: Vec::new(),
        methods: methods.iter().map(|m| m.to_string()).collect(),
        limit,
        datasets_root: root.join("datasets"),
        reports: root.join("reports"),
        force: false,
        gallery_pairs: 1,
        validation: Vec::new(),
    };
    evaluate(registry, &[spec()], &options, &NoProgress).expect("the evaluation runs")
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The CSV's rows as maps from column name to cell.
fn rows(path: &Path) -> Vec<std::collections::HashMap<String, String>> {
    let text = read(path);
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().expect("a header").split(',').collect();
    lines
        .map(|l| {
            header.iter().map(|h| h.to_string()).zip(l.split(',').map(str::to_owned)).collect()
        })
        .collect()
}

#[test]
fn oracle_is_perfect_failures_are_counted_and_reruns_are_identical() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let first = run(dir.path(), &registry("one-part v1"));
    assert_eq!(first.fresh, 3);
    let reports = dir.path().join("reports");
    let seg = rows(&reports.join("leaderboard_seg.csv"));
    let flow = rows(&reports.join("leaderboard_flow.csv"));
    let row = |table: &[std::collections::HashMap<String, String>], name: &str| {
        table.iter().find(|r| r["method"] == name).cloned().expect("the row is listed")
    };
    let gt = row(&seg, "gt");
    assert_eq!((gt["ri"].as_str(), gt["iou"].as_str()), ("1.0000", "1.0000"));
    assert_eq!(gt["rotation_deg"], "0.0000");
    assert_eq!(row(&flow, "gt")["epe"], "0.0000");
    assert_eq!(row(&flow, "gt")["pcc_0.05"], "1.0000");
    // Four pairs, so Broken fails three ways and scores one.
    let broken = row(&seg, "broken");
    assert_eq!((broken["pairs"].as_str(), broken["failed"].as_str()), ("1", "3"));
    assert_eq!(first.failed, 3);
    let runs = read(&reports.join("runs/tiny/broken.csv"));
    for reason in [
        "segments_p has 95 entries, expected 96",
        "flow[48] is not finite",
        "panicked: broken on purpose",
    ] {
        assert!(runs.contains(reason), "{reason:?} missing from {runs}");
    }
    assert!(reports.join("LEADERBOARD.md").exists());
    let gallery = reports.join("gallery/segmentation/tiny/sf2f-00000-0.png");
    let picture = image::open(&gallery).expect("the gallery picture reads back");
    // Ground truth, one-part and broken: three panels.
    assert_eq!(picture.width(), 3 * generator::gallery::PANEL);
    assert!(reports.join("pcc_tiny.svg").exists() && reports.join("pcc_tiny.png").exists());
    let tables = ["leaderboard_flow.csv", "leaderboard_seg.csv"].map(|f| read(&reports.join(f)));

    let again = run(dir.path(), &registry("one-part v1"));
    assert_eq!((again.fresh, again.cached), (0, 3));
    assert_eq!(
        tables,
        ["leaderboard_flow.csv", "leaderboard_seg.csv"].map(|f| read(&reports.join(f)))
    );

    let changed = run(dir.path(), &registry("one-part v2"));
    assert_eq!((changed.fresh, changed.cached), (1, 2));
    assert_eq!(
        tables,
        ["leaderboard_flow.csv", "leaderboard_seg.csv"].map(|f| read(&reports.join(f)))
    );
}

#[test]
fn unknown_names_are_refused_with_the_known_ones() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let options = Options {
        datasets: vec!["nope".into()],
        methods: Vec::new(),
        limit: None,
        datasets_root: dir.path().join("datasets"),
        reports: dir.path().join("reports"),
        force: false,
        gallery_pairs: 0,
        validation: Vec::new(),
    };
    let err = evaluate(&registry("x"), &[spec()], &options, &NoProgress).err().expect("refused");
    assert!(err.to_string().contains("unknown dataset \"nope\"; known: tiny"), "{err}");
    let err = registry("x").select(&["seqransac@nowhere".into()]).err().expect("refused");
    assert!(err.to_string().contains("known: gt, one-part@gt-flow, broken"), "{err}");
}

/// Progress hooks that keep the notices.
#[derive(Default)]
struct Notices(std::sync::Mutex<Vec<String>>);

impl evaluator::commands::pipeline::Progress for Notices {
    fn generating(&self, _: &str, _: u64, _: u64) {}
    fn start(&self, _: &str, _: &str, _: u64) {}
    fn tick(&self) {}
    fn finish(&self, _: &str, _: &str, _: bool) {}
    fn notice(&self, message: &str) {
        self.0.lock().expect("not poisoned").push(message.to_owned());
    }
}

fn options(root: &Path) -> Options {
    Options {
        datasets: Vec::new(),
        methods: Vec::new(),
        limit: None,
        datasets_root: root.join("datasets"),
        reports: root.join("reports"),
        force: false,
        gallery_pairs: 0,
        validation: Vec::new(),
    }
}

#[test]
fn a_stale_default_dataset_is_regenerated_and_its_rows_recomputed() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let registry = registry("one-part v1");
    let first = evaluate(&registry, &[spec()], &options(dir.path()), &NoProgress).expect("runs");
    assert_eq!(first.fresh, 3);
    // The spec now asks for another seed: the folder on disk no longer matches it.
    let mut changed = spec();
    changed.config.as_mut().expect("a generated spec").seed = 1;
    let notices = Notices::default();
    let second =
        evaluate(&registry, &[changed.clone()], &options(dir.path()), &notices).expect("runs");
    let said = notices.0.lock().expect("not poisoned").clone();
    assert_eq!(said.len(), 1, "{said:?}");
    assert!(
        said[0].contains("regenerating tiny") && said[0].contains("config differs"),
        "{said:?}"
    );
    assert_eq!((second.fresh, second.cached), (3, 0), "new data recomputes every row");
    let manifest =
        pairs::dataset::Manifest::read(&dir.path().join("datasets/tiny")).expect("reads");
    assert_eq!(manifest.origin.seed, 1);
    // Matching again: nothing regenerated, everything cached.
    let notices = Notices::default();
    let third = evaluate(&registry, &[changed], &options(dir.path()), &notices).expect("runs");
    assert!(notices.0.lock().expect("not poisoned").is_empty());
    assert_eq!((third.fresh, third.cached), (0, 3));
}

#[test]
fn a_user_dataset_is_scored_under_its_name_and_bad_folders_are_refused() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let made = dir.path().join("mine");
    let config = spec().config.expect("a generated spec");
    generator::generate::generate_dataset(&config, &made, false, None, |_| {}).expect("generated");
    let registry = registry("one-part v1");
    let user = DatasetSpec::user("lamps", &made);
    let summary = evaluate(&registry, &[user], &options(dir.path()), &NoProgress).expect("runs");
    assert_eq!(summary.fresh, 3);
    let reports = dir.path().join("reports");
    let seg = read(&reports.join("leaderboard_seg.csv"));
    assert!(seg.lines().any(|l| l.starts_with("lamps,gt,gt,true,1.0000,1.0000")), "{seg}");
    let board = read(&reports.join("LEADERBOARD.md"));

    // Not a dataset: the error names the folder; the reports are left as they were.
    let empty = dir.path().join("empty");
    std::fs::create_dir_all(&empty).expect("made");
    let err = evaluate(
        &registry,
        &[DatasetSpec::user("nothing", &empty)],
        &options(dir.path()),
        &NoProgress,
    )
    .err()
    .expect("refused");
    assert!(err.to_string().contains("nothing") && err.to_string().contains("empty"), "{err}");
    // A corrupt pair file: the checksum check names the file.
    let broken = dir.path().join("broken");
    generator::generate::generate_dataset(&config, &broken, false, None, |_| {})
        .expect("generated");
    let pairs_file = broken.join(pairs::dataset::PAIRS_FILE);
    let bytes = std::fs::read(&pairs_file).expect("read");
    std::fs::write(&pairs_file, &bytes[..bytes.len() / 2]).expect("truncated");
    let err = evaluate(
        &registry,
        &[DatasetSpec::user("broken", &broken)],
        &options(dir.path()),
        &NoProgress,
    )
    .err()
    .expect("refused");
    assert!(err.to_string().contains("broken") && err.to_string().contains("pairs.mcap"), "{err}");
    assert_eq!(read(&reports.join("LEADERBOARD.md")), board, "failed runs leave the reports alone");
}

#[test]
fn a_board_of_one_row_prints_its_names_unquoted() {
    // Columns whose rows are all equal come back from polars as one owned scalar; the
    // report printed those with Debug quotes ("tiny") before.
    let dir = tempfile::tempdir().expect("a temporary folder");
    let mut registry = Registry::new();
    registry.oracle();
    run(dir.path(), &registry);
    let report = read(&dir.path().join("reports/LEADERBOARD.md"));
    assert!(report.contains("| tiny | gt | gt | true | 0.0000 |"), "{report}");
    assert!(!report.contains("\"tiny\""), "{report}");
}

/// An iterative method under the iteration board's row name: one part in its first pass,
/// then P split at its median x in a second pass, except on the first pair, where it stops
/// after one pass. Counts its calls.
struct TwoPasses {
    calls: std::sync::atomic::AtomicUsize,
}

impl Method for TwoPasses {
    fn name(&self) -> &str {
        evaluator::boards::iterations::ITERATIVE_ROW
    }

    fn predict(&self, _: &PairInput) -> Result<Prediction, MethodError> {
        panic!("an iterative row is run through predict_passes")
    }

    fn iterative(&self) -> bool {
        true
    }

    fn predict_passes(&self, input: &PairInput) -> Result<Vec<Prediction>, MethodError> {
        self.calls.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
        let n = input.p.len();
        let one = Prediction {
            flow: Some(vec![Vector3::zeros(); n]),
            segments_p: vec![0; n],
            ..Prediction::default()
        };
        if input.id.ends_with("00000-0") {
            return Ok(vec![one]);
        }
        let mut xs: Vec<f32> = input.p.points.iter().map(|p| p.x).collect();
        xs.sort_by(f32::total_cmp);
        let median = xs[n / 2];
        let split = Prediction {
            flow: Some(vec![Vector3::new(0.01, 0.0, 0.0); n]),
            segments_p: input.p.points.iter().map(|p| u32::from(p.x >= median)).collect(),
            ..Prediction::default()
        };
        Ok(vec![one, split])
    }
}

#[test]
fn the_iterative_row_runs_each_pass_once_and_its_board_comes_from_the_cache() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let method = Arc::new(TwoPasses { calls: Default::default() });
    let mut registry = Registry::new();
    registry.method(method.clone(), Board::Both, "two passes v1");
    let calls = || method.calls.load(std::sync::atomic::Ordering::SeqCst);
    let first = run(dir.path(), &registry);
    assert_eq!(calls(), 4, "one call per pair, for the row and its board together");
    let reports = dir.path().join("reports");
    let table = read(&reports.join("iterations.csv"));
    let lines: Vec<&str> = table.lines().collect();
    assert_eq!(lines.len(), 3, "a header and two passes:\n{table}");
    // Iteration 2: four pairs scored, three still running; the first pair keeps its one pass.
    assert!(lines[1].starts_with("tiny,1,4,4,") && lines[2].starts_with("tiny,2,4,3,"), "{table}");
    assert_eq!(first.iterations.len(), 2);
    assert_ne!(first.iterations[1].epe, first.iterations[0].epe, "the passes differ");
    assert_eq!(first.iteration_joints.len(), 2);
    assert!(reports.join("runs/tiny/net-iter.passes.csv").exists());
    let joints = read(&reports.join("iterations_joints.csv"));

    let again = run(dir.path(), &registry);
    assert_eq!((again.fresh, again.cached, calls()), (0, 1, 4), "the board is read from the cache");
    assert_eq!(read(&reports.join("iterations.csv")), table);
    assert_eq!(read(&reports.join("iterations_joints.csv")), joints);

    // Without its passes the cached run is not complete: the row runs again.
    std::fs::remove_file(reports.join("runs/tiny/net-iter.passes.csv")).expect("removed");
    let rerun = run(dir.path(), &registry);
    assert_eq!((rerun.fresh, calls()), (1, 8));
    assert_eq!(read(&reports.join("iterations.csv")), table);
}

/// A flow of zeros (P stays where it is), on the flow board.
struct Still;

impl Method for Still {
    fn name(&self) -> &str {
        "still"
    }

    fn predict(&self, input: &PairInput) -> Result<Prediction, MethodError> {
        let n = input.p.len();
        Ok(Prediction {
            flow: Some(vec![Vector3::zeros(); n]),
            segments_p: vec![0; n],
            ..Prediction::default()
        })
    }
}

#[test]
fn a_cross_instance_set_is_on_the_segmentation_board_only_and_skips_true_flow_rows() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let config = GeneratorConfig {
        kind: pairs::PairKind::Xf2f,
        categories: vec!["laptop".into(), "cabinet".into()],
        ..spec().config.expect("a generated spec")
    };
    let cross = DatasetSpec::generated("cross", config);
    let mut registry = registry("one-part v1");
    let still: Arc<dyn Method> = Arc::new(Still);
    registry.method(still.clone(), Board::Flow, "still v1");
    registry.combine(Arc::new(OnePart), FlowSource::Method(still), "one-part v1", None);
    let summary =
        evaluate(&registry, &[spec(), cross], &options(dir.path()), &NoProgress).expect("runs");
    // Five rows on the single-object set; on the cross-instance one, neither the flow row
    // nor the segmenter on the true flow.
    assert_eq!(summary.fresh, 5 + 3);
    let reports = dir.path().join("reports");
    let seg = rows(&reports.join("leaderboard_seg.csv"));
    let on = |table: &[std::collections::HashMap<String, String>], dataset: &str| {
        let mut names: Vec<String> =
            table.iter().filter(|r| r["dataset"] == dataset).map(|r| r["method"].clone()).collect();
        names.sort();
        names
    };
    assert_eq!(on(&seg, "cross"), ["broken", "gt", "one-part@still-flow"]);
    let flow = rows(&reports.join("leaderboard_flow.csv"));
    assert!(on(&flow, "cross").is_empty(), "cross-instance rows on the flow board");
    assert!(!on(&flow, "tiny").is_empty());
    let gt = seg.iter().find(|r| r["dataset"] == "cross" && r["method"] == "gt").expect("gt");
    assert_eq!((gt["ri"].as_str(), gt["iou"].as_str()), ("1.0000", "1.0000"));
    // Per pair, the flow columns are empty, never zero.
    let runs = rows(&reports.join("runs/cross/gt.csv"));
    assert!(!runs.is_empty() && runs.iter().all(|r| r["epe"].is_empty()), "{runs:?}");
}

#[test]
fn a_set_dataset_gets_a_set_board_of_the_segmentation_rows_and_leaves_the_pair_boards() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let sets = GeneratorConfig {
        objects: 2,
        points: 96,
        min_part_points: 4,
        sets: Some(generator::config::SetsConfig { views: 3, ..Default::default() }),
        ..GeneratorConfig::default()
    };
    let specs = [spec(), DatasetSpec::generated("tiny-sets", sets)];
    let options = Options {
        datasets: Vec::new(),
        methods: Vec::new(),
        limit: None,
        datasets_root: dir.path().join("datasets"),
        reports: dir.path().join("reports"),
        force: false,
        gallery_pairs: 1,
        validation: Vec::new(),
    };
    let registry = registry("one-part v1");
    let first = evaluate(&registry, &specs, &options, &NoProgress).expect("runs");
    // Three rows on the pairs, three on the sets.
    assert_eq!(first.fresh, 6);
    let reports = dir.path().join("reports");
    let board = rows(&reports.join("leaderboard_sets.csv"));
    let row = |name: &str| board.iter().find(|r| r["method"] == name).cloned().expect("listed");
    for name in ["gt", "one-part", "broken"] {
        let r = row(name);
        assert_eq!(
            (r["dataset"].as_str(), r["views"].as_str(), r["sets"].as_str()),
            ("tiny-sets", "3", "2")
        );
    }
    // Broken's pair (0, 1) has a NaN flow and its pair (0, 2) panics: both sets fail, and
    // nothing is averaged.
    let broken = row("broken");
    assert_eq!((broken["failed"].as_str(), broken["multi_scan_miou"].as_str()), ("2", ""));
    assert_eq!(first.failed_sets, 2);
    let (gt, one) = (row("gt"), row("one-part"));
    let number = |r: &std::collections::HashMap<String, String>, c: &str| -> f64 {
        r[c].parse().expect("a number")
    };
    for c in ["multi_scan_miou", "per_scan_miou", "multi_scan_ri", "per_scan_ri"] {
        let (g, o) = (number(&gt, c), number(&one, c));
        assert!((0.0..=1.0).contains(&g) && (0.0..=1.0).contains(&o), "{c}: {g} {o}");
        assert!(g > o, "{c}: the truth of each pair ({g}) beats one part ({o})");
    }
    // One part per view: the per-scan RI of a single segment is the chance that two points
    // share a part, below 1; the pair boards do not list the set dataset.
    assert!(number(&one, "per_scan_ri") < 1.0);
    // Motions to every view: the pairs' true motions carried to the set beat one rigid fit.
    assert!(number(&gt, "rotation_deg") < number(&one, "rotation_deg"), "{gt:?} {one:?}");
    assert!(number(&gt, "translation") < number(&one, "translation"), "{gt:?} {one:?}");
    assert!(!read(&reports.join("leaderboard_seg.csv")).contains("tiny-sets"));
    assert!(read(&reports.join("LEADERBOARD.md")).contains("## Sets"));
    // A rerun reuses every run and writes the same board.
    let before = read(&reports.join("leaderboard_sets.csv"));
    let second = evaluate(&registry, &specs, &options, &NoProgress).expect("runs");
    assert_eq!((second.fresh, second.cached), (0, 6));
    assert_eq!(read(&reports.join("leaderboard_sets.csv")), before);

    // A set method run elsewhere: its labels (the set parts, one id per part in every view,
    // renamed) written as the records of the pairs (0, k), scored onto the set board. The
    // lifting keeps consistent labels as they are, so it scores 1 everywhere.
    let set_dir = dir.path().join("datasets/tiny-sets");
    let manifest = pairs::dataset::Manifest::read(&set_dir).expect("a manifest");
    let hash = &manifest.files[pairs::dataset::SETS_FILE].sha256;
    let file = dir.path().join("perfect.mcap");
    let header = PredictionHeader::new("perfect-sets", "", hash);
    let mut writer = PredictionWriter::create(&file, &header).expect("created");
    let dataset = pairs::dataset::Dataset::open(&set_dir).expect("opens");
    for set in dataset.sets().expect("sets") {
        let set = set.expect("a set");
        let labels: Vec<Vec<u32>> = set
            .truth()
            .parts
            .iter()
            .map(|v| v.iter().map(|&p| 7 - u32::from(p)).collect())
            .collect();
        for k in 1..set.len() {
            let prediction = Prediction {
                segments_p: labels[0].clone(),
                segments_q: labels[k].clone(),
                ..Prediction::default()
            };
            let id = set.pair_id(0, k);
            writer.write(&PredictionRecord::from_prediction(&id, &prediction)).expect("written");
        }
    }
    writer.finish().expect("finished");
    let setup = CommandOptions {
        datasets_root: dir.path().join("datasets"),
        reports: reports.clone(),
        gallery_pairs: 1,
    };
    let (name, _) =
        score_predictions(&registry, &specs, "tiny-sets", &file, None, &setup, &NoProgress)
            .expect("scored");
    assert_eq!(name, "perfect-sets");
    let board = rows(&reports.join("leaderboard_sets.csv"));
    let perfect = board.iter().find(|r| r["method"] == "perfect-sets").expect("on the board");
    assert_eq!(perfect["flow_source"], "external");
    for c in ["multi_scan_miou", "per_scan_miou", "multi_scan_ri", "per_scan_ri"] {
        assert_eq!(perfect[c], "1.0000", "{c}");
    }
    // Labels without motions: no motion is scored.
    assert_eq!((perfect["rotation_deg"].as_str(), perfect["translation"].as_str()), ("", ""));
    // The other rows stay, from the cache.
    assert!(board.iter().any(|r| r["method"] == "one-part"));
}
