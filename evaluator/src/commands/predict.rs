//! One row's predictions on one dataset, as the leaderboards would score them
//! (`evaluator predict`).

use pairs::Prediction;
use rayon::prelude::*;

use crate::commands::pipeline::{resolve_tuning, Options, Progress};
use crate::datasets::{
    ensure_dataset, holds_sets, load_dataset, load_set_dataset, DatasetSpec, LoadedDataset,
};
use crate::error::EvalError;
use crate::rows::registry::Registry;
use crate::running::run::{predict_pair, prepare, FlowCache};

/// Every prediction of row `row` on the dataset `options.datasets[0]` (made when missing),
/// in the dataset's pair order, as the leaderboards would score them: a tuned row with its
/// chosen parameters (tuned now unless its sweep is cached), a segmenter on its flow
/// source's flow. A pair the row fails on has the reason instead.
pub fn predict_row(
    registry: &Registry,
    specs: &[DatasetSpec],
    options: &Options,
    row: &str,
    progress: &dyn Progress,
) -> Result<RowPredictions, EvalError> {
    let name = options.datasets.first().cloned().unwrap_or_default();
    let spec = specs.iter().find(|s| s.name == name).ok_or_else(|| EvalError::Unknown {
        what: "dataset",
        name: name.clone(),
        known: specs.iter().map(|s| s.name.as_str()).collect::<Vec<_>>().join(", "),
    })?;
    ensure_dataset(spec, &options.datasets_root, &|m| progress.notice(m), |done, total| {
        progress.generating(&spec.name, done, total)
    })?;
    let dir = spec.dir(&options.datasets_root);
    // On a set dataset the row predicts the pairs (view 0, view k) of every set, the records
    // a set prediction file holds (docs/FORMAT.md).
    let dataset = if holds_sets(spec, &dir) {
        load_set_dataset(&spec.name, &dir, options.limit)?.pairs
    } else {
        load_dataset(&spec.name, &dir, options.limit)?
    };
    let selected = registry.select(&[row.to_owned()])?;
    let flows = FlowCache::default();
    let (entries, _) =
        resolve_tuning(registry.entries(), &selected, true, options, &flows, progress)?;
    let entry = entries.into_iter().find(|e| e.name == row).expect("selected above");
    let (source_flows, runner) = prepare(&entry, &dataset, &flows)?;
    let runner = &runner;
    progress.start(row, &dataset.name, dataset.pairs.len() as u64);
    let predictions = dataset
        .pairs
        .par_iter()
        .enumerate()
        .map(|(i, pair)| {
            let prediction = predict_pair(runner, pair, source_flows.as_ref().map(|f| &f[i]));
            progress.tick();
            (pair.id().to_owned(), prediction)
        })
        .collect();
    progress.finish(row, &dataset.name, false);
    Ok(RowPredictions { fingerprint: entry.fingerprint_for(&dataset.name), dataset, predictions })
}

/// What [`predict_row`] returns.
pub struct RowPredictions {
    /// The row's fingerprint (its code, parameters and weights).
    pub fingerprint: String,
    /// The dataset predicted.
    pub dataset: LoadedDataset,
    /// Each pair's id and prediction (or why it has none), in the dataset's order.
    pub predictions: Vec<(String, Result<Prediction, String>)>,
}
