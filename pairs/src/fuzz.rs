//! What the fuzz targets in `pairs/fuzz` run on their input, shared with the regression test
//! that replays the inputs they found (`tests/fuzz_regressions.rs`): each reads a byte stream
//! to its end or to its first error, and must never panic.

use crate::dataset::{PairReader, SetReader};
use crate::predictions::PredictionReader;
use crate::renders::{
    parse_predictions, parse_truth, ObjectTruth, RenderRecord, RenderTruth, WorldFrame,
};

/// Reads `data` as a `pairs.mcap` stream; returns the pairs read before the end or the
/// first error.
pub fn read_pairs(data: &[u8]) -> usize {
    PairReader::new("fuzz input", data).map_while(Result::ok).count()
}

/// Reads `data` as a `sets.mcap` stream; returns the sets read before the end or the first
/// error.
pub fn read_sets(data: &[u8]) -> usize {
    SetReader::new("fuzz input", data).map_while(Result::ok).count()
}

/// Reads `data` as a prediction file; returns the records read before the end or the first
/// error (0 when the header is refused).
pub fn read_predictions(data: &[u8]) -> usize {
    let mut reader = PredictionReader::new("fuzz input", data);
    if reader.header().is_err() {
        return 0;
    }
    reader.map_while(Result::ok).count()
}

/// Reads `data` as a render folder's records: `render.json` (any settings) and
/// `ground_truth.json` (with its world frames and joints checked); returns the objects the
/// two list (0 for each that is refused).
pub fn read_render_records(data: &[u8]) -> usize {
    let Ok(text) = std::str::from_utf8(data) else { return 0 };
    let path = std::path::Path::new("fuzz input");
    let record = serde_json::from_str::<RenderRecord<serde_json::Value>>(text)
        .map_or(0, |r| r.objects.len());
    let truth = parse_truth(text, path).map_or(0, |t| t.objects.len());
    record + truth
}

/// Reads `data` as a joints-only prediction file for a render of two objects
/// (`000000_laptop`, `000001_cabinet`); returns the objects it lists (0 when refused).
pub fn read_joint_predictions(data: &[u8]) -> usize {
    let Ok(text) = std::str::from_utf8(data) else { return 0 };
    let object = |object_id: u32, category: &str| ObjectTruth {
        folder: format!("{object_id:06}_{category}"),
        object_id,
        category: category.into(),
        world: WorldFrame::identity(),
        diagonal: 1.0,
        joints: Vec::new(),
    };
    let truth = RenderTruth {
        layout: "native".into(),
        seed: 0,
        objects: vec![object(0, "laptop"), object(1, "cabinet")],
    };
    parse_predictions(text, std::path::Path::new("fuzz input"), &truth)
        .map_or(0, |p| p.objects.len())
}
