//! Streaming dataset reader: pairs come one at a time from a forward pass over `pairs.mcap`,
//! so a dataset of any size is read in bounded memory.

use std::fs::File;
use std::io::{BufReader, Read};
use std::path::{Path, PathBuf};

use mcap::records::Record;

use super::manifest::Manifest;
use super::records::{RecordStream, StreamError};
use super::schema::{
    decode_record, OLDEST_SCHEMA_VERSION, PAIR_ENCODING, PAIR_SCHEMA, PAIR_TOPIC, SCHEMA_VERSION,
};
use super::writer::PAIRS_FILE;
use crate::error::DatasetError;
use crate::pair::Pair;
use crate::scan::{PairImages, Scan, ScanImages};

/// A dataset folder opened for reading: its manifest and a way to stream its pairs.
#[derive(Debug, Clone)]
pub struct Dataset {
    dir: PathBuf,
    manifest: Manifest,
}

impl Dataset {
    /// Opens a dataset folder; fails if it has no valid `manifest.json`.
    pub fn open(dir: impl AsRef<Path>) -> Result<Self, DatasetError> {
        let dir = dir.as_ref();
        Ok(Self { dir: dir.into(), manifest: Manifest::read(dir)? })
    }

    /// The dataset's manifest.
    pub fn manifest(&self) -> &Manifest {
        &self.manifest
    }

    /// The dataset folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Checks every file against the sizes and checksums of the manifest.
    pub fn verify(&self) -> Result<(), DatasetError> {
        self.manifest.verify(&self.dir)
    }

    /// The PNG bytes of a pair's scan images, read from the dataset folder (empty for
    /// full shapes).
    pub fn read_images(&self, pair: &Pair) -> Result<PairImages, DatasetError> {
        let read = |scan: &Option<Scan>| -> Result<Option<ScanImages<Vec<u8>>>, DatasetError> {
            let Some(scan) = scan else { return Ok(None) };
            let file = |rel: &String| {
                let path = self.dir.join(rel);
                std::fs::read(&path).map_err(DatasetError::io(&path))
            };
            Ok(Some(ScanImages {
                depth: file(&scan.images.depth)?,
                labels: file(&scan.images.labels)?,
                colour: file(&scan.images.colour)?,
            }))
        };
        Ok(PairImages { p: read(&pair.scans().p)?, q: read(&pair.scans().q)? })
    }

    /// Streams the pairs in file order; the stream ends with an error if the file holds fewer
    /// pairs than the manifest announces.
    pub fn pairs(&self) -> Result<PairReader<BufReader<File>>, DatasetError> {
        let mut reader = PairReader::open(self.dir.join(PAIRS_FILE))?;
        reader.expected = Some(self.manifest.counts.pairs);
        Ok(reader)
    }
}

/// An iterator over the pairs of one `pairs.mcap` stream, validating each.
pub struct PairReader<R> {
    path: PathBuf,
    records: RecordStream<R>,
    pair_channel: Option<u16>,
    expected: Option<u64>,
    count: u64,
    done: bool,
}

impl PairReader<BufReader<File>> {
    /// Opens a `pairs.mcap` file on its own (no manifest, so no count check).
    pub fn open(path: impl AsRef<Path>) -> Result<Self, DatasetError> {
        let path = path.as_ref();
        let file = File::open(path).map_err(DatasetError::io(path))?;
        Ok(Self::new(path, BufReader::with_capacity(1 << 16, file)))
    }
}

impl<R: Read> PairReader<R> {
    /// Reads pairs from any byte stream; `path` names it in errors.
    pub fn new(path: impl Into<PathBuf>, source: R) -> Self {
        Self {
            path: path.into(),
            records: RecordStream::new(source),
            pair_channel: None,
            expected: None,
            count: 0,
            done: false,
        }
    }

    /// The next pair, `Ok(None)` at a clean end of the stream.
    fn next_pair(&mut self) -> Result<Option<Pair>, DatasetError> {
        let path = self.path.as_path();
        while let Some(record) = self.records.next_record().map_err(|e| stream_error(path, e))? {
            match record {
                Record::Channel(channel) if channel.topic == PAIR_TOPIC => {
                    check_channel(path, &channel)?;
                    self.pair_channel = Some(channel.id);
                }
                Record::Message { header, data }
                    if Some(header.channel_id) == self.pair_channel =>
                {
                    let message = self.count;
                    let record = decode_record(&data).map_err(|reason| DatasetError::Decode {
                        path: path.into(),
                        message,
                        reason,
                    })?;
                    let pair = record.into_pair().map_err(|source| DatasetError::InvalidPair {
                        path: path.into(),
                        source,
                    })?;
                    self.count += 1;
                    return Ok(Some(pair));
                }
                _ => {}
            }
        }
        if self.pair_channel.is_none() {
            let reason = format!("no {PAIR_TOPIC} channel");
            return Err(DatasetError::Schema { path: path.into(), reason });
        }
        match self.expected {
            Some(expected) if expected != self.count => {
                Err(DatasetError::Truncated { path: path.into(), expected, found: self.count })
            }
            _ => Ok(None),
        }
    }
}

fn stream_error(path: &Path, error: StreamError) -> DatasetError {
    match error {
        StreamError::Io(source) => DatasetError::Io { path: path.into(), source },
        StreamError::Mcap(source) => DatasetError::Mcap { path: path.into(), source },
        StreamError::CorruptChannel => {
            DatasetError::Schema { path: path.into(), reason: StreamError::CORRUPT_CHANNEL.into() }
        }
    }
}

fn check_channel(path: &Path, channel: &mcap::records::Channel) -> Result<(), DatasetError> {
    let schema = channel.metadata.get("schema").map(String::as_str);
    let version = channel.metadata.get("schema_version").map(String::as_str);
    let known = version
        .and_then(|v| v.parse::<u32>().ok())
        .is_some_and(|v| (OLDEST_SCHEMA_VERSION..=SCHEMA_VERSION).contains(&v));
    if channel.message_encoding != PAIR_ENCODING || schema != Some(PAIR_SCHEMA) || !known {
        let reason = format!(
            "{PAIR_TOPIC} has encoding {:?}, schema {schema:?} version {version:?} \
             (expected {PAIR_ENCODING:?}, {PAIR_SCHEMA:?} version \
             {OLDEST_SCHEMA_VERSION} to {SCHEMA_VERSION})",
            channel.message_encoding
        );
        return Err(DatasetError::Schema { path: path.into(), reason });
    }
    Ok(())
}

impl<R: Read> Iterator for PairReader<R> {
    type Item = Result<Pair, DatasetError>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.done {
            return None;
        }
        let result = self.next_pair();
        if !matches!(result, Ok(Some(_))) {
            self.done = true;
        }
        result.transpose()
    }
}
