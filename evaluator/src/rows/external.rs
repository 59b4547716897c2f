//! Rows scored from prediction files (docs/FORMAT.md, "Prediction files"): a method written
//! in any language predicts every pair of a dataset into a file, and `evaluator score` puts
//! it on the boards through the very path the built-in rows take ([`crate::running::run::run_entry`]
//! and `pairs::metrics::score_pair`), with `external` in the `flow_source` column.
//!
//! The file is checked before anything is scored: it must be a readable prediction file
//! whose header names the dataset's content hash, with every prediction's id a pair of the
//! dataset and no pair twice; otherwise the whole file is refused with an error naming it
//! (and the pair), and no report changes. A pair without a prediction, or whose record does
//! not make a valid prediction for it, fails with its reason like a built-in method's pair.
//!
//! External rows are remembered in `<reports>/external_rows.json` (row, dataset, file), so
//! they stay on the boards of later runs while their files exist; their cached runs are
//! keyed by the file's sha256.

use std::collections::{BTreeMap, HashMap, HashSet};
use std::io::{BufReader, Read};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use pairs::predictions::{PredictionHeader, PredictionReader, ReadPrediction};
use pairs::{Method, MethodError, PairInput, Prediction};
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};

use crate::datasets::LoadedDataset;
use crate::error::EvalError;
use pairs::atomic::replace_bytes;

/// The file under the reports folder that remembers the external rows scored into it.
pub const EXTERNAL_ROWS_FILE: &str = "external_rows.json";

/// The `flow_source` column of an external row.
pub const EXTERNAL: &str = "external";

/// One external row's prediction file for one dataset.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct ExternalFile {
    /// The prediction file.
    pub path: PathBuf,
    /// Its sha256 (lowercase hex) when it was scored: the key of its cached run.
    pub sha256: String,
    /// The file's contents when they were read with its hash ([`PredictionFile::read`]),
    /// so that scoring it does not read it again; not part of the file's identity.
    #[serde(skip)]
    pub contents: Contents,
}

impl ExternalFile {
    /// The file `file`, read once for both its hash and its predictions.
    pub fn read(file: PredictionFile) -> Self {
        Self {
            path: file.path.clone(),
            sha256: file.sha256.clone(),
            contents: Contents(Some(Arc::new(file))),
        }
    }
}

/// An [`ExternalFile`]'s contents when they were read with its hash. Equal to any other:
/// a file is named by its path and hash.
#[derive(Clone, Default)]
pub struct Contents(Option<Arc<PredictionFile>>);

impl PartialEq for Contents {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl Eq for Contents {}

impl std::fmt::Debug for Contents {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(if self.0.is_some() { "Contents(read)" } else { "Contents(unread)" })
    }
}

/// A prediction file read once, from first byte to last: its header, its records and the
/// sha256 of its bytes.
#[derive(Debug, Clone, PartialEq)]
pub struct PredictionFile {
    /// Where it was read.
    pub path: PathBuf,
    /// Its header.
    pub header: PredictionHeader,
    /// Its records, in file order.
    pub records: Vec<ReadPrediction>,
    /// The sha256 of its bytes (lowercase hex).
    pub sha256: String,
}

impl PredictionFile {
    /// Reads the prediction file `path` once: every record is decoded as the bytes are
    /// hashed. An unreadable file, a bad header or a bad record is an error naming the file.
    pub fn read(path: &Path) -> Result<Self, EvalError> {
        let io = |source| EvalError::Io { path: path.to_path_buf(), source };
        let file = std::fs::File::open(path).map_err(io)?;
        let mut hashing =
            Hashing { inner: BufReader::with_capacity(1 << 16, file), hash: Sha256::new() };
        let (header, records) = {
            let mut reader = PredictionReader::new(path, &mut hashing);
            let header = reader.header()?.clone();
            let records = reader.collect::<Result<Vec<_>, _>>()?;
            (header, records)
        };
        // What the records did not need (the file's index and footer) is hashed too.
        std::io::copy(&mut hashing, &mut std::io::sink()).map_err(io)?;
        let sha256 = hashing.hash.finalize().iter().map(|b| format!("{b:02x}")).collect();
        Ok(Self { path: path.to_path_buf(), header, records, sha256 })
    }
}

