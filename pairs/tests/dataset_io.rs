//! Dataset folders: round trips, determinism, and every bad-input case of the format.

use std::collections::BTreeMap;
use std::path::Path;

use pairs::dataset::schema::{PairRecord, PAIR_SCHEMA};
use pairs::dataset::{
    Dataset, DatasetOrigin, DatasetWriter, PairReader, MANIFEST_FILE, PAIRS_FILE,
};
use pairs::{synthetic, DatasetError, Pair, PairError};

fn origin() -> DatasetOrigin {
    DatasetOrigin {
        generator_version: "test".into(),
        seed: 7,
        config: serde_json::json!({"points": 32}),
        splits: Default::default(),
        shard: None,
        assets: Vec::new(),
        left_out: Default::default(),
    }
}

fn sample_pairs() -> Vec<Pair> {
    (0..3)
        .map(|i| synthetic::hinge_pair(&format!("hinge-{i}"), 4 + i, 0.3 * (i + 1) as f32))
        .collect()
}

fn write_dataset(dir: &Path, pairs: &[Pair]) {
    let mut writer = DatasetWriter::create(dir, false).expect("create");
    for pair in pairs {
        writer.write(pair).expect("write");
    }
    writer.finish(origin()).expect("finish");
}

fn read_all(dir: &Path) -> Result<Vec<Pair>, DatasetError> {
    Dataset::open(dir)?.pairs()?.collect()
}

/// Writes an MCAP file with a `/pair` channel of the given encoding and metadata.
fn write_raw_mcap(path: &Path, encoding: &str, schema: &str, messages: &[Vec<u8>]) {
    let file = std::io::BufWriter::new(std::fs::File::create(path).expect("create"));
    let mut w = mcap::Writer::new(file).expect("writer");
    let meta = BTreeMap::from([
        ("schema".to_string(), schema.to_string()),
        ("schema_version".to_string(), "1".to_string()),
    ]);
    let ch = w.add_channel(0, "/pair", encoding, &meta).expect("channel");
    for (i, m) in messages.iter().enumerate() {
        let header = mcap::records::MessageHeader {
            channel_id: ch,
            sequence: i as u32,
            log_time: i as u64,
            publish_time: i as u64,
        };
        w.write_to_known_channel(&header, m).expect("write");
    }
    w.finish().expect("finish");
}

fn encode(record: &PairRecord) -> Vec<u8> {
    let mut out = Vec::new();
    ciborium::into_writer(record, &mut out).expect("encode");
    out
}

#[test]
fn write_then_read_gives_identical_records() {
    let dir = tempfile::tempdir().expect("tempdir");
    let pairs = sample_pairs();
    write_dataset(dir.path(), &pairs);
    let dataset = Dataset::open(dir.path()).expect("open");
    dataset.verify().expect("checksums match");
    assert_eq!(dataset.manifest().counts.pairs, 3);
    assert_eq!(dataset.manifest().counts.categories["hinge"], 3);
    assert_eq!(read_all(dir.path()).expect("read"), pairs);
    let index = std::fs::read_to_string(dir.path().join("index.csv")).expect("index");
    assert_eq!(index.lines().count(), 4, "header plus one row per pair");
    assert!(index.starts_with("id,kind,category,object_id"));
    assert!(!dir.path().join("pairs.mcap.partial").exists());
}

#[test]
fn same_pairs_give_byte_identical_files() {
    let (a, b) = (tempfile::tempdir().expect("tempdir"), tempfile::tempdir().expect("tempdir"));
    write_dataset(a.path(), &sample_pairs());
    write_dataset(b.path(), &sample_pairs());
    for name in [PAIRS_FILE, "index.csv", MANIFEST_FILE] {
        let read = |d: &Path| std::fs::read(d.join(name)).expect("read");
        assert_eq!(read(a.path()), read(b.path()), "{name} differs");
    }
}

