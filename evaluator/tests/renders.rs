//! The render benchmark: the default render's clouds back-projected and scored on joints.
//! The `gt` oracle (true parts and motions, joints estimated from them) must land on the
//! true joints in every convention; a method that fails leaves every joint missed; the
//! LEADERBOARD section lists both.

use std::sync::Arc;

use evaluator::boards::render_joints::{score_joints, section, upsert, RenderJointRow};
use evaluator::rows::registry::{Board, Registry};
use evaluator::running::renders::render_joints;
use generator::config::GeneratorConfig;
use generator::objects::built_in_objects;
use pairs::metrics::render_joints::Variant;
use pairs::{Method, MethodError, PairInput, Prediction};
use renderer::layout::{write_render, Layout};
use renderer::{RenderConfig, RenderJob};

/// Renders the first `objects` test objects into `root` (native layout, two states, `views`
/// cameras of `width` x `height`).
fn render(root: &std::path::Path, objects: u32, width: u32, height: u32, views: u32) {
    let config = RenderConfig { width, height, views, states: 2, ..RenderConfig::default() };
    let objects = GeneratorConfig { objects, ..GeneratorConfig::default() };
    let jobs = built_in_objects(&objects)
        .expect("objects")
        .into_iter()
        .map(|o| RenderJob::new(&config, 0, o, None, Layout::Native));
    write_render(&config, 0, jobs, Layout::Native, root, false, &|_| {}).expect("render");
}

struct Fails;

impl Method for Fails {
    fn name(&self) -> &str {
        "fails"
    }

    fn predict(&self, input: &PairInput) -> Result<Prediction, MethodError> {
        Err(MethodError::new(self.name(), &input.id, "always"))
    }
}

#[test]
fn the_oracle_finds_the_true_joints_and_a_failing_row_none() {
    let dir = tempfile::tempdir().expect("tmp");
    let root = dir.path().join("render");
    // Six objects: the desk lamp (object 5) has parts on moving parts.
    render(&root, 6, 160, 120, 6);
    let mut registry = Registry::new();
    registry.oracle();
    registry.method(Arc::new(Fails), Board::Both, "fails v1");
    let entries: Vec<_> = registry.entries().iter().collect();
    let joints = render_joints(&entries, "render", &root, &|_| {}).expect("joints");
    let truth = pairs::renders::read_truth(&root).expect("truth");
    let rows: Vec<RenderJointRow> =
        joints.iter().flat_map(|(row, p)| score_joints(&truth, p, "render", row)).collect();
    assert_eq!(rows.len(), 2 * Variant::ALL.len());
    let row = |method: &str, variant: Variant| -> &RenderJointRow {
        rows.iter().find(|r| r.method == method && r.variant == variant).expect("row")
    };
    for variant in Variant::ALL {
        let gt = row("gt", variant).scores;
        assert!(
            gt.joints >= 3 && gt.matched == gt.joints && gt.type_correct == gt.joints,
            "{variant:?}: {gt:?}"
        );
        assert!(gt.angle() < 0.5, "{variant:?}: axis {}°", gt.angle());
        let state = gt.revolute_state();
        assert!(state.is_nan() || state < 0.5, "{variant:?}: state {state}°");
        assert!(
            gt.distances == 0 || gt.distance() < 0.05,
            "{variant:?}: distance {}",
            gt.distance()
        );
        let failed = row("fails", variant).scores;
        assert_eq!((failed.joints, failed.matched), (gt.joints, 0));
    }
    let reports = dir.path().join("reports");
    upsert(&reports, &rows).expect("board");
    let text = section(&reports).expect("a section");
    assert!(text.contains("| render | `gt` |") && text.contains("| render | `fails` |"), "{text}");
}

#[test]
fn a_render_folder_given_with_dataset_is_scored_on_its_joints() {
    use evaluator::boards::render_joints::RENDER_JOINTS_FILE;
    use evaluator::commands::pipeline::{evaluate, NoProgress, Options};
    use evaluator::datasets::DatasetSpec;

    let dir = tempfile::tempdir().expect("tmp");
    let mine = dir.path().join("mine");
    render(&mine, 2, 96, 72, 4);
    let mut registry = Registry::new();
    registry.oracle();
    let reports = dir.path().join("reports");
    let options = Options {
        datasets: vec!["myrender".into()],
        methods: Vec::new(),
        limit: None,
        datasets_root: dir.path().join("datasets"),
        reports: reports.clone(),
        force: false,
        gallery_pairs: 0,
        validation: Vec::new(),
    };
    let spec = DatasetSpec::user("myrender", &mine);
    evaluate(&registry, &[spec], &options, &NoProgress).expect("the render is scored");
    let board = std::fs::read_to_string(reports.join(RENDER_JOINTS_FILE)).expect("joints board");
    let rows: Vec<Vec<&str>> = board
        .lines()
        .map(|l| l.split(',').collect::<Vec<_>>())
        .filter(|r| r[0] == "myrender")
        .collect();
    assert_eq!(rows.len(), Variant::ALL.len(), "{board}");
    for row in &rows {
        // The oracle matches every true joint of the two objects.
        assert_eq!(row[1], "gt", "{board}");
        assert!(row[3].parse::<u32>().expect("joints") > 0 && row[3] == row[4], "{board}");
    }
    // The render is not mistaken for a dataset of pairs, and no default render was made.
    assert!(!dir.path().join("datasets").join("render").exists());
}
