//! Inputs of the fuzz targets in `pairs/fuzz` (seeds and any input that once crashed one),
//! replayed: `tests/fuzz_regressions/<target>/<file>` is fed to the function the target
//! `<target>` runs, which must return without panicking. A file named `<n>-pairs.*` or
//! `<n>-records.*` must read exactly `n` pairs or records (the valid seeds).

use std::path::Path;

fn replay(target: &str, read: fn(&[u8]) -> usize) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz_regressions").join(target);
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.expect("an entry").path())
        .collect();
    files.sort();
    assert!(!files.is_empty(), "{} holds no inputs", dir.display());
    for file in files {
        let data = std::fs::read(&file).expect("readable");
        let read = read(&data);
        let name = file.file_name().and_then(|n| n.to_str()).unwrap_or_default();
        if let Some((n, _)) = name.split_once("-pairs.").or(name.split_once("-records.")) {
            assert_eq!(read.to_string(), n, "{name}");
        }
    }
}

#[test]
fn pair_reader_inputs_are_read_or_refused() {
    replay("pair_reader", pairs::fuzz::read_pairs);
}

#[test]
fn set_reader_inputs_are_read_or_refused() {
    replay("set_reader", pairs::fuzz::read_sets);
}

#[test]
fn prediction_reader_inputs_are_read_or_refused() {
    replay("prediction_reader", pairs::fuzz::read_predictions);
}

/// Rewrites the valid seeds and their truncated halves (`cargo test -p pairs --test
/// fuzz_regressions -- --ignored`); the fuzz targets start from them
/// (`cargo +nightly fuzz run pair_reader tests/fuzz_regressions/pair_reader`, from `pairs/fuzz`
/// with the folder given as `../tests/fuzz_regressions/pair_reader`).
#[test]
#[ignore = "writes the seed inputs into the source tree"]
fn write_seeds() {
    use pairs::dataset::{DatasetOrigin, DatasetWriter, PAIRS_FILE};
    use pairs::predictions::{PredictionHeader, PredictionRecord, PredictionWriter};
    use pairs::{synthetic, Prediction};

    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz_regressions");
    let tmp = tempfile::tempdir().expect("tempdir");
    let pair = synthetic::hinge_pair("seed-0", 4, 0.5);
    let mut writer = DatasetWriter::create(tmp.path(), false).expect("create");
    writer.write(&pair).expect("write");
    let origin_of = |version: &str| DatasetOrigin {
        generator_version: version.into(),
        seed: 0,
        config: serde_json::json!({}),
        splits: Default::default(),
        shard: None,
        assets: Vec::new(),
        left_out: Default::default(),
    };
    writer.finish(origin_of("seed")).expect("finish");
    let pairs_file = std::fs::read(tmp.path().join(PAIRS_FILE)).expect("written");

    let predictions = tmp.path().join("predictions.mcap");
    let header = PredictionHeader::new("seed", "1", &"0".repeat(64));
    let mut writer = PredictionWriter::create(&predictions, &header).expect("create");
    let t = pair.truth();
    let full = Prediction {
        flow: t.flow.clone(),
        segments_p: t.part_p.iter().map(|&k| u32::from(k)).collect(),
        segments_q: t.part_q.iter().map(|&k| u32::from(k)).collect(),
        motions: t.motions.clone(),
        corr_mask: Some(vec![1.0; t.part_p.len()]),
        ..Prediction::default()
    };
    writer.write(&PredictionRecord::from_prediction(pair.id(), &full)).expect("write");
    let minimal = Prediction { segments_p: vec![0; 3], ..Prediction::default() };
    writer.write(&PredictionRecord::from_prediction("m", &minimal)).expect("write");
    writer.write(&PredictionRecord::failure("f", "seed failure")).expect("write");
    writer.finish().expect("finish");
    let prediction_file = std::fs::read(&predictions).expect("written");

    let sets_dir = tmp.path().join("sets");
    let mut writer = DatasetWriter::create_sets(&sets_dir, false).expect("create");
    let set = synthetic::hinge_set("seed-set", 3, &[0.0, 0.4, 0.4]);
    writer.write_set(&set, &[None, None, None]).expect("write");
    writer.finish(origin_of("seed")).expect("finish");
    let sets_file = std::fs::read(sets_dir.join(pairs::dataset::SETS_FILE)).expect("written");

    for (target, bytes, count) in [
        ("pair_reader", pairs_file, "1-pairs"),
        ("prediction_reader", prediction_file, "3-records"),
        ("set_reader", sets_file, "1-pairs"),
    ] {
        let dir = root.join(target);
        std::fs::create_dir_all(&dir).expect("a folder");
        std::fs::write(dir.join(format!("{count}.mcap")), &bytes).expect("written");
        std::fs::write(dir.join("truncated.mcap"), &bytes[..bytes.len() / 2]).expect("written");
    }
}

#[test]
fn render_record_inputs_are_read_or_refused() {
    replay("render_records", pairs::fuzz::read_render_records);
}

#[test]
fn joint_prediction_inputs_are_read_or_refused() {
    replay("joint_predictions", pairs::fuzz::read_joint_predictions);
}