#[test]
fn existing_output_is_kept_unless_overwrite_is_asked() {
    let dir = tempfile::tempdir().expect("tempdir");
    write_dataset(dir.path(), &sample_pairs());
    let before = std::fs::read(dir.path().join(PAIRS_FILE)).expect("read");
    assert!(matches!(DatasetWriter::create(dir.path(), false), Err(DatasetError::Exists { .. })));
    // An unfinished overwrite leaves the old dataset as it was.
    let mut writer = DatasetWriter::create(dir.path(), true).expect("create");
    writer.write(&synthetic::hinge_pair("other", 3, 1.0)).expect("write");
    drop(writer);
    assert_eq!(std::fs::read(dir.path().join(PAIRS_FILE)).expect("read"), before);
    assert_eq!(read_all(dir.path()).expect("read").len(), 3);
}

#[test]
fn missing_or_bad_manifest_is_reported() {
    let dir = tempfile::tempdir().expect("tempdir");
    assert!(matches!(Dataset::open(dir.path()), Err(DatasetError::MissingManifest { .. })));
    write_dataset(dir.path(), &sample_pairs());
    let manifest = dir.path().join(MANIFEST_FILE);
    std::fs::write(&manifest, b"{ not json").expect("write");
    assert!(matches!(Dataset::open(dir.path()), Err(DatasetError::Manifest { .. })));
    std::fs::write(&manifest, br#"{"format":"part-induction-dataset","format_version":99}"#)
        .expect("write");
    let err = Dataset::open(dir.path()).expect_err("unknown version");
    assert!(err.to_string().contains("manifest"), "{err}");
}

#[test]
fn truncated_files_give_errors_never_panics() {
    let dir = tempfile::tempdir().expect("tempdir");
    write_dataset(dir.path(), &sample_pairs());
    let path = dir.path().join(PAIRS_FILE);
    let full = std::fs::read(&path).expect("read");
    for cut in (0..full.len()).step_by(61).chain([full.len() - 1]) {
        std::fs::write(&path, &full[..cut]).expect("write");
        let result = read_all(dir.path());
        assert!(result.is_err(), "a file cut at {cut} of {} bytes read as complete", full.len());
        assert!(Dataset::open(dir.path()).expect("open").verify().is_err());
    }
}

#[test]
fn corrupt_bytes_give_errors_or_the_original_pairs() {
    let dir = tempfile::tempdir().expect("tempdir");
    let pairs = sample_pairs();
    write_dataset(dir.path(), &pairs);
    let path = dir.path().join(PAIRS_FILE);
    let full = std::fs::read(&path).expect("read");
    let mut detected = 0;
    for pos in (0..full.len()).step_by(37) {
        let mut bad = full.clone();
        bad[pos] ^= 0x5a;
        std::fs::write(&path, &bad).expect("write");
        match read_all(dir.path()) {
            Err(_) => detected += 1,
            // A flip in a part the pairs do not depend on (e.g. a summary offset) may pass,
            // but it must never change a pair.
            Ok(read) => assert_eq!(read, pairs, "a flip at byte {pos} changed the pairs"),
        }
        let verify = Dataset::open(dir.path()).expect("open").verify();
        assert!(
            matches!(verify, Err(DatasetError::Checksum { .. })),
            "flip at {pos} passed verify"
        );
    }
    assert!(detected > 0);
}

#[test]
fn version_1_records_still_read_and_unknown_versions_are_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join(PAIRS_FILE);
    let pair = synthetic::hinge_pair("a", 3, 0.2);
    // A version-1 record: no configurations or poses in its provenance.
    let mut old = PairRecord::from_pair(&pair);
    old.schema_version = 1;
    let mut value: ciborium::Value =
        ciborium::from_reader(encode(&old).as_slice()).expect("cbor value");
    if let ciborium::Value::Map(fields) = &mut value {
        for (key, field) in fields.iter_mut() {
            if key.as_text() == Some("provenance") {
                if let ciborium::Value::Map(provenance) = field {
                    provenance.retain(|(k, _)| {
                        !matches!(k.as_text(), Some("joints_p" | "joints_q" | "pose_p" | "pose_q"))
                    });
                    assert_eq!(provenance.len(), 6, "the six version-1 keys are left");
                }
            }
        }
    }
    let mut bytes = Vec::new();
    ciborium::into_writer(&value, &mut bytes).expect("encode");
    write_raw_mcap(&path, "cbor", PAIR_SCHEMA, std::slice::from_ref(&bytes));
    let read = PairReader::open(&path).expect("open").next().expect("an item").expect("read");
    assert_eq!(read, pair);
    assert!(read.provenance().joints_p.is_empty() && read.provenance().pose_p.is_none());
    let mut future = PairRecord::from_pair(&pair);
    future.schema_version = 3;
    write_raw_mcap(&path, "cbor", PAIR_SCHEMA, &[encode(&future)]);
    let err = PairReader::open(&path).expect("open").next().expect("an item").expect_err("v3");
    assert!(err.to_string().contains("schema_version"), "{err}");
}

