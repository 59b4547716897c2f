//! Set datasets (`generator --kind sets`): deterministic whatever the thread count, sharded
//! and merged byte for byte, read back as written, images for the scanned views, and bad
//! set configs refused by field.

use std::path::Path;

use generator::config::{GeneratorConfig, SetsConfig};
use generator::generate::{generate_dataset, object_sets};
use generator::shard::merge_shards;
use pairs::dataset::{Dataset, Shard, INDEX_FILE, MANIFEST_FILE, SETS_FILE};
use pairs::{SetMode, ViewKind};

fn config(mode: SetMode, views: u32) -> GeneratorConfig {
    GeneratorConfig {
        objects: 9,
        points: 96,
        min_part_points: 4,
        seed: 5,
        sets: Some(SetsConfig { views, mode, per_object: 2 }),
        ..Default::default()
    }
}

fn generate_with_threads(threads: usize, dir: &Path, config: &GeneratorConfig) {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("pool");
    pool.install(|| generate_dataset(config, dir, false, None, |_| {})).expect("generate");
}

fn same_files(a: &Path, b: &Path) {
    for name in [SETS_FILE, INDEX_FILE, MANIFEST_FILE] {
        let read = |d: &Path| std::fs::read(d.join(name)).expect("read");
        assert!(read(a) == read(b), "{name} differs");
    }
}

#[test]
fn set_datasets_are_deterministic_and_read_back_as_generated() {
    let config = config(SetMode::Full, 5);
    let (a, b) = (tempfile::tempdir().expect("tempdir"), tempfile::tempdir().expect("tempdir"));
    generate_with_threads(1, a.path(), &config);
    generate_with_threads(2, b.path(), &config);
    same_files(a.path(), b.path());
    let dataset = Dataset::open(a.path()).expect("opens");
    dataset.verify().expect("checksums hold");
    assert!(dataset.holds_sets());
    assert_eq!(dataset.manifest().counts.sets, 18);
    assert_eq!(dataset.manifest().counts.pairs, 0);
    let read: Vec<_> = dataset.sets().expect("sets").collect::<Result<_, _>>().expect("valid");
    let made: Vec<_> = (0..config.objects)
        .flat_map(|i| object_sets(&config, i, false).expect("sets"))
        .map(|g| g.set)
        .collect();
    assert_eq!(read.len(), made.len());
    assert!(read == made, "the sets read back differ from the sets generated");
    for set in &read {
        assert_eq!(set.len(), 5);
        assert_eq!(set.truth().parts.len(), 5);
        // Part ids hold in every view: every set part has points in every view.
        for parts in &set.truth().parts {
            for s in 0..set.truth().num_parts() {
                assert!(parts.iter().filter(|&&p| usize::from(p) == s).count() >= 4);
            }
        }
    }
    let index = std::fs::read_to_string(a.path().join(INDEX_FILE)).expect("index");
    assert!(index.starts_with("id,mode,views,category,object_id,set_index,articulations"));
    assert_eq!(index.lines().count(), 19);
    // A pair reader refuses the folder: it holds sets.
    assert!(dataset.pairs().is_err());
}

#[test]
fn scanned_views_come_with_their_images_and_shards_merge_byte_for_byte() {
    let config = GeneratorConfig { objects: 5, ..config(SetMode::Mixed, 3) };
    let root = tempfile::tempdir().expect("tempdir");
    let whole = root.path().join("whole");
    generate_dataset(&config, &whole, false, None, |_| {}).expect("whole");
    let shards: Vec<_> = [1, 0]
        .map(|i| {
            let dir = root.path().join(i.to_string());
            generate_dataset(&config, &dir, false, Some(Shard { index: i, count: 2 }), |_| {})
                .expect("shard");
            dir
        })
        .into();
    let merged = root.path().join("merged");
    merge_shards(&shards, &merged, false, |_| {}).expect("merge");
    same_files(&whole, &merged);
    let dataset = Dataset::open(&whole).expect("opens");
    dataset.verify().expect("checksums hold, images included");
    for set in dataset.sets().expect("sets") {
        let set = set.expect("valid");
        let kinds: Vec<ViewKind> = set.input().views.iter().map(|v| v.kind).collect();
        assert_eq!(kinds, [ViewKind::Full, ViewKind::Scan, ViewKind::Scan]);
        let images = dataset.read_set_images(&set).expect("images");
        assert!(images[0].is_none() && images[1..].iter().all(Option::is_some));
        for (k, image) in images.iter().enumerate().skip(1) {
            let image = image.as_ref().expect("an image");
            assert!(image.depth.starts_with(b"\x89PNG"), "view {k}'s depth is a PNG");
        }
        // A scan as P with the full view 0 as Q makes no pair; the other way round does.
        assert!(set.pair(1, 0).is_err());
        assert_eq!(set.pair(0, 2).expect("SF2P").input().kind, pairs::PairKind::Sf2p);
        assert_eq!(set.pair(1, 2).expect("SP2P").input().kind, pairs::PairKind::Sp2p);
    }
}

#[test]
fn bad_set_configs_name_the_field() {
    let cases = [
        (config(SetMode::Full, 1), "sets.views"),
        (config(SetMode::Full, 17), "sets.views"),
        (
            GeneratorConfig {
                sets: Some(SetsConfig { per_object: 0, ..SetsConfig::default() }),
                ..config(SetMode::Full, 4)
            },
            "sets.per_object",
        ),
        (GeneratorConfig { kind: pairs::PairKind::Xf2f, ..config(SetMode::Full, 4) }, "kind"),
    ];
    for (config, field) in cases {
        let err = config.validate().expect_err(field).to_string();
        assert!(err.contains(field), "{err}");
    }
    let parsed: GeneratorConfig =
        toml::from_str("[sets]\nviews = 6\nmode = \"scan\"\n").expect("a sets table parses");
    assert_eq!(parsed.sets, Some(SetsConfig { views: 6, mode: SetMode::Scan, per_object: 1 }));
    assert!(parsed.resolved().scan.is_some(), "a scanned set dataset records its scanner");
}

#[test]
fn user_assets_give_sets_too() {
    use generator::asset_dataset::{generate_asset_dataset, load_assets};
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/assets");
    let config = GeneratorConfig {
        points: 128,
        min_part_points: 4,
        seed: 5,
        sets: Some(SetsConfig { views: 3, mode: SetMode::Mixed, per_object: 2 }),
        ..Default::default()
    };
    let sources = load_assets(&root, &config).expect("listed");
    assert!(!sources.is_empty());
    let out = tempfile::tempdir().expect("tempdir");
    let made = generate_asset_dataset(&config, &root, &sources, out.path(), false, |_| {})
        .expect("a set dataset of the assets");
    assert!(made.failures.is_empty(), "{:?}", made.failures);
    assert_eq!(made.manifest.counts.sets, 2 * sources.len() as u64);
    let dataset = Dataset::open(out.path()).expect("opens");
    for set in dataset.sets().expect("sets") {
        let set = set.expect("valid");
        assert_eq!(set.len(), 3);
        assert_eq!(set.provenance().category, "lamp");
        for k in 1..3 {
            set.pair(0, k).expect("the pair of view 0 and a scan");
        }
    }
}
