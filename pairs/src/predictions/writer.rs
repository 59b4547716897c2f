//! Streaming writer of prediction files: records go to `<file>.partial` as they come, and
//! [`PredictionWriter::finish`] renames it into place, so a reader never sees half a file
//! under the real name and an existing file stays untouched until the new one is complete.

use std::collections::BTreeMap;
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

use mcap::records::MessageHeader;
use mcap::Writer;

use super::schema::{
    PredictionHeader, PredictionRecord, HEADER_SCHEMA, HEADER_TOPIC, PREDICTIONS_VERSION,
    PREDICTION_ENCODING, PREDICTION_SCHEMA, PREDICTION_TOPIC,
};
use crate::atomic::partial_path;
use crate::error::PredictionsError;
use crate::mcap_files::reproducible_writer;

/// Writes one prediction file, record by record. Dropped before
/// [`finish`](PredictionWriter::finish), it removes its partial file.
pub struct PredictionWriter {
    path: PathBuf,
    partial: PathBuf,
    /// `None` once finished.
    mcap: Option<Writer<BufWriter<File>>>,
    channel: u16,
    count: u64,
}

impl PredictionWriter {
    /// Starts `path` (as `path.partial`) with `header`.
    pub fn create(path: &Path, header: &PredictionHeader) -> Result<Self, PredictionsError> {
        let partial = partial_path(path);
        let file = File::create(&partial).map_err(PredictionsError::io(&partial))?;
        let mut mcap = reproducible_writer(file).map_err(PredictionsError::mcap(&partial))?;
        let meta = |schema: &str| {
            BTreeMap::from([
                ("schema".to_string(), schema.to_string()),
                ("schema_version".to_string(), PREDICTIONS_VERSION.to_string()),
            ])
        };
        let add = |mcap: &mut Writer<_>, topic, schema| {
            mcap.add_channel(0, topic, PREDICTION_ENCODING, &meta(schema))
        };
        let header_channel = add(&mut mcap, HEADER_TOPIC, HEADER_SCHEMA)
            .map_err(PredictionsError::mcap(&partial))?;
        let channel = add(&mut mcap, PREDICTION_TOPIC, PREDICTION_SCHEMA)
            .map_err(PredictionsError::mcap(&partial))?;
        let mut writer = Self { path: path.into(), partial, mcap: Some(mcap), channel, count: 0 };
        writer.message(header_channel, 0, &cbor(header))?;
        Ok(writer)
    }

    fn message(&mut self, channel_id: u16, time: u64, data: &[u8]) -> Result<(), PredictionsError> {
        let header =
            MessageHeader { channel_id, sequence: time as u32, log_time: time, publish_time: time };
        let mcap = self.mcap.as_mut().expect("present until finish or drop");
        mcap.write_to_known_channel(&header, data).map_err(PredictionsError::mcap(&self.partial))
    }

    /// Appends one pair's record.
    pub fn write(&mut self, record: &PredictionRecord) -> Result<(), PredictionsError> {
        self.count += 1;
        self.message(self.channel, self.count, &cbor(record))
    }

    /// Records written so far.
    pub fn len(&self) -> u64 {
        self.count
    }

    /// Whether no record was written yet.
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// Closes the file and renames it into place; returns its path.
    pub fn finish(mut self) -> Result<PathBuf, PredictionsError> {
        let mut mcap = self.mcap.take().expect("present until finish or drop");
        mcap.finish().map_err(PredictionsError::mcap(&self.partial))?;
        let file = mcap.into_inner().into_inner().map_err(|e| {
            PredictionsError::io(&self.partial)(std::io::Error::other(e.to_string()))
        })?;
        file.sync_all().map_err(PredictionsError::io(&self.partial))?;
        drop(file);
        std::fs::rename(&self.partial, &self.path).map_err(PredictionsError::io(&self.path))?;
        Ok(self.path.clone())
    }
}

impl Drop for PredictionWriter {
    fn drop(&mut self) {
        if let Some(mcap) = self.mcap.take() {
            // Unfinished: the partial file is never a prediction file.
            drop(mcap);
            let _ = std::fs::remove_file(&self.partial);
        }
    }
}

fn cbor(value: &impl serde::Serialize) -> Vec<u8> {
    let mut out = Vec::new();
    ciborium::into_writer(value, &mut out).expect("writing CBOR into a Vec cannot fail");
    out
}
