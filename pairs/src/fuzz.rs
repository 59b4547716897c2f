//! What the fuzz targets in `pairs/fuzz` run on their input, shared with the regression test
//! that replays the inputs they found (`tests/fuzz_regressions.rs`): each reads a byte stream
//! to its end or to its first error, and must never panic.

use crate::dataset::{PairReader, SetReader};
use crate::predictions::PredictionReader;

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
