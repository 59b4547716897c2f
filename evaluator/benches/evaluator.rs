//! The evaluator's own costs: scoring one pair at N = 512 (target under 1 ms), and a whole
//! evaluation's overhead (loading, checks, metrics, runs files, leaderboards, plots,
//! gallery, report) on 3 x 875 pairs with the `gt` and `one-part@gt-flow` rows, whose
//! predictions cost next to nothing (target under 10 s).
//!
//! `cargo bench -p evaluator`

use std::sync::Arc;

use criterion::{criterion_group, criterion_main, Criterion};
use evaluator::commands::pipeline::{evaluate, NoProgress, Options};
use evaluator::datasets::DatasetSpec;
use evaluator::rows::reference::OnePart;
use evaluator::rows::registry::{FlowSource, Registry};
use generator::config::GeneratorConfig;
use generator::generate::object_pairs;
use pairs::metrics::score_pair;
use pairs::{Prediction, Segmenter};

fn score_one_pair(c: &mut Criterion) {
    let config = GeneratorConfig::default();
    let pair = object_pairs(&config, 0).expect("a test object").remove(0).pair;
    let prediction: Prediction = OnePart
        .segment(pair.input(), pair.truth().flow.as_deref().expect("a flow"))
        .expect("one-part segments");
    c.bench_function("score_pair N=512 (flow, P and Q segmentation, motions)", |b| {
        b.iter(|| score_pair(&prediction, pair.input(), pair.truth()).expect("scores"))
    });
}

fn evaluation_overhead(c: &mut Criterion) {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let specs: Vec<DatasetSpec> = ["a", "b", "c"]
        .iter()
        .map(|name| DatasetSpec::generated(name, GeneratorConfig::default()))
        .collect();
    let mut registry = Registry::new();
    registry.oracle();
    let options = Options {
        datasets: Vec::new(),
        methods: Vec::new(),
        limit: None,
        datasets_root: dir.path().join("datasets"),
        reports: dir.path().join("reports"),
        force: true,
        gallery_pairs: 3,
        validation: Vec::new(),
    };
    // Generate the three datasets once, outside the measurement.
    evaluate(&registry, &specs, &options, &NoProgress).expect("the first evaluation runs");
    registry.combine(Arc::new(OnePart), FlowSource::GroundTruth, "bench", None);
    let mut group = c.benchmark_group("evaluation");
    group.sample_size(10);
    group.bench_function("gt + one-part@gt-flow on 3 x 875 pairs, forced", |b| {
        b.iter(|| evaluate(&registry, &specs, &options, &NoProgress).expect("evaluates"))
    });
    group.finish();
}

criterion_group!(benches, score_one_pair, evaluation_overhead);
criterion_main!(benches);
