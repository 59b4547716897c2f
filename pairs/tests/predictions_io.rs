//! Prediction files: every field round-trips bit for bit; a broken file (wrong schema,
//! missing or late header, truncated, not CBOR, no id, a pair twice) is an error naming the
//! file; a record that decodes but is not a valid prediction fails its pair only.

use std::collections::BTreeMap;
use std::path::Path;

use mcap::records::MessageHeader;
use mcap::WriteOptions;
use pairs::joint_estimate::JointEstimate;
use pairs::math::{Point3, Vector3};
use pairs::predictions::{
    read_predictions, PredictionHeader, PredictionReader, PredictionRecord, PredictionWriter,
};
use pairs::{synthetic, JointKind, Prediction, PredictionsError, Similarity};

fn header() -> PredictionHeader {
    PredictionHeader::new("mine", "0.1", &"ab".repeat(32))
}

/// A prediction with every field set, from a hinge pair's truth.
fn full_prediction() -> (String, Prediction) {
    let pair = synthetic::hinge_pair("h-0", 6, 0.4);
    let t = pair.truth();
    let n = pair.input().p.len();
    let mut turned = t.motions[1];
    turned.scale = 0.9;
    let prediction = Prediction {
        flow: t.flow.clone(),
        // Segment ids swapped against the part ids.
        segments_p: t.part_p.iter().map(|&k| 1 - u32::from(k)).collect(),
        segments_q: t.part_q.iter().map(|&k| 1 - u32::from(k)).collect(),
        motions: vec![turned, t.motions[0]],
        corr_mask: Some((0..n).map(|i| i as f32 / n as f32).collect()),
        segment_probs: Some((0..n).map(|i| vec![0.25, 0.75 - i as f32 * 1e-3, 1e-7]).collect()),
        joints: Some(vec![
            Some(JointEstimate {
                kind: JointKind::Revolute,
                axis: Vector3::new(0.0, 0.6, 0.8),
                pivot: Point3::new(0.1, -0.2, 0.3),
                value: 0.4,
            }),
            None,
        ]),
    };
    (pair.id().to_owned(), prediction)
}

#[test]
fn an_unfinished_file_leaves_nothing_behind() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("p.mcap");
    let mut writer = PredictionWriter::create(&path, &header()).expect("create");
    writer.write(&PredictionRecord::failure("f", "x")).expect("write");
    drop(writer);
    let left: Vec<_> = std::fs::read_dir(dir.path()).expect("readable").collect();
    assert!(left.is_empty(), "{left:?}");
}

#[test]
fn every_field_round_trips_exactly() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("p.mcap");
    let (id, prediction) = full_prediction();
    let minimal = Prediction { segments_p: vec![3, 1, 2], ..Prediction::default() };
    let mut writer = PredictionWriter::create(&path, &header()).expect("create");
    assert!(!path.exists(), "the file appears only when finished");
    writer.write(&PredictionRecord::from_prediction(&id, &prediction)).expect("write");
    writer.write(&PredictionRecord::from_prediction("m", &minimal)).expect("write");
    writer.write(&PredictionRecord::failure("f", "no memory")).expect("write");
    assert_eq!(writer.len(), 3);
    writer.finish().expect("finish");
    let (read_header, records) = read_predictions(&path).expect("reads");
    assert_eq!(read_header, header());
    assert_eq!(records[0], (id, Ok(prediction)));
    assert_eq!(records[1], ("m".to_owned(), Ok(minimal)));
    assert_eq!(records[2], ("f".to_owned(), Err("the method failed: no memory".to_owned())));
}

/// A file written with raw MCAP: channels `(topic, schema, version)`, then messages
/// `(channel index, CBOR bytes)`.
fn raw_file(path: &Path, channels: &[(&str, &str, &str)], messages: &[(usize, Vec<u8>)]) {
    let file = std::io::BufWriter::new(std::fs::File::create(path).expect("create"));
    let mut mcap = WriteOptions::new().profile("").create(file).expect("mcap");
    let ids: Vec<u16> = channels
        .iter()
        .map(|(topic, schema, version)| {
            let meta = BTreeMap::from([
                ("schema".to_string(), schema.to_string()),
                ("schema_version".to_string(), version.to_string()),
            ]);
            mcap.add_channel(0, topic, "cbor", &meta).expect("channel")
        })
        .collect();
    for (i, (channel, data)) in messages.iter().enumerate() {
        let h = MessageHeader {
            channel_id: ids[*channel],
            sequence: i as u32,
            log_time: i as u64,
            publish_time: i as u64,
        };
        mcap.write_to_known_channel(&h, data).expect("message");
    }
    mcap.finish().expect("finish");
}

fn cbor(value: &impl serde::Serialize) -> Vec<u8> {
    let mut out = Vec::new();
    ciborium::into_writer(value, &mut out).expect("cbor");
    out
}

const HEADER: (&str, &str, &str) = ("/header", "part_induction.PredictionHeader", "1");
const PREDICTION: (&str, &str, &str) = ("/prediction", "part_induction.Prediction", "1");

fn read_all(path: &Path) -> Result<usize, PredictionsError> {
    let mut reader = PredictionReader::open(path)?;
    reader.header()?;
    reader.try_fold(0, |n, r| r.map(|_| n + 1))
}

