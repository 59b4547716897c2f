//! Generation speed: one object's pairs, and a paper-size SF2F set (175 objects, 875 pairs,
//! N = 512) written to disk. Target: the paper-size set in under 5 s on 2 cores.

use criterion::{criterion_group, criterion_main, Criterion};
use generator::config::GeneratorConfig;
use generator::generate::{generate_dataset, object_pairs};

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
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
