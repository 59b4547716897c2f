//! Cross-validated rows: tuning reads validation pairs only (a test set is refused), widens a
//! grid whose best value sits on its edge, is cached by the flow source's fingerprint, and a
//! tuned row in the evaluation is scored with the chosen parameters and states them.

use std::collections::BTreeSet;
use std::path::Path;
use std::sync::{Arc, Mutex};

use articulated::categories::Split;
use evaluator::commands::pipeline::{evaluate, NoProgress, Options};
use evaluator::datasets::{DatasetSpec, LoadedDataset};
use evaluator::rows::grid::{Axis, Grid};
use evaluator::rows::registry::{Board, FlowSource, Registry, Runner};
use evaluator::running::run::FlowCache;
use evaluator::tuning::tune;
use evaluator::EvalError;
use generator::config::GeneratorConfig;
use pairs::math::Vector3;
use pairs::segments::complete_prediction;
use pairs::synthetic::hinge_pair;
use pairs::{MethodError, PairInput, Prediction, Segmenter};

/// Two segments split by flow magnitude: points moving more than `tau` against the rest. On
/// a hinge pair (a still base, a turning lid) a small `tau` finds the lid.
#[derive(Debug)]
struct FlowCut {
    tau: f32,
    seen: Arc<Mutex<Vec<String>>>,
}

impl Segmenter for FlowCut {
    fn name(&self) -> &str {
        "flowcut"
    }

    fn segment(&self, input: &PairInput, flow: &[Vector3]) -> Result<Prediction, MethodError> {
        self.seen.lock().expect("not poisoned").push(input.id.clone());
        let labels: Vec<u8> = flow.iter().map(|f| u8::from(f.norm() > self.tau)).collect();
        Ok(complete_prediction(input, flow, &labels, false))
    }
}

fn grid(seen: &Arc<Mutex<Vec<String>>>, values: &[f64]) -> Grid {
    let seen = seen.clone();
    let mut grid = Grid::new(vec![Axis::new("tau", values, 2.0, 0.001, 4.0)], move |v| {
        let segmenter = FlowCut { tau: v[0] as f32, seen: seen.clone() };
        // Its parameters only (its Debug form would print the pairs seen so far).
        let fingerprint = format!("flowcut tau={}", segmenter.tau);
        (
            Runner::Segmenter { segmenter: Arc::new(segmenter), flow: FlowSource::GroundTruth },
            fingerprint,
        )
    });
    grid.max_rounds = 8;
    grid
}

fn dataset(name: &str, split: Split, angle: f32) -> LoadedDataset {
    let pairs =
        (0..3).map(|i| hinge_pair(&format!("{name}-{i}"), 6, angle + 0.1 * i as f32)).collect();
    LoadedDataset {
        name: name.into(),
        pairs,
        content_hash: format!("{name}-hash"),
        split: Some(split),
        cross_instance: false,
    }
}

