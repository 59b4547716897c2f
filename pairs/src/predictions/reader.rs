//! Streaming reader of prediction files: the header first, then one pair's prediction at a
//! time, so a file of any size is read in bounded memory.

use std::collections::HashSet;
use std::fs::File;
use std::io::{BufReader, Read};
use std::path::{Path, PathBuf};

use mcap::records::Record;

use super::schema::{
    PredictionHeader, PredictionRecord, HEADER_SCHEMA, HEADER_TOPIC, PREDICTIONS_FORMAT,
    PREDICTIONS_VERSION, PREDICTION_ENCODING, PREDICTION_SCHEMA, PREDICTION_TOPIC,
};
use crate::dataset::records::{RecordStream, StreamError};
use crate::error::PredictionsError;
use crate::method::Prediction;

/// One pair's entry of a prediction file.
#[derive(Debug, Clone, PartialEq)]
pub struct ReadPrediction {
    /// The pair's id.
    pub id: String,
    /// The prediction, or why the record holds none (the method's own error, or a field
    /// that does not decode).
    pub prediction: Result<Prediction, String>,
}

/// An iterator over the predictions of one file, after its header.
pub struct PredictionReader<R> {
    path: PathBuf,
    records: RecordStream<R>,
    header_channel: Option<u16>,
    prediction_channel: Option<u16>,
    header: Option<PredictionHeader>,
    seen: HashSet<String>,
    count: u64,
    done: bool,
}

impl PredictionReader<BufReader<File>> {
    /// Opens a prediction file and reads its header.
    pub fn open(path: impl AsRef<Path>) -> Result<Self, PredictionsError> {
        let path = path.as_ref();
        let file = File::open(path).map_err(PredictionsError::io(path))?;
        let mut reader = Self::new(path, BufReader::with_capacity(1 << 16, file));
        reader.header()?;
        Ok(reader)
    }
}

/// What the next record of the file is.
enum Next {
    Header(PredictionHeader),
    Prediction(ReadPrediction),
}

impl<R: Read> PredictionReader<R> {
    /// Reads predictions from any byte stream; `path` names it in errors. The header is read
    /// by the first call to [`header`](Self::header) or to the iterator.
    pub fn new(path: impl Into<PathBuf>, source: R) -> Self {
        Self {
            path: path.into(),
            records: RecordStream::new(source),
            header_channel: None,
            prediction_channel: None,
            header: None,
            seen: HashSet::new(),
            count: 0,
            done: false,
        }
    }

    /// The file's header; an error if the file does not start with a valid one.
    pub fn header(&mut self) -> Result<&PredictionHeader, PredictionsError> {
        if self.header.is_none() {
            match self.next_record()? {
                Some(Next::Header(header)) => self.header = Some(header),
                Some(Next::Prediction(_)) => {
                    return Err(self.schema(format!(
                        "a {PREDICTION_TOPIC} record comes before the {HEADER_TOPIC} record"
                    )));
                }
                None => return Err(self.schema(format!("no {HEADER_TOPIC} record"))),
            }
        }
        Ok(self.header.as_ref().expect("read above"))
    }

    fn schema(&self, reason: String) -> PredictionsError {
        PredictionsError::Schema { path: self.path.clone(), reason }
    }

    /// The next header or prediction record, `Ok(None)` at a clean end of the file.
    fn next_record(&mut self) -> Result<Option<Next>, PredictionsError> {
        let path = self.path.clone();
        let path = path.as_path();
        while let Some(record) = self.records.next_record().map_err(|e| stream_error(path, e))? {
            match record {
                Record::Channel(channel) if channel.topic == HEADER_TOPIC => {
                    check_channel(path, &channel, HEADER_SCHEMA)?;
                    self.header_channel = Some(channel.id);
                }
                Record::Channel(channel) if channel.topic == PREDICTION_TOPIC => {
                    check_channel(path, &channel, PREDICTION_SCHEMA)?;
                    self.prediction_channel = Some(channel.id);
                }
                Record::Message { header, data }
                    if Some(header.channel_id) == self.header_channel =>
                {
                    if self.header.is_some() {
                        return Err(self.schema(format!("a second {HEADER_TOPIC} record")));
                    }
                    return Ok(Some(Next::Header(decode_header(path, &data)?)));
                }
                Record::Message { header, data }
                    if Some(header.channel_id) == self.prediction_channel =>
                {
                    let message = self.count;
                    self.count += 1;
                    return Ok(Some(Next::Prediction(decode_prediction(path, message, &data)?)));
                }
                _ => {}
            }
        }
        Ok(None)
    }

