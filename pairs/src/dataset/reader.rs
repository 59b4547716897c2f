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
use super::set_schema::{decode_set_record, SET_SCHEMA, SET_SCHEMA_VERSION, SET_TOPIC};
use super::writer::{PAIRS_FILE, SETS_FILE};
use crate::error::DatasetError;
use crate::pair::Pair;
use crate::scan::{PairImages, Scan, ScanImages};
use crate::set::Set;

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
        Ok(PairImages {
            p: self.scan_images(&pair.scans().p)?,
            q: self.scan_images(&pair.scans().q)?,
        })
    }

    /// The PNG bytes of one scan's images.
    fn scan_images(
        &self,
        scan: &Option<Scan>,
    ) -> Result<Option<ScanImages<Vec<u8>>>, DatasetError> {
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
    }

    /// Streams the pairs in file order; the stream ends with an error if the file holds fewer
    /// pairs than the manifest announces.
    pub fn pairs(&self) -> Result<PairReader<BufReader<File>>, DatasetError> {
        let mut reader = PairReader::open(self.dir.join(PAIRS_FILE))?;
        reader.expected = Some(self.manifest.counts.pairs);
        Ok(reader)
    }

    /// Whether the folder is a set dataset (`sets.mcap`; its manifest counts sets).
    pub fn holds_sets(&self) -> bool {
        self.manifest.counts.sets > 0 || self.manifest.files.contains_key(SETS_FILE)
    }

    /// Streams the sets of a set dataset in file order, as [`pairs`](Self::pairs) streams
    /// pairs.
    pub fn sets(&self) -> Result<SetReader<BufReader<File>>, DatasetError> {
        let mut reader = SetReader::open(self.dir.join(SETS_FILE))?;
        reader.expected = Some(self.manifest.counts.sets);
        Ok(reader)
    }

    /// The PNG bytes of a set's scan images, per view (`None` for a full view).
    pub fn read_set_images(
        &self,
        set: &Set,
    ) -> Result<Vec<Option<ScanImages<Vec<u8>>>>, DatasetError> {
        set.scans().iter().map(|scan| self.scan_images(scan)).collect()
    }
}

/// What a records file holds: `/pair` messages ([`Pairs`]) or `/set` messages ([`Sets`]).
pub trait RecordKind {
    /// The validated record.
    type Item;
    /// Its channel's topic.
    const TOPIC: &'static str;
    /// Its channel's `schema` metadata.
    const SCHEMA: &'static str;
    /// Oldest and newest layout versions read.
    const VERSIONS: (u32, u32);
    /// Decodes and validates one message (`message`: its number on the channel).
    fn decode(path: &Path, message: u64, data: &[u8]) -> Result<Self::Item, DatasetError>;
}

/// The `/pair` records of `pairs.mcap`.
#[derive(Debug, Clone, Copy)]
pub struct Pairs;

/// The `/set` records of `sets.mcap`.
#[derive(Debug, Clone, Copy)]
pub struct Sets;

impl RecordKind for Pairs {
    type Item = Pair;
    const TOPIC: &'static str = PAIR_TOPIC;
    const SCHEMA: &'static str = PAIR_SCHEMA;
    const VERSIONS: (u32, u32) = (OLDEST_SCHEMA_VERSION, SCHEMA_VERSION);

    fn decode(path: &Path, message: u64, data: &[u8]) -> Result<Pair, DatasetError> {
        let record = decode_record(data).map_err(|reason| DatasetError::Decode {
            path: path.into(),
            message,
            reason,
        })?;
        record.into_pair().map_err(|source| DatasetError::InvalidPair { path: path.into(), source })
    }
}

impl RecordKind for Sets {
    type Item = Set;
    const TOPIC: &'static str = SET_TOPIC;
    const SCHEMA: &'static str = SET_SCHEMA;
    const VERSIONS: (u32, u32) = (SET_SCHEMA_VERSION, SET_SCHEMA_VERSION);

