//! Sharding for clusters: the shards of a run, merged, are byte-identical to the unsharded
//! run; shards that do not belong together are refused.

use std::path::{Path, PathBuf};

use generator::config::GeneratorConfig;
use generator::generate::generate_dataset;
use generator::shard::{merge_shards, ShardError};
use pairs::dataset::{Shard, INDEX_FILE, MANIFEST_FILE, PAIRS_FILE};

fn config() -> GeneratorConfig {
    GeneratorConfig {
        objects: 11,
        pairs_per_object: 2,
        points: 64,
        min_part_points: 4,
        seed: 3,
        ..Default::default()
    }
}

/// Generates shard `index` of `count` of `config` into `root/<index>`.
fn shard(root: &Path, config: &GeneratorConfig, index: u32, count: u32) -> PathBuf {
    let dir = root.join(index.to_string());
    generate_dataset(config, &dir, false, Some(Shard { index, count }), |_| {}).expect("shard");
    dir
}

#[test]
fn four_merged_shards_are_byte_identical_to_one_run() {
    let config = config();
    let root = tempfile::tempdir().expect("tempdir");
    let whole = root.path().join("whole");
    generate_dataset(&config, &whole, false, None, |_| {}).expect("whole");
    // Shards given out of order, as a shell glob or a scheduler might list them.
    let shards: Vec<PathBuf> = [2, 0, 3, 1].map(|i| shard(root.path(), &config, i, 4)).into();
    let merged = root.path().join("merged");
    let manifest = merge_shards(&shards, &merged, false, |_| {}).expect("merge");
    assert_eq!(manifest.counts.pairs, 22);
    assert_eq!(manifest.origin.shard, None);
    for name in [PAIRS_FILE, INDEX_FILE, MANIFEST_FILE] {
        let read = |d: &Path| std::fs::read(d.join(name)).expect("read");
        assert!(read(&whole) == read(&merged), "{name} differs between merged and whole");
    }
}

#[test]
fn shards_that_do_not_belong_together_are_refused() {
    let config = config();
    let root = tempfile::tempdir().expect("tempdir");
    let out = root.path().join("out");
    let a = shard(root.path(), &config, 0, 2);
    let missing = merge_shards(std::slice::from_ref(&a), &out, false, |_| {});
    assert!(matches!(missing, Err(ShardError::Incomplete { .. })), "{missing:?}");
    let other = GeneratorConfig { seed: 4, ..config.clone() };
    let b = shard(&root.path().join("other"), &other, 1, 2);
    let mixed = merge_shards(&[a.clone(), b], &out, false, |_| {});
    assert!(matches!(mixed, Err(ShardError::Mismatch { what: "seed", .. })), "{mixed:?}");
    let twice = merge_shards(&[a.clone(), a], &out, false, |_| {});
    assert!(matches!(twice, Err(ShardError::Incomplete { .. })), "{twice:?}");
    let whole = root.path().join("whole");
    generate_dataset(&config, &whole, false, None, |_| {}).expect("whole");
    let not_a_shard = merge_shards(&[whole], &out, false, |_| {});
    assert!(matches!(not_a_shard, Err(ShardError::NotAShard(_))), "{not_a_shard:?}");
    assert!(!out.join(MANIFEST_FILE).exists(), "a refused merge wrote a dataset");
}