#[test]
fn wrong_schema_is_reported() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join(PAIRS_FILE);
    let record = encode(&PairRecord::from_pair(&synthetic::hinge_pair("a", 3, 0.2)));
    write_raw_mcap(&path, "json", PAIR_SCHEMA, std::slice::from_ref(&record));
    let err = PairReader::open(&path).expect("open").next().expect("an item").expect_err("schema");
    assert!(matches!(err, DatasetError::Schema { .. }), "{err}");
    write_raw_mcap(&path, "cbor", "someone.Else", std::slice::from_ref(&record));
    let err = PairReader::open(&path).expect("open").next().expect("an item").expect_err("schema");
    assert!(err.to_string().contains("someone.Else"), "{err}");
    write_raw_mcap(&path, "cbor", PAIR_SCHEMA, &[b"\x01\x02garbage".to_vec()]);
    let err = PairReader::open(&path).expect("open").next().expect("an item").expect_err("decode");
    assert!(matches!(err, DatasetError::Decode { message: 0, .. }), "{err}");
}

#[test]
fn invalid_records_name_the_pair_and_the_field() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join(PAIRS_FILE);
    let good = PairRecord::from_pair(&synthetic::hinge_pair("bad-one", 3, 0.2));
    let mut nan_flow = good.clone();
    nan_flow.flow.as_mut().expect("a flow")[0..4].copy_from_slice(&f32::NAN.to_le_bytes());
    let mut short_parts = good.clone();
    short_parts.part_q.pop();
    let mut part_range = good.clone();
    part_range.part_p[2] = 9;
    let mut odd_bytes = good.clone();
    odd_bytes.p.points.pop();
    let mut bad_index = good.clone();
    bad_index.corr_index[0..4].copy_from_slice(&1000i32.to_le_bytes());
    let mut bad_mask = good.clone();
    bad_mask.corr_mask[1] = 0;
    let mut no_flow = good.clone();
    no_flow.flow = None;
    let mut cross_with_flow = good.clone();
    cross_with_flow.kind = pairs::PairKind::Xf2f;
    let cases: [(PairRecord, &str); 8] = [
        (nan_flow, "flow"),
        (no_flow, "flow"),
        (cross_with_flow, "flow"),
        (short_parts, "part_q"),
        (part_range, "part_p"),
        (odd_bytes, "p.points"),
        (bad_index, "corr_index"),
        (bad_mask, "corr_index"),
    ];
    for (record, field) in cases {
        write_raw_mcap(&path, "cbor", PAIR_SCHEMA, &[encode(&record)]);
        let err = PairReader::open(&path).expect("open").next().expect("an item").expect_err(field);
        match &err {
            DatasetError::InvalidPair { source, .. } => {
                let text = source.to_string();
                assert!(text.contains("bad-one") && text.contains(field), "{text}");
                assert!(!matches!(source, PairError::Length { found: 0, .. }));
            }
            other => panic!("expected an invalid pair for {field}, got {other}"),
        }
    }
}

#[test]
fn a_cross_instance_pair_round_trips_without_a_flow() {
    let dir = tempfile::tempdir().expect("tempdir");
    let pair = synthetic::cross_instance(synthetic::hinge_pair("x", 4, 0.6), 1.3);
    let record = PairRecord::from_pair(&pair);
    assert!(record.flow.is_none(), "no flow is written");
    let mut writer = DatasetWriter::create(dir.path(), false).expect("create");
    writer.write(&pair).expect("write");
    writer.finish(origin()).expect("finish");
    let read: Vec<Pair> = pairs::dataset::Dataset::open(dir.path())
        .expect("open")
        .pairs()
        .expect("pairs")
        .collect::<Result<_, _>>()
        .expect("valid pairs");
    assert_eq!(read, vec![pair.clone()]);
    assert_eq!(read[0].input().kind, pairs::PairKind::Xf2f);
    assert!(read[0].truth().flow.is_none());
    assert_eq!(read[0].provenance().seed_q, Some(1));
}