    fn decode(path: &Path, message: u64, data: &[u8]) -> Result<Set, DatasetError> {
        let record = decode_set_record(data).map_err(|reason| DatasetError::Decode {
            path: path.into(),
            message,
            reason,
        })?;
        record.into_set().map_err(|source| DatasetError::InvalidSet {
            path: path.into(),
            source: Box::new(source),
        })
    }
}

/// An iterator over the records of one MCAP stream, validating each.
pub struct RecordReader<R, K> {
    path: PathBuf,
    records: RecordStream<R>,
    channel: Option<u16>,
    expected: Option<u64>,
    count: u64,
    done: bool,
    kind: std::marker::PhantomData<K>,
}

/// An iterator over the pairs of one `pairs.mcap` stream, validating each.
pub type PairReader<R> = RecordReader<R, Pairs>;

/// An iterator over the sets of one `sets.mcap` stream, validating each.
pub type SetReader<R> = RecordReader<R, Sets>;

impl<K: RecordKind> RecordReader<BufReader<File>, K> {
    /// Opens a records file on its own (no manifest, so no count check).
    pub fn open(path: impl AsRef<Path>) -> Result<Self, DatasetError> {
        let path = path.as_ref();
        let file = File::open(path).map_err(DatasetError::io(path))?;
        Ok(Self::new(path, BufReader::with_capacity(1 << 16, file)))
    }
}

impl<R: Read, K: RecordKind> RecordReader<R, K> {
    /// Reads records from any byte stream; `path` names it in errors.
    pub fn new(path: impl Into<PathBuf>, source: R) -> Self {
        Self {
            path: path.into(),
            records: RecordStream::new(source),
            channel: None,
            expected: None,
            count: 0,
            done: false,
            kind: std::marker::PhantomData,
        }
    }

    /// The next record, `Ok(None)` at a clean end of the stream.
    fn next_record(&mut self) -> Result<Option<K::Item>, DatasetError> {
        let path = self.path.as_path();
        while let Some(record) = self.records.next_record().map_err(|e| stream_error(path, e))? {
            match record {
                Record::Channel(channel) if channel.topic == K::TOPIC => {
                    check_channel::<K>(path, &channel)?;
                    self.channel = Some(channel.id);
                }
                Record::Message { header, data } if Some(header.channel_id) == self.channel => {
                    let item = K::decode(path, self.count, &data)?;
                    self.count += 1;
                    return Ok(Some(item));
                }
                _ => {}
            }
        }
        if self.channel.is_none() {
            let reason = format!("no {} channel", K::TOPIC);
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

fn check_channel<K: RecordKind>(
    path: &Path,
    channel: &mcap::records::Channel,
) -> Result<(), DatasetError> {
    let schema = channel.metadata.get("schema").map(String::as_str);
    let version = channel.metadata.get("schema_version").map(String::as_str);
    let (oldest, newest) = K::VERSIONS;
    let known =
        version.and_then(|v| v.parse::<u32>().ok()).is_some_and(|v| (oldest..=newest).contains(&v));
    if channel.message_encoding != PAIR_ENCODING || schema != Some(K::SCHEMA) || !known {
        let reason = format!(
            "{} has encoding {:?}, schema {schema:?} version {version:?} \
             (expected {PAIR_ENCODING:?}, {:?} version {oldest} to {newest})",
            K::TOPIC,
            channel.message_encoding,
            K::SCHEMA,
        );
        return Err(DatasetError::Schema { path: path.into(), reason });
    }
    Ok(())
}

impl<R: Read, K: RecordKind> Iterator for RecordReader<R, K> {
    type Item = Result<K::Item, DatasetError>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.done {
            return None;
        }
        let result = self.next_record();
        if !matches!(result, Ok(Some(_))) {
            self.done = true;
        }
        result.transpose()
    }
}