#[test]
fn broken_files_are_errors_that_name_the_file() {
    let dir = tempfile::tempdir().expect("tempdir");
    let ok = cbor(&PredictionRecord::from_prediction(
        "a",
        &Prediction { segments_p: vec![0], ..Default::default() },
    ));
    let other_format = PredictionHeader { format: "csv".into(), ..header() };
    let no_id = cbor(&BTreeMap::from([("segments_p", 1)]));
    type Case = (
        &'static str,
        Vec<(&'static str, &'static str, &'static str)>,
        Vec<(usize, Vec<u8>)>,
        &'static str,
    );
    let cases: Vec<Case> = vec![
        (
            "schema",
            vec![HEADER, ("/prediction", "part_induction.Pair", "1")],
            vec![(0, cbor(&header()))],
            "schema Some(\"part_induction.Pair\")",
        ),
        (
            "version",
            vec![HEADER, ("/prediction", "part_induction.Prediction", "2")],
            vec![(0, cbor(&header()))],
            "version Some(\"2\")",
        ),
        ("no-header", vec![HEADER, PREDICTION], vec![], "no /header record"),
        (
            "late-header",
            vec![HEADER, PREDICTION],
            vec![(1, ok.clone()), (0, cbor(&header()))],
            "comes before the /header record",
        ),
        (
            "two-headers",
            vec![HEADER, PREDICTION],
            vec![(0, cbor(&header())), (0, cbor(&header()))],
            "a second /header record",
        ),
        (
            "format",
            vec![HEADER, PREDICTION],
            vec![(0, cbor(&other_format))],
            "the header names format \"csv\"",
        ),
        (
            "not-cbor",
            vec![HEADER, PREDICTION],
            vec![(0, cbor(&header())), (1, vec![0xff, 0x00])],
            "/prediction message 0: cannot decode",
        ),
        (
            "no-id",
            vec![HEADER, PREDICTION],
            vec![(0, cbor(&header())), (1, no_id)],
            "not a map with a text `id`",
        ),
        (
            "twice",
            vec![HEADER, PREDICTION],
            vec![(0, cbor(&header())), (1, ok.clone()), (1, ok.clone())],
            "pair a has two predictions",
        ),
    ];
    for (name, channels, messages, expected) in cases {
        let path = dir.path().join(format!("{name}.mcap"));
        raw_file(&path, &channels, &messages);
        let err = read_all(&path).expect_err(name).to_string();
        assert!(err.contains(expected) && err.contains(&*path.to_string_lossy()), "{name}: {err}");
    }
    // Truncated anywhere after the magic: an error, never a panic or a short success.
    let path = dir.path().join("good.mcap");
    let mut writer = PredictionWriter::create(&path, &header()).expect("create");
    let (id, prediction) = full_prediction();
    for i in 0..20 {
        writer
            .write(&PredictionRecord::from_prediction(&format!("{id}-{i}"), &prediction))
            .expect("write");
    }
    writer.finish().expect("finish");
    let bytes = std::fs::read(&path).expect("read");
    assert_eq!(read_all(&path).expect("the whole file reads"), 20);
    let cut = dir.path().join("cut.mcap");
    for len in (9..bytes.len()).step_by(97) {
        std::fs::write(&cut, &bytes[..len]).expect("write");
        assert!(read_all(&cut).is_err(), "{len} of {} bytes read without error", bytes.len());
    }
}

#[test]
fn a_record_that_is_not_a_valid_prediction_fails_its_pair_only() {
    let (_, good) = full_prediction();
    let record = |change: fn(&mut PredictionRecord)| {
        let mut r = PredictionRecord::from_prediction("x", &good);
        change(&mut r);
        r.into_prediction().expect_err("invalid")
    };
    type Breakage = fn(&mut PredictionRecord);
    let cases: [(Breakage, &str); 12] = [
        (
            |r| {
                let motions = r.motions.as_mut().expect("set");
                motions.push(motions[0].clone());
            },
            "motions has 3 entries, expected 2",
        ),
        (|r| r.joints.as_mut().expect("set").truncate(1), "joints has 1 entries, expected 2"),
        (
            |r| r.corr_mask.as_mut().expect("set")[0..4].copy_from_slice(&1.5f32.to_le_bytes()),
            "corr_mask[0] is not in [0, 1]",
        ),
        (
            |r| {
                r.segment_probs.as_mut().expect("set").values[4..8]
                    .copy_from_slice(&f32::NAN.to_le_bytes())
            },
            "segment_probs value 1 is not finite",
        ),
        (|r| r.segments_p = None, "no segments_p"),
        (|r| r.segments_p.as_mut().expect("set").pop().map(drop).unwrap_or(()), "segments_p has"),
        (|r| r.flow.as_mut().expect("set").truncate(8), "flow has 2 floats, not a multiple of 3"),
        (
            |r| r.motions.as_mut().expect("set")[1].rotation[0] = 2.0,
            "motions[1].rotation is not a rotation",
        ),
        (|r| r.motions.as_mut().expect("set")[0].scale = -1.0, "motions[0].scale is -1"),
        (
            |r| r.motions.as_mut().expect("set")[0].translation[2] = f32::NAN,
            "motions[0] is not finite",
        ),
        (
            |r| r.joints.as_mut().expect("set")[0].as_mut().expect("set").kind = "ball".into(),
            "joints[0].kind is \"ball\"",
        ),
        (|r| r.segment_probs.as_mut().expect("set").columns = 5, "not a multiple of 5 columns"),
    ];
    for (change, expected) in cases {
        let err = record(change);
        assert!(err.contains(expected), "{err:?} should say {expected:?}");
    }
    // A reflection is not a rotation either.
    let mut mirrored = good.clone();
    mirrored.motions[0] =
        Similarity { rotation: -pairs::math::Matrix3::identity(), ..Similarity::identity() };
    let err =
        PredictionRecord::from_prediction("x", &mirrored).into_prediction().expect_err("det -1");
    assert!(err.contains("not a rotation"), "{err}");
}
