//! Typed errors of the shared data model and of the dataset files.

use std::path::{Path, PathBuf};

/// A pair record that breaks an invariant; names the pair and the field.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum PairError {
    /// An array has the wrong number of entries.
    #[error("pair {pair}: field `{field}` has {found} entries, expected {expected}")]
    Length {
        /// Pair id.
        pair: String,
        /// Field name as in the file format.
        field: &'static str,
        /// Expected number of entries.
        expected: usize,
        /// Number found.
        found: usize,
    },
    /// A value is NaN or infinite.
    #[error("pair {pair}: field `{field}` has a non-finite value at entry {index}")]
    NonFinite {
        /// Pair id.
        pair: String,
        /// Field name as in the file format.
        field: &'static str,
        /// Entry (point, part or joint) index.
        index: usize,
    },
    /// A part id is not below the pair's number of parts.
    #[error("pair {pair}: field `{field}` entry {index} holds part {id}, but the pair has {parts} parts")]
    PartOutOfRange {
        /// Pair id.
        pair: String,
        /// Field name as in the file format.
        field: &'static str,
        /// Entry index.
        index: usize,
        /// The offending id.
        id: usize,
        /// Number of parts of the pair.
        parts: usize,
    },
    /// A value contradicts another field or the definitions of DESIGN.md.
    #[error("pair {pair}: field `{field}` entry {index}: {reason}")]
    Inconsistent {
        /// Pair id.
        pair: String,
        /// Field name as in the file format.
        field: &'static str,
        /// Entry index.
        index: usize,
        /// What is wrong.
        reason: String,
    },
}

/// A set record that breaks an invariant, or a pair it cannot give.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SetError {
    /// A field has the wrong shape or an id out of range.
    #[error("set {set}: field `{field}` entry {index}: {reason}")]
    Invalid {
        /// Set id.
        set: String,
        /// Field name as in the file format.
        field: &'static str,
        /// Entry (view, part or joint) index.
        index: usize,
        /// What is wrong.
        reason: String,
    },
    /// A view index past the set's views.
    #[error("set {set}: there is no view {view} (the set has {views} views)")]
    NoView {
        /// Set id.
        set: String,
        /// The index asked for.
        view: usize,
        /// Number of views.
        views: usize,
    },
    /// Two views that make no pair.
    #[error("set {set}: views {i} and {j} make no pair: {reason}")]
    NoPair {
        /// Set id.
        set: String,
        /// View taken as P.
        i: usize,
        /// View taken as Q.
        j: usize,
        /// Why.
        reason: String,
    },
    /// The pair of two views breaks a pair invariant.
    #[error("set {set}, pair of views {i} and {j}: {source}")]
    Pair {
        /// Set id.
        set: String,
        /// View taken as P.
        i: usize,
        /// View taken as Q.
        j: usize,
        /// The broken invariant.
        source: PairError,
    },
}

