//! Rows scored from prediction files (docs/FORMAT.md, "Prediction files"): a method written
//! in any language predicts every pair of a dataset into a file, and `evaluator score` puts
//! it on the boards through the very path the built-in rows take ([`crate::run::run_entry`]
//! and [`crate::score::score_pair`]), with `external` in the `flow_source` column.
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
use std::io::Read;
use std::path::{Path, PathBuf};

use pairs::predictions::PredictionReader;
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
        load_predictions(name, &file.path, dataset)
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
/// (without the `:first<N>` of a limited load).
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

/// Reads the prediction file `path` for `dataset` as row `name`: the header must name the
/// dataset's content hash and every record a pair of the dataset, once.
pub fn load_predictions(
    name: &str,
    path: &Path,
    dataset: &LoadedDataset,
) -> Result<FilePredictions, EvalError> {
    let mismatch = |message: String| EvalError::PredictionsMismatch { path: path.into(), message };
    let mut reader = PredictionReader::open(path)?;
    let header = reader.header()?;
    let expected = dataset_hash(dataset);
    if header.dataset != expected {
        return Err(mismatch(format!(
            "made for the dataset with content hash {:?}, not for {} ({expected}); a prediction \
             file names the sha256 of its dataset's pairs.mcap from manifest.json",
            header.dataset, dataset.name
        )));
    }
    let ids: HashSet<&str> = dataset.pairs.iter().map(|p| p.id()).collect();
    let mut predictions = HashMap::new();
    let limited = dataset.content_hash.contains(':');
    for read in reader {
        let read = read?;
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
        predictions.insert(read.id, read.prediction);
    }
    Ok(FilePredictions { name: name.into(), path: path.into(), predictions })
}