/// A reader that hashes what passes through it.
struct Hashing<R> {
    inner: R,
    hash: Sha256,
}

impl<R: Read> Read for Hashing<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.hash.update(&buf[..n]);
        Ok(n)
    }
}

/// An external row: its prediction file per dataset name.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct ExternalFiles {
    /// Dataset name → file.
    pub files: BTreeMap<String, ExternalFile>,
}

impl ExternalFiles {
    /// The fingerprint of the row's run on `dataset`: the file's hash and the scoring code.
    pub fn fingerprint(&self, dataset: &str) -> Option<String> {
        let file = self.files.get(dataset)?;
        Some(format!(
            "external {} pairs {} scoring {} lock {}",
            file.sha256,
            env!("SOURCE_HASH_PAIRS"),
            env!("SOURCE_HASH_SCORING"),
            env!("SOURCE_HASH_LOCK")
        ))
    }

    /// The predictions for `dataset`, read and checked against it.
    pub fn load(&self, name: &str, dataset: &LoadedDataset) -> Result<FilePredictions, EvalError> {
        let file = self.files.get(&dataset.name).ok_or_else(|| EvalError::PredictionsMismatch {
            path: PathBuf::from(EXTERNAL_ROWS_FILE),
            message: format!(
                "row {name} has no prediction file for dataset {} (score one with `evaluator \
                 score --dataset {} --predictions FILE --name {name}`)",
                dataset.name, dataset.name
            ),
        })?;
        match &file.contents.0 {
            Some(contents) => check_predictions(name, contents, dataset),
            None => {
                let contents = PredictionFile::read(&file.path)?;
                if contents.sha256 != file.sha256 {
                    return Err(EvalError::PredictionsMismatch {
                        path: file.path.clone(),
                        message: "the file changed while the evaluation ran; score it again".into(),
                    });
                }
                check_predictions(name, &contents, dataset)
            }
        }
    }
}

/// The external rows remembered in `reports` (row name → files), none when there is no
/// such file; an error when it cannot be read or parsed (so that it is never overwritten
/// with less than it held).
pub fn remembered_rows(reports: &Path) -> Result<BTreeMap<String, ExternalFiles>, EvalError> {
    let path = reports.join(EXTERNAL_ROWS_FILE);
    let text = match std::fs::read_to_string(&path) {
        Ok(text) => text,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(BTreeMap::new()),
        Err(source) => return Err(EvalError::Io { path, source }),
    };
    serde_json::from_str(&text).map_err(|e| EvalError::Csv {
        path,
        message: format!("not a map of external rows ({e}); fix or delete it"),
    })
}

/// Remembers `rows` in `reports`, replacing the file whole.
pub fn remember_rows(
    reports: &Path,
    rows: &BTreeMap<String, ExternalFiles>,
) -> Result<(), EvalError> {
    let path = reports.join(EXTERNAL_ROWS_FILE);
    let json = serde_json::to_string_pretty(rows).expect("a row map serialises");
    Ok(replace_bytes(&path, json.as_bytes())?)
}

/// The sha256 of a file, lowercase hex.
pub fn file_sha256(path: &Path) -> Result<String, EvalError> {
    let io = |source| EvalError::Io { path: path.to_path_buf(), source };
    let mut file = std::fs::File::open(path).map_err(io)?;
    let mut hasher = Sha256::new();
    let mut buf = vec![0u8; 1 << 16];
    loop {
        let n = file.read(&mut buf).map_err(io)?;
        if n == 0 {
            break;
        }
        hasher.update(&buf[..n]);
    }
    Ok(hasher.finalize().iter().map(|b| format!("{b:02x}")).collect())
}

/// The dataset's content hash as a prediction file names it: the sha256 of its `pairs.mcap`
/// (`sets.mcap` for a set dataset), without the `:first<N>` of a limited load.
pub fn dataset_hash(dataset: &LoadedDataset) -> &str {
    dataset.content_hash.split(':').next().unwrap_or_default()
}

/// One dataset's predictions from a file, served by pair id as a [`Method`].
pub struct FilePredictions {
    name: String,
    path: PathBuf,
    predictions: HashMap<String, Result<Prediction, String>>,
}

impl FilePredictions {
    /// Pairs with a record in the file.
    pub fn len(&self) -> usize {
        self.predictions.len()
    }

