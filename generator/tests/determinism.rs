//! The same config and seed give byte-identical dataset files, whatever the thread count.

use generator::config::GeneratorConfig;
use generator::generate::generate_dataset;
use pairs::dataset::{Dataset, INDEX_FILE, MANIFEST_FILE, PAIRS_FILE};

fn generate_with_threads(threads: usize, dir: &std::path::Path, config: &GeneratorConfig) {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("pool");
    pool.install(|| generate_dataset(config, dir, false, None, |_| {})).expect("generate");
}

#[test]
fn one_and_two_threads_give_byte_identical_files() {
    // More objects than one parallel batch, so that batches and threads interleave.
    let config = GeneratorConfig {
        objects: 40,
        pairs_per_object: 2,
        points: 64,
        min_part_points: 4,
        seed: 5,
        ..Default::default()
    };
    let (a, b) = (tempfile::tempdir().expect("tempdir"), tempfile::tempdir().expect("tempdir"));
    generate_with_threads(1, a.path(), &config);
    generate_with_threads(2, b.path(), &config);
    for name in [PAIRS_FILE, INDEX_FILE, MANIFEST_FILE] {
        let read = |d: &std::path::Path| std::fs::read(d.join(name)).expect("read");
        assert!(read(a.path()) == read(b.path()), "{name} differs between 1 and 2 threads");
    }
    let dataset = Dataset::open(a.path()).expect("open");
    dataset.verify().expect("checksums");
    let pairs: Vec<_> =
        dataset.pairs().expect("pairs").collect::<Result<_, _>>().expect("valid pairs");
    assert_eq!(pairs.len(), 80);
    assert_eq!(dataset.manifest().origin.config["seed"], 5);
    let other_seed = GeneratorConfig { seed: 6, ..config };
    let c = tempfile::tempdir().expect("tempdir");
    generate_with_threads(2, c.path(), &other_seed);
    let read = |d: &std::path::Path| std::fs::read(d.join(PAIRS_FILE)).expect("read");
    assert!(read(a.path()) != read(c.path()), "the seed has no effect");
}

#[test]
fn existing_datasets_are_not_overwritten_by_default() {
    let config =
        GeneratorConfig { objects: 1, points: 64, min_part_points: 4, ..Default::default() };
    let dir = tempfile::tempdir().expect("tempdir");
    generate_dataset(&config, dir.path(), false, None, |_| {}).expect("first");
    let before = std::fs::read(dir.path().join(PAIRS_FILE)).expect("read");
    let again = GeneratorConfig { seed: 9, ..config };
    assert!(generate_dataset(&again, dir.path(), false, None, |_| {}).is_err());
    assert_eq!(std::fs::read(dir.path().join(PAIRS_FILE)).expect("read"), before);
    generate_dataset(&again, dir.path(), true, None, |_| {}).expect("forced");
    assert_ne!(std::fs::read(dir.path().join(PAIRS_FILE)).expect("read"), before);
}
