//! The datasets the evaluator scores: their names, generator configs and folders, generation
//! of missing ones through the generator library, loading, and a content hash that tells a
//! changed dataset from the one a cached run was made on.

use std::path::{Path, PathBuf};

use generator::config::GeneratorConfig;
use generator::generate::generate_dataset;
use pairs::dataset::{Dataset, PAIRS_FILE};
use pairs::{Pair, PairKind};

use crate::error::EvalError;

/// A dataset the evaluator knows by name.
#[derive(Debug, Clone)]
pub struct DatasetSpec {
    /// Leaderboard name (`sf2f`).
    pub name: String,
    /// The generator config that makes it when it is missing.
    pub config: GeneratorConfig,
}

impl DatasetSpec {
    /// Its folder under `root` (`datasets/<name>`).
    pub fn dir(&self, root: &Path) -> PathBuf {
        root.join(&self.name)
    }
}

/// The default datasets: the paper's three synthetic test sets (SF2F, SF2P, SP2P) on the
/// generator's defaults, named by their kind.
pub fn default_datasets() -> Vec<DatasetSpec> {
    [PairKind::Sf2f, PairKind::Sf2p, PairKind::Sp2p]
        .into_iter()
        .map(|kind| DatasetSpec {
            name: kind.as_str().to_lowercase(),
            config: GeneratorConfig::of_kind(kind),
        })
        .collect()
}

/// A loaded dataset: its pairs in file order and the hash of its pair file.
#[derive(Debug)]
pub struct LoadedDataset {
    /// Leaderboard name.
    pub name: String,
    /// The pairs (the first `limit` of the file when a limit was given).
    pub pairs: Vec<Pair>,
    /// sha256 of `pairs.mcap` as the manifest records it, plus the limit: a cached run made on
    /// other data does not match.
    pub content_hash: String,
}

/// Generates `spec` into `root` unless it already holds a dataset; `progress(done, total)`
/// follows the pairs written. Returns whether it generated.
pub fn ensure_dataset(
    spec: &DatasetSpec,
    root: &Path,
    progress: impl FnMut(u64, u64),
) -> Result<bool, EvalError> {
    let dir = spec.dir(root);
    if dir.join(pairs::dataset::MANIFEST_FILE).exists() {
        return Ok(false);
    }
    let total = spec.config.total_pairs();
    let mut progress = progress;
    generate_dataset(&spec.config, &dir, false, None, |n| progress(n, total))
        .map_err(|e| EvalError::Generate { name: spec.name.clone(), source: Box::new(e) })?;
    Ok(true)
}

/// Loads the dataset `name` from `dir` (verifying its checksums), keeping the first `limit`
/// pairs when a limit is given.
pub fn load_dataset(
    name: &str,
    dir: &Path,
    limit: Option<usize>,
) -> Result<LoadedDataset, EvalError> {
    let err = |source| EvalError::Dataset { name: name.to_owned(), source };
    let dataset = Dataset::open(dir).map_err(err)?;
    dataset.verify().map_err(err)?;
    let hash =
        dataset.manifest().files.get(PAIRS_FILE).map(|f| f.sha256.clone()).unwrap_or_default();
    let pairs: Vec<Pair> = dataset
        .pairs()
        .map_err(err)?
        .take(limit.unwrap_or(usize::MAX))
        .collect::<Result<_, _>>()
        .map_err(err)?;
    let content_hash = match limit {
        Some(l) => format!("{hash}:first{l}"),
        None => hash,
    };
    Ok(LoadedDataset { name: name.to_owned(), pairs, content_hash })
}
