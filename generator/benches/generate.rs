//! Generation speed. Targets on 2 cores: a paper-size SF2F set (175 objects, 875 pairs,
//! N = 512) written to disk in under 5 s, and the training stream delivering at least
//! 1,000 full pairs per second.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use generator::config::GeneratorConfig;
use generator::generate::{generate_dataset, object_pairs};
use generator::stream::TrainingStream;

/// Pairs drawn from the training stream per iteration.
const STREAM_PAIRS: u64 = 2000;

fn bench(c: &mut Criterion) {
    let config = GeneratorConfig::default();
    c.bench_function("object_pairs (5 pairs, N=512)", |b| {
        b.iter(|| object_pairs(&config, 1).expect("pairs"))
    });
    let mut group = c.benchmark_group("dataset");
    group.sample_size(10);
    group.bench_function("paper-size SF2F (875 pairs, N=512)", |b| {
        b.iter(|| {
            let dir = tempfile::tempdir().expect("tempdir");
            generate_dataset(&config, dir.path(), false, None, |_| {}).expect("dataset")
        })
    });
    group.throughput(Throughput::Elements(STREAM_PAIRS));
    group.bench_function("training stream (N=512, pairs/s)", |b| {
        b.iter(|| {
            let stream = TrainingStream::new(GeneratorConfig::training()).expect("stream");
            stream.take(STREAM_PAIRS as usize).try_fold(0, |n, p| p.map(|_| n + 1)).expect("pairs")
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
