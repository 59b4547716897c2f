//! `evaluator score` and `evaluator predict` as library calls: a prediction file scored onto
//! the boards as an external row, and any row's predictions written as such a file.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use pairs::predictions::{PredictionHeader, PredictionRecord, PredictionWriter};

use crate::commands::pipeline::{evaluate, Options, Progress, Summary};
use crate::commands::predict::predict_row;
use crate::datasets::{remember_datasets, validation_datasets, DatasetSpec};
use crate::error::EvalError;
use crate::rows::external::{
    dataset_hash, file_sha256, remember_rows, remembered_rows, ExternalFile, ExternalFiles,
    PredictionFile,
};
use crate::rows::registry::{Registry, Runner};

/// Where `score` and `predict` read and write.
#[derive(Debug, Clone)]
pub struct CommandOptions {
    /// Folder holding the dataset folders (`datasets`).
    pub datasets_root: PathBuf,
    /// Folder of the reports (`reports`).
    pub reports: PathBuf,
    /// Pairs per dataset in the segmentation gallery: the number the other rows' cached
    /// runs were made with (`evaluator --gallery-pairs`, 3 by default), or they leave the
    /// boards.
    pub gallery_pairs: usize,
}

/// The dataset named `arg`: one of `specs` by name, or a dataset folder (a user dataset,
/// named by the folder's name unless that is a default's, then by the path's spec).
pub fn resolve_dataset(
    arg: &str,
    specs: &[DatasetSpec],
    datasets_root: &Path,
) -> Result<DatasetSpec, EvalError> {
    if let Some(spec) = specs.iter().find(|s| s.name == arg) {
        return Ok(spec.clone());
    }
    let path = Path::new(arg);
    if path.join(pairs::dataset::MANIFEST_FILE).exists() {
        let canonical = |p: &Path| std::fs::canonicalize(p).ok();
        let known = specs.iter().find(|s| {
            let dir = s.dir(datasets_root);
            dir.exists() && canonical(&dir) == canonical(path)
        });
        if let Some(spec) = known {
            return Ok(spec.clone());
        }
        let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("dataset");
        if specs.iter().any(|s| s.name == name) {
            return Err(EvalError::PredictionsMismatch {
                path: path.into(),
                message: format!(
                    "the folder's name {name} is another dataset's; score it once with \
                     `evaluator --dataset OTHER_NAME={arg}` and then use OTHER_NAME"
                ),
            });
        }
        return Ok(DatasetSpec::user(name, path));
    }
    Err(EvalError::Unknown {
        what: "dataset (a name, or a folder with manifest.json)",
        name: arg.to_owned(),
        known: specs.iter().map(|s| s.name.as_str()).collect::<Vec<_>>().join(", "),
    })
}

/// Adds the external rows remembered in `reports` whose files still exist, so that their
/// cached runs stay on the boards. Each file is hashed again: one that changed since it was
/// scored no longer matches its cached run, and its row leaves the boards until it is scored
/// again (`evaluator --all` runs an external row only when `--methods` names it).
pub fn add_remembered_rows(registry: &mut Registry, reports: &Path) -> Result<(), EvalError> {
    add_rows(registry, remembered_rows(reports)?)
}

/// [`add_remembered_rows`] for the rows `rows`.
fn add_rows(
    registry: &mut Registry,
    rows: BTreeMap<String, ExternalFiles>,
) -> Result<(), EvalError> {
    for (name, mut files) in rows {
        if registry.entries().iter().any(|e| e.name == name) {
            continue;
        }
        files.files.retain(|_, f| f.path.exists());
        for file in files.files.values_mut() {
            file.sha256 = file_sha256(&file.path)?;
        }
        if !files.files.is_empty() {
            registry.external(&name, files);
        }
    }
    Ok(())
}

/// Whether `name` may name an external row: a plain file name (no separators, no `@`, which
/// separates a segmenter from its flow source, no `,`, which separates rows, nothing a
/// Markdown table cell breaks on) that is not a built-in row's.
fn check_row_name(name: &str, registry: &Registry) -> Result<(), String> {
    let allowed = |c: char| c.is_ascii_alphanumeric() || "._+-".contains(c);
    if name.is_empty() || !name.chars().all(allowed) || name.starts_with('.') {
        return Err(format!(
            "{name:?} cannot name a row: letters, digits, '.', '_', '+' and '-' only, not \
             starting with '.'"
        ));
    }
    // Case-insensitively, as the runs files of rows are named after them.
    let builtin = registry
        .entries()
        .iter()
        .any(|e| e.name.eq_ignore_ascii_case(name) && !matches!(e.runner, Runner::External(_)));
    if builtin {
        return Err(format!("{name} is a built-in row's name; choose another with --name"));
    }
    Ok(())
}

