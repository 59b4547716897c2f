//! Time per pair of every baseline at N = 512 (the synthetic hinge, 16 x 16 points per
//! part): segmenters on the exact flow, methods on the pair. The budgets on 2
//! cores: SeqRANSAC, SC, JLC under 100 ms; NRR and ED under 2 s; NN, ICP, FPFH under 50 ms.

use baselines::{methods, segmenters};
use criterion::{criterion_group, criterion_main, Criterion};
use pairs::synthetic::hinge_pair;
use std::time::Duration;

fn bench(c: &mut Criterion) {
    let pair = hinge_pair("bench", 16, 0.8);
    assert_eq!(pair.input().p.len(), 512);
    let mut group = c.benchmark_group("baselines_n512");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    for segmenter in segmenters() {
        group.bench_function(segmenter.name(), |b| {
            b.iter(|| {
                segmenter
                    .segment(pair.input(), pair.truth().flow.as_deref().expect("a flow"))
                    .expect("segments")
            })
        });
    }
    for method in methods() {
        group.bench_function(method.name(), |b| {
            b.iter(|| method.predict(pair.input()).expect("predicts"))
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
