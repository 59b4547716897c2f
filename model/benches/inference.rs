//! Speed of the inference procedure with the shipped weights (`model/weights/cpu`) at
//! N = 512: one pass (`net`), the full iterative procedure (`net-iter`, up to 10 passes)
//! and the 48-rotation search (one batch of 48 flow evaluations). Targets on 2 cores:
//! 0.4 s, 2 s and 1 s.

use std::path::Path;

use criterion::{criterion_group, criterion_main, Criterion};
use model::inference::InferenceParams;
use model::train::validation::validation_pairs;
use model::weights;

// The binaries' allocator (jemalloc, from the `cli` crate), so timings are theirs.
use cli as _;

fn bench(c: &mut Criterion) {
    let weights = Path::new(env!("CARGO_MANIFEST_DIR")).join("weights/cpu");
    let net = weights::load(&weights).expect("the shipped weights load").net;
    let pairs = validation_pairs(512, 2, false).expect("validation pairs");
    let input = pairs[0].input();
    let mut group = c.benchmark_group("inference");
    group.sample_size(10);
    group.bench_function("single_pass_n512", |b| {
        b.iter(|| net.infer(input, &InferenceParams::single_pass()).expect("runs"))
    });
    group.bench_function("iterative_n512", |b| {
        b.iter(|| net.infer(input, &InferenceParams::iterative()).expect("runs"))
    });
    group.bench_function("rotation_search_48_n512", |b| {
        b.iter(|| net.search_rotation(input).expect("runs"))
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