/// `evaluator score`: scores the prediction file `predictions` on `dataset` (a name or a
/// folder) as the external row `name` (default: the method named in the file's header),
/// adds it to every board under `setup.reports`, and remembers it there. Returns the row's
/// name and the evaluation's summary. Nothing under the reports folder changes when the
/// file is refused.
pub fn score_predictions(
    registry: &Registry,
    specs: &[DatasetSpec],
    dataset: &str,
    predictions: &Path,
    name: Option<&str>,
    setup: &CommandOptions,
    progress: &dyn Progress,
) -> Result<(String, Summary), EvalError> {
    let spec = resolve_dataset(dataset, specs, &setup.datasets_root)?;
    let path = std::fs::canonicalize(predictions)
        .map_err(|source| EvalError::Io { path: predictions.into(), source })?;
    // The file is read once: its header, records and hash.
    let file = PredictionFile::read(&path)?;
    let name = name.unwrap_or(&file.header.method).to_owned();
    check_row_name(&name, registry)
        .map_err(|message| EvalError::PredictionsMismatch { path: predictions.into(), message })?;
    let mut rows = remembered_rows(&setup.reports)?;
    let mut files = rows.remove(&name).unwrap_or_default();
    files.files.insert(spec.name.clone(), ExternalFile::read(file));
    let mut registry = registry.clone();
    add_rows(&mut registry, rows.clone())?;
    registry.external(&name, files.clone());
    let mut all_specs = specs.to_vec();
    if !all_specs.iter().any(|s| s.name == spec.name) {
        all_specs.push(spec.clone());
    }
    let options = Options {
        datasets: vec![spec.name.clone()],
        methods: vec![name.clone()],
        limit: None,
        datasets_root: setup.datasets_root.clone(),
        reports: setup.reports.clone(),
        force: false,
        gallery_pairs: setup.gallery_pairs,
        validation: validation_datasets(),
    };
    let summary = evaluate(&registry, &all_specs, &options, progress)?;
    rows.insert(name.clone(), files);
    remember_rows(&setup.reports, &rows)?;
    remember_datasets(&setup.reports, std::slice::from_ref(&spec))?;
    Ok((name, summary))
}

/// What `evaluator predict` writes.
#[derive(Debug, Clone)]
pub struct PredictRequest {
    /// The dataset: a name, or a dataset folder.
    pub dataset: String,
    /// The row.
    pub row: String,
    /// The prediction file to write.
    pub out: PathBuf,
    /// Only the first pairs of the dataset.
    pub limit: Option<usize>,
}

/// `evaluator predict`: writes row `row`'s predictions on `dataset` (a name or a folder) to
/// `out` in the prediction file format; returns the number of pairs and of failed pairs.
pub fn write_predictions(
    registry: &Registry,
    specs: &[DatasetSpec],
    request: &PredictRequest,
    setup: &CommandOptions,
    progress: &dyn Progress,
) -> Result<(usize, usize), EvalError> {
    let PredictRequest { dataset, row, out, limit } = request;
    let (row, limit) = (row.as_str(), *limit);
    let spec = resolve_dataset(dataset, specs, &setup.datasets_root)?;
    let mut all_specs = specs.to_vec();
    if !all_specs.iter().any(|s| s.name == spec.name) {
        all_specs.push(spec.clone());
    }
    let options = Options {
        datasets: vec![spec.name.clone()],
        methods: vec![row.to_owned()],
        limit,
        datasets_root: setup.datasets_root.clone(),
        reports: setup.reports.clone(),
        force: false,
        gallery_pairs: 0,
        validation: validation_datasets(),
    };
    let rows = predict_row(registry, &all_specs, &options, row, progress)?;
    let header = PredictionHeader::new(row, &rows.fingerprint, dataset_hash(&rows.dataset));
    let mut writer = PredictionWriter::create(out, &header)?;
    let mut failed = 0;
    for (id, prediction) in &rows.predictions {
        let record = match prediction {
            Ok(p) => PredictionRecord::from_prediction(id, p),
            Err(reason) => {
                failed += 1;
                PredictionRecord::failure(id, reason)
            }
        };
        writer.write(&record)?;
    }
    writer.finish()?;
    Ok((rows.predictions.len(), failed))
}