#[test]
fn tuning_reads_validation_pairs_only_and_widens_an_edge() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let seen = Arc::new(Mutex::new(Vec::new()));
    let validation = dataset("val", Split::Validation, 0.8);
    let test = dataset("test", Split::Test, 0.8);
    let flows = FlowCache::default();
    // A test set never reaches tuning.
    let err = tune(
        "flowcut@gt-flow",
        &grid(&seen, &[0.8, 1.6]),
        "gt",
        &[&validation, &test],
        &flows,
        dir.path(),
        &|_| {},
    )
    .expect_err("a test set is refused");
    assert!(matches!(err, EvalError::NotValidation { ref name, .. } if name == "test"), "{err}");
    assert!(seen.lock().expect("not poisoned").is_empty(), "nothing was segmented");

    // Every threshold of the starting grid is above the lid's motion except at the hinge:
    // the best is the smallest value, on the grid's edge, so the grid widens downwards.
    let sweep = tune(
        "flowcut@gt-flow",
        &grid(&seen, &[0.8, 1.6]),
        "gt",
        &[&validation],
        &flows,
        dir.path(),
        &|_| {},
    )
    .expect("tunes");
    let chosen = &sweep.candidates[sweep.chosen];
    assert!(chosen.values[0] < 0.8, "widened below the starting grid: {sweep:?}");
    assert!(chosen.round > 0);
    let start_best =
        sweep.candidates.iter().filter(|c| c.round == 0).map(|c| c.iou).fold(0.0, f64::max);
    assert!(chosen.iou > start_best, "{sweep:?}");
    // Widening stopped once the best lay inside the grid: scored values on both sides.
    let tau = chosen.values[0];
    assert!(sweep.candidates.iter().any(|c| c.values[0] < tau), "{sweep:?}");
    assert!(sweep.candidates.iter().any(|c| c.values[0] > tau), "{sweep:?}");
    let ids: BTreeSet<String> = seen.lock().expect("not poisoned").iter().cloned().collect();
    let validation_ids: BTreeSet<String> =
        validation.pairs.iter().map(|p| p.id().to_owned()).collect();
    assert_eq!(ids, validation_ids, "tuning saw exactly the validation pairs");

    // The sweep is written, and cached by the flow source's fingerprint.
    let csv =
        std::fs::read_to_string(dir.path().join("tuning/flowcut@gt-flow.csv")).expect("written");
    assert_eq!(csv.lines().count(), sweep.candidates.len() + 1);
    assert_eq!(csv.lines().filter(|l| l.ends_with(",true")).count(), 1);
    let calls = seen.lock().expect("not poisoned").len();
    let again = tune(
        "flowcut@gt-flow",
        &grid(&seen, &[0.8, 1.6]),
        "gt",
        &[&validation],
        &flows,
        dir.path(),
        &|_| {},
    )
    .expect("cached");
    assert_eq!((again, seen.lock().expect("not poisoned").len()), (sweep, calls));
    tune(
        "flowcut@gt-flow",
        &grid(&seen, &[0.8, 1.6]),
        "other source",
        &[&validation],
        &flows,
        dir.path(),
        &|_| {},
    )
    .expect("retuned");
    assert!(seen.lock().expect("not poisoned").len() > calls, "a new source fingerprint retunes");
}

fn tiny(split: Split, seed: u64) -> GeneratorConfig {
    GeneratorConfig {
        objects: 2,
        states_per_object: 3,
        pairs_per_object: 2,
        points: 96,
        min_part_points: 4,
        split,
        seed,
        ..GeneratorConfig::default()
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
        validation: vec![DatasetSpec::generated("val-tiny", tiny(Split::Validation, 7))],
    }
}

#[test]
fn a_tuned_row_is_scored_with_its_chosen_parameters() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let seen = Arc::new(Mutex::new(Vec::new()));
    let mut registry = Registry::new();
    registry.oracle();
    registry.tuned("flowcut@gt-flow", grid(&seen, &[0.8, 1.6]), Board::Segmentation, "gt", true);
    let specs = [DatasetSpec::generated("tiny", tiny(Split::Test, 0))];
    let summary = evaluate(&registry, &specs, &options(dir.path()), &NoProgress).expect("runs");
    assert_eq!(summary.sweeps.len(), 1);
    let chosen = summary.sweeps[0].chosen_label();
    let report =
        std::fs::read_to_string(dir.path().join("reports/LEADERBOARD.md")).expect("written");
    assert!(report.contains("## Tuned parameters") && report.contains(&chosen), "{report}");
    let seg =
        std::fs::read_to_string(dir.path().join("reports/leaderboard_seg.csv")).expect("written");
    let row = seg.lines().find(|l| l.contains("flowcut@gt-flow")).expect("the tuned row is listed");
    assert!(row.starts_with("tiny,flowcut@gt-flow,gt-flow,true,"), "{row}");
    // The validation set is not a board's dataset.
    assert!(!seg.contains("val-tiny"), "{seg}");
    // A rerun reuses the sweep and the run.
    let again = evaluate(&registry, &specs, &options(dir.path()), &NoProgress).expect("runs");
    assert_eq!((again.fresh, again.cached), (0, 2));
    assert_eq!(again.sweeps, summary.sweeps);
}
