//! Prediction files (docs/FORMAT.md, "Prediction files"): one method's [`Prediction`] for
//! every pair of one dataset, in an MCAP file that any language can write, so that a method
//! outside this workspace is scored exactly as a built-in one.
//!
//! A file holds one `/header` record ([`PredictionHeader`]: the method, its version and the
//! content hash of the dataset it was made for), then one `/prediction` record per pair
//! ([`PredictionRecord`]). [`PredictionWriter`] writes one under a temporary name and renames
//! it into place when finished; [`PredictionReader`] streams one back, checking the header,
//! the channels' schemas and that no pair comes twice. A record that decodes but does not
//! make a valid prediction (a length that is not a whole number of elements, a rotation that
//! is not one, an unknown joint kind) is not an error of the file: it is returned as that
//! pair's failure, so that one bad pair does not cost a method its other pairs.
//!
//! ```
//! use pairs::predictions::{PredictionHeader, PredictionReader, PredictionRecord, PredictionWriter};
//! use pairs::{synthetic, Prediction};
//!
//! let dir = tempfile::tempdir()?;
//! let path = dir.path().join("predictions.mcap");
//! let pair = synthetic::hinge_pair("demo", 4, 0.5);
//! let prediction = Prediction { segments_p: vec![0; pair.input().p.len()], ..Default::default() };
//! let mut writer = PredictionWriter::create(&path, &PredictionHeader::new("one-part", "1", "abc"))?;
//! writer.write(&PredictionRecord::from_prediction(pair.id(), &prediction))?;
//! writer.finish()?;
//!
//! let mut reader = PredictionReader::open(&path)?;
//! assert_eq!(reader.header()?.method, "one-part");
//! let read = reader.next().expect("one record")?;
//! assert_eq!((read.id.as_str(), read.prediction.expect("valid")), (pair.id(), prediction));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod reader;
mod schema;
mod writer;

pub use reader::{PredictionReader, ReadPrediction};
pub use schema::{
    JointPredictionRecord, MotionPredictionRecord, PredictionHeader, PredictionRecord,
    SegmentProbsRecord, HEADER_SCHEMA, HEADER_TOPIC, PREDICTIONS_FORMAT, PREDICTIONS_VERSION,
    PREDICTION_ENCODING, PREDICTION_SCHEMA, PREDICTION_TOPIC,
};
pub use writer::PredictionWriter;

use crate::Prediction;

/// Each pair's id and its prediction, or why its record holds none, in file order.
pub type Predictions = Vec<(String, Result<Prediction, String>)>;

/// The file's records read into memory: the header and every pair's prediction (or why it
/// could not be read), in file order. Fails on any error of the file itself.
pub fn read_predictions(
    path: impl AsRef<std::path::Path>,
) -> Result<(PredictionHeader, Predictions), crate::PredictionsError> {
    let mut reader = PredictionReader::open(path)?;
    let header = reader.header()?.clone();
    let records = reader.map(|r| r.map(|r| (r.id, r.prediction))).collect::<Result<_, _>>()?;
    Ok((header, records))
}