    /// The next prediction, `Ok(None)` at a clean end of the file.
    fn next_prediction(&mut self) -> Result<Option<ReadPrediction>, PredictionsError> {
        self.header()?;
        match self.next_record()? {
            Some(Next::Prediction(read)) => {
                if !self.seen.insert(read.id.clone()) {
                    let (path, id) = (self.path.clone(), read.id);
                    return Err(PredictionsError::Duplicate { path, id });
                }
                Ok(Some(read))
            }
            Some(Next::Header(_)) => Err(self.schema(format!("a second {HEADER_TOPIC} record"))),
            None => Ok(None),
        }
    }
}

fn stream_error(path: &Path, error: StreamError) -> PredictionsError {
    match error {
        StreamError::Io(source) => PredictionsError::Io { path: path.into(), source },
        StreamError::Mcap(source) => PredictionsError::Mcap { path: path.into(), source },
        StreamError::CorruptChannel => PredictionsError::Schema {
            path: path.into(),
            reason: StreamError::CORRUPT_CHANNEL.into(),
        },
    }
}

impl<R: Read> Iterator for PredictionReader<R> {
    type Item = Result<ReadPrediction, PredictionsError>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.done {
            return None;
        }
        let result = self.next_prediction();
        if !matches!(result, Ok(Some(_))) {
            self.done = true;
        }
        result.transpose()
    }
}

fn check_channel(
    path: &Path,
    channel: &mcap::records::Channel,
    expected: &str,
) -> Result<(), PredictionsError> {
    let schema = channel.metadata.get("schema").map(String::as_str);
    let version = channel.metadata.get("schema_version").map(String::as_str);
    let expected_version = PREDICTIONS_VERSION.to_string();
    if channel.message_encoding != PREDICTION_ENCODING
        || schema != Some(expected)
        || version != Some(expected_version.as_str())
    {
        let reason = format!(
            "{} has encoding {:?}, schema {schema:?} version {version:?} \
             (expected {PREDICTION_ENCODING:?}, {expected:?} version {PREDICTIONS_VERSION})",
            channel.topic, channel.message_encoding
        );
        return Err(PredictionsError::Schema { path: path.into(), reason });
    }
    Ok(())
}

fn decode_header(path: &Path, data: &[u8]) -> Result<PredictionHeader, PredictionsError> {
    let schema = |reason: String| PredictionsError::Schema { path: path.into(), reason };
    let header: PredictionHeader = ciborium::from_reader(data)
        .map_err(|e| schema(format!("the {HEADER_TOPIC} record does not decode: {e}")))?;
    if header.format != PREDICTIONS_FORMAT || header.format_version != PREDICTIONS_VERSION {
        return Err(schema(format!(
            "the header names format {:?} version {} (expected {PREDICTIONS_FORMAT:?} version \
             {PREDICTIONS_VERSION})",
            header.format, header.format_version
        )));
    }
    Ok(header)
}

/// A prediction record: CBOR with a text `id`, or the file is broken; a record whose other
/// fields do not decode is that pair's failure.
fn decode_prediction(
    path: &Path,
    message: u64,
    data: &[u8],
) -> Result<ReadPrediction, PredictionsError> {
    let decode = |reason: String| PredictionsError::Decode { path: path.into(), message, reason };
    let value: ciborium::Value = ciborium::from_reader(data).map_err(|e| decode(e.to_string()))?;
    let id = value
        .as_map()
        .and_then(|map| map.iter().find(|(k, _)| k.as_text() == Some("id")))
        .and_then(|(_, v)| v.as_text())
        .ok_or_else(|| decode("not a map with a text `id`".into()))?
        .to_owned();
    let prediction = value
        .deserialized::<PredictionRecord>()
        .map_err(|e| format!("the prediction record does not decode: {e}"))
        .and_then(PredictionRecord::into_prediction);
    Ok(ReadPrediction { id, prediction })
}