#[test]
fn an_mcap_without_pairs_is_a_schema_error() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join(PAIRS_FILE);
    let file = std::io::BufWriter::new(std::fs::File::create(&path).expect("create"));
    let mut w = mcap::Writer::new(file).expect("writer");
    w.finish().expect("finish");
    drop(w);
    let err = PairReader::open(&path).expect("open").next().expect("an item").expect_err("schema");
    assert!(matches!(err, DatasetError::Schema { .. }), "{err}");
}

/// A hinge pair whose Q is marked as scanned, with stand-in image bytes.
fn scanned_pair(id: &str) -> (Pair, pairs::scan::PairImages) {
    use pairs::math::{Isometry3, Vector3};
    use pairs::scan::{PairImages, ScanImages};
    use pairs::{Intrinsics, Scan, Scans};
    let camera = Isometry3::new(Vector3::new(0.0, 0.0, 2.0), Vector3::y() * 3.0);
    let intrinsics = Intrinsics::with_fov(32, 24, 0.8);
    let scan = Scan::new(intrinsics, &camera, 1e-4, ScanImages::for_pair(id, "q"));
    let pair = synthetic::hinge_pair(id, 4, 0.5)
        .with_scans(Scans { p: None, q: Some(scan) })
        .expect("a valid camera");
    let bytes = |kind: &str| format!("{id} {kind}").into_bytes();
    let images =
        ScanImages { depth: bytes("depth"), labels: bytes("labels"), colour: bytes("colour") };
    (pair, PairImages { p: None, q: Some(images) })
}

#[test]
fn scan_images_are_written_checksummed_and_read_back() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut writer = DatasetWriter::create(dir.path(), false).expect("create");
    let written: Vec<_> = ["a", "b"].map(scanned_pair).into();
    for (pair, images) in &written {
        writer.write_scanned(pair, images).expect("write");
    }
    let manifest = writer.finish(origin()).expect("finish");
    assert!(manifest.files.contains_key("images/a_q_depth.png"));
    assert_eq!(manifest.files.len(), 2 + 2 * 3);
    assert!(!dir.path().join("images.partial").exists());
    let dataset = Dataset::open(dir.path()).expect("open");
    dataset.verify().expect("checksums");
    let read = read_all(dir.path()).expect("pairs");
    for ((pair, images), back) in written.iter().zip(&read) {
        assert_eq!(pair, back, "the scan record survives the round trip");
        assert_eq!(&dataset.read_images(back).expect("images"), images);
    }
    // A changed image fails verification.
    std::fs::write(dir.path().join("images/b_q_labels.png"), b"tampered").expect("write");
    let err = dataset.verify().expect_err("tampered").to_string();
    assert!(err.contains("b_q_labels.png"), "{err}");
    // Overwriting with a dataset of full shapes removes the old images.
    let mut writer = DatasetWriter::create(dir.path(), true).expect("create");
    writer.write(&synthetic::hinge_pair("full", 4, 0.5)).expect("write");
    writer.finish(origin()).expect("finish");
    assert!(!dir.path().join("images").exists());
}

#[test]
fn scanned_pairs_without_their_images_or_with_stray_paths_are_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut writer = DatasetWriter::create(dir.path(), false).expect("create");
    let (pair, images) = scanned_pair("a");
    let err = writer.write(&pair).expect_err("no images").to_string();
    assert!(err.contains("without its images"), "{err}");
    let (other, _) = scanned_pair("../escape");
    let err = writer.write_scanned(&other, &images).expect_err("stray path").to_string();
    assert!(err.contains("not a file name under images/"), "{err}");
    let full = synthetic::hinge_pair("full", 4, 0.5);
    let err = writer.write_scanned(&full, &images).expect_err("no scan").to_string();
    assert!(err.contains("no scan record"), "{err}");
}