    /// Whether the file holds no record.
    pub fn is_empty(&self) -> bool {
        self.predictions.is_empty()
    }
}

impl Method for FilePredictions {
    fn name(&self) -> &str {
        &self.name
    }

    fn predict(&self, input: &PairInput) -> Result<Prediction, MethodError> {
        match self.predictions.get(&input.id) {
            Some(Ok(prediction)) => Ok(prediction.clone()),
            Some(Err(reason)) => Err(MethodError::new(&self.name, &input.id, reason.clone())),
            None => Err(MethodError::new(
                &self.name,
                &input.id,
                format!("no prediction for this pair in {}", self.path.display()),
            )),
        }
    }
}

/// Row `name`'s predictions for `dataset` from the prediction file `file`: the header must
/// name the dataset's content hash and every record a pair of the dataset, once.
pub fn check_predictions(
    name: &str,
    file: &PredictionFile,
    dataset: &LoadedDataset,
) -> Result<FilePredictions, EvalError> {
    let path = file.path.as_path();
    let mismatch = |message: String| EvalError::PredictionsMismatch { path: path.into(), message };
    let expected = dataset_hash(dataset);
    if file.header.dataset != expected {
        return Err(mismatch(format!(
            "made for the dataset with content hash {:?}, not for {} ({expected}); a prediction \
             file names the sha256 of its dataset's pairs.mcap from manifest.json",
            file.header.dataset, dataset.name
        )));
    }
    let ids: HashSet<&str> = dataset.pairs.iter().map(|p| p.id()).collect();
    let mut predictions = HashMap::new();
    let limited = dataset.content_hash.contains(':');
    for read in &file.records {
        if !ids.contains(read.id.as_str()) {
            // A limited load (`--limit`) holds only the first pairs of the dataset, whose
            // content hash the header matched: a record of a later pair is skipped unchecked.
            if limited {
                continue;
            }
            return Err(mismatch(format!(
                "pair {} is not a pair of dataset {}",
                read.id, dataset.name
            )));
        }
        predictions.insert(read.id.clone(), read.prediction.clone());
    }
    Ok(FilePredictions { name: name.into(), path: path.into(), predictions })
}

#[cfg(test)]
mod tests {
    use super::*;
    use pairs::predictions::{PredictionRecord, PredictionWriter};
    use pairs::synthetic::hinge_pair;

    #[test]
    fn one_read_gives_the_records_and_the_hash_of_every_byte() {
        let dir = tempfile::tempdir().expect("a temporary folder");
        let path = dir.path().join("p.mcap");
        let header = PredictionHeader::new("m", "f", "abc");
        let mut writer = PredictionWriter::create(&path, &header).expect("created");
        let pairs: Vec<_> = (0..3).map(|k| hinge_pair(&format!("h{k}"), 8, 0.5)).collect();
        for pair in &pairs {
            let truth = pair.truth();
            let prediction = Prediction {
                flow: truth.flow.clone(),
                segments_p: truth.part_p.iter().map(|&p| u32::from(p)).collect(),
                ..Prediction::default()
            };
            writer.write(&PredictionRecord::from_prediction(pair.id(), &prediction)).expect("w");
        }
        writer.write(&PredictionRecord::failure("h9", "it failed")).expect("written");
        writer.finish().expect("finished");
        let file = PredictionFile::read(&path).expect("read");
        assert_eq!(file.sha256, file_sha256(&path).expect("hashed"));
        assert_eq!(file.header.method, "m");
        let ids: Vec<&str> = file.records.iter().map(|r| r.id.as_str()).collect();
        assert_eq!(ids, ["h0", "h1", "h2", "h9"]);
        assert_eq!(file.records[3].prediction, Err("the method failed: it failed".to_owned()));
        let flow = file.records[1].prediction.as_ref().expect("a prediction").flow.as_ref();
        assert_eq!(flow, pairs[1].truth().flow.as_ref());
        // A truncated file is refused whole, naming it.
        let bytes = std::fs::read(&path).expect("read");
        std::fs::write(&path, &bytes[..bytes.len() / 2]).expect("written");
        let err = PredictionFile::read(&path).expect_err("truncated").to_string();
        assert!(err.contains("p.mcap"), "{err}");
    }
}