/// Failure to read or write a dataset folder.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum DatasetError {
    /// An operating-system error on a file.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The MCAP container is malformed, truncated or fails its checksums.
    #[error("{path}: not a readable MCAP file (truncated or corrupt?): {source}")]
    Mcap {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: mcap::McapError,
    },
    /// The folder has no `manifest.json`: it is not a dataset, or its writing never finished.
    #[error("{dir}: no manifest.json (not a dataset, or its generation did not finish)")]
    MissingManifest {
        /// The dataset folder.
        dir: PathBuf,
    },
    /// The manifest cannot be parsed or has an unsupported format version.
    #[error("{path}: invalid manifest: {reason}")]
    Manifest {
        /// The manifest file.
        path: PathBuf,
        /// What is wrong.
        reason: String,
    },
    /// A file's checksum or size differs from the manifest's.
    #[error("{path}: {reason} (the file changed after the manifest was written)")]
    Checksum {
        /// The file.
        path: PathBuf,
        /// Which of size or sha256 differs.
        reason: String,
    },
    /// The MCAP file does not carry the `/pair` channel in the documented schema.
    #[error("{path}: wrong schema: {reason}")]
    Schema {
        /// The file.
        path: PathBuf,
        /// What differs from docs/FORMAT.md.
        reason: String,
    },
    /// A `/pair` message cannot be decoded as the documented CBOR record.
    #[error("{path}: /pair message {message}: cannot decode: {reason}")]
    Decode {
        /// The file.
        path: PathBuf,
        /// Zero-based message number on `/pair`.
        message: u64,
        /// The decoder's complaint.
        reason: String,
    },
    /// A decoded pair breaks an invariant.
    #[error("{path}: {source}")]
    InvalidPair {
        /// The file.
        path: PathBuf,
        /// The broken invariant.
        source: PairError,
    },
    /// A decoded set breaks an invariant.
    #[error("{path}: {source}")]
    InvalidSet {
        /// The file.
        path: PathBuf,
        /// The broken invariant (boxed: a set's error is larger than the others).
        source: Box<SetError>,
    },
    /// The file ended before the number of pairs the manifest announces.
    #[error("{path}: holds {found} pairs but the manifest announces {expected} (truncated?)")]
    Truncated {
        /// The file.
        path: PathBuf,
        /// Pairs announced.
        expected: u64,
        /// Pairs found.
        found: u64,
    },
    /// A scanned side came without its images, or with an image path outside `images/`.
    #[error("pair {pair}: {reason}")]
    Images {
        /// The pair.
        pair: String,
        /// What is wrong.
        reason: String,
    },
    /// The output folder already holds a dataset and overwriting was not asked for.
    #[error("{dir} already holds a dataset; choose another folder or allow overwriting")]
    Exists {
        /// The dataset folder.
        dir: PathBuf,
    },
    /// Writing `index.csv` failed.
    #[error("{path}: {source}")]
    Csv {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: csv::Error,
    },
}

impl From<crate::atomic::FileError> for DatasetError {
    fn from(e: crate::atomic::FileError) -> Self {
        Self::Io { path: e.path, source: e.source }
    }
}

impl DatasetError {
    /// Wraps an I/O error with the file it concerns.
    /// The path is copied only when an error occurs, so success paths stay allocation-free.
    pub(crate) fn io(path: &Path) -> impl FnOnce(std::io::Error) -> Self + '_ {
        move |source| Self::Io { path: path.into(), source }
    }

    /// Wraps an MCAP error with the file it concerns.
    pub(crate) fn mcap(path: &Path) -> impl FnOnce(mcap::McapError) -> Self + '_ {
        move |source| Self::Mcap { path: path.into(), source }
    }
}

/// Failure to read or write a prediction file (docs/FORMAT.md, "Prediction files"). A pair
/// whose record decodes but is not a valid prediction is not one of these: it is that
/// pair's failure ([`crate::predictions::ReadPrediction::prediction`]).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PredictionsError {
    /// An operating-system error on the file.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The MCAP container is malformed, truncated or fails its checksums.
    #[error("{path}: not a readable MCAP file (truncated or corrupt?): {source}")]
    Mcap {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: mcap::McapError,
    },
    /// The header or a channel is not the documented one, or the header is missing or not
    /// first.
    #[error("{path}: not a prediction file of this format: {reason}")]
    Schema {
        /// The file.
        path: PathBuf,
        /// What differs from docs/FORMAT.md.
        reason: String,
    },
    /// A `/prediction` message is not CBOR or has no text `id`.
    #[error("{path}: /prediction message {message}: cannot decode: {reason}")]
    Decode {
        /// The file.
        path: PathBuf,
        /// Zero-based message number on `/prediction`.
        message: u64,
        /// The decoder's complaint.
        reason: String,
    },
    /// Two records for one pair.
    #[error("{path}: pair {id} has two predictions")]
    Duplicate {
        /// The file.
        path: PathBuf,
        /// The pair.
        id: String,
    },
}

impl PredictionsError {
    pub(crate) fn io(path: &Path) -> impl FnOnce(std::io::Error) -> Self + '_ {
        move |source| Self::Io { path: path.into(), source }
    }

    pub(crate) fn mcap(path: &Path) -> impl FnOnce(mcap::McapError) -> Self + '_ {
        move |source| Self::Mcap { path: path.into(), source }
    }
}
