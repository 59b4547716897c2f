//! The method registry: every row of the leaderboards by name. A row is a whole method
//! (`net`, `nrr`, a flow baseline), a segmenter combined with a flow source
//! (`seqransac@gt-flow`, `seqransac@net-flow`), or the `gt` sanity oracle. Combinations come
//! from [`Registry::combine`], not from copied code.

use std::sync::Arc;

use pairs::{Method, Segmenter};

use crate::error::EvalError;
use crate::rows::external::{ExternalFiles, EXTERNAL};
use crate::rows::grid::Grid;
pub use crate::rows::runner::{method_flow_name, FlowSource, Runner};

/// What a row is scored on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Board {
    /// Flow only (flow baselines: their single segment is not a segmentation).
    Flow,
    /// Segmentation only (a segmenter on someone else's flow reports no flow of its own).
    Segmentation,
    /// Both leaderboards.
    Both,
}

/// One leaderboard row: a name, how to run it, and what identifies its results.
#[derive(Clone)]
pub struct Entry {
    /// Row name (`seqransac@net-flow`).
    pub name: String,
    /// How predictions are made.
    pub runner: Runner,
    /// Which leaderboards list it.
    pub board: Board,
    /// Identifies the method's code (a hash of its crates' source), parameters and weights:
    /// cached results made with another fingerprint are recomputed. For a tuned row, what
    /// identifies its flow source; the chosen parameters are added once tuned.
    pub fingerprint: String,
    /// The parameters cross-validated for this row on the validation sets ([`crate::tuning`]);
    /// `runner` then holds the grid's first point until the row is tuned.
    pub grid: Option<Grid>,
    /// Whether the row reads the ground truth (the `gt` oracle and rows on `gt-flow`).
    pub oracle: bool,
}

impl Entry {
    /// The `flow_source` column: `gt` for the oracle, `own` for whole methods, `external` for
    /// rows scored from prediction files, else the source's name.
    pub fn flow_source(&self) -> String {
        match &self.runner {
            Runner::Oracle => "gt".into(),
            Runner::Method(_) => "own".into(),
            Runner::External(_) => EXTERNAL.into(),
            Runner::Segmenter { flow, .. } => flow.name(),
        }
    }

    /// The fingerprint of the row's results on `dataset`: [`Entry::fingerprint`], or for an
    /// external row its file's for that dataset.
    pub fn fingerprint_for(&self, dataset: &str) -> String {
        match &self.runner {
            Runner::External(files) => files.fingerprint(dataset).unwrap_or_default(),
            _ => self.fingerprint.clone(),
        }
    }

    /// Whether the row has results on `dataset`: every row but an external one without a
    /// prediction file for it.
    pub fn runs_on(&self, dataset: &str, cross_instance: bool) -> bool {
        match &self.runner {
            Runner::External(files) => files.files.contains_key(dataset),
            _ if !cross_instance => true,
            Runner::Segmenter { flow: FlowSource::GroundTruth, .. } => false,
            _ => self.board != Board::Flow,
        }
    }

    /// The method column: the row name without its `@flow` suffix.
    pub fn method(&self) -> &str {
        self.name.split('@').next().unwrap_or(&self.name)
    }
}

/// The ordered set of rows the evaluator can run.
#[derive(Clone, Default)]
pub struct Registry {
    entries: Vec<Entry>,
}

impl Registry {
    /// An empty registry.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds the `gt` oracle row.
    pub fn oracle(&mut self) -> &mut Self {
        let fingerprint = format!("gt {}", env!("SOURCE_HASH_SCORING"));
        self.push(Entry {
            name: "gt".into(),
            runner: Runner::Oracle,
            board: Board::Both,
            fingerprint,
            grid: None,
            oracle: true,
        })
    }

    /// Adds a whole method under its own name.
    pub fn method(
        &mut self,
        method: Arc<dyn Method>,
        board: Board,
        fingerprint: &str,
    ) -> &mut Self {
        let name = method.name().to_owned();
        let runner = Runner::Method(method);
        let fingerprint = fingerprint.into();
        self.push(Entry { name, runner, board, fingerprint, grid: None, oracle: false })
    }

    /// Adds `segmenter` on `flow` as `<segmenter>@<flow>` (segmentation board only: the flow
    /// is the source's), or under `name` when given: a row of its own such as `one-part`,
    /// which reports its own flow and so is on both boards.
    pub fn combine(
        &mut self,
        segmenter: Arc<dyn Segmenter>,
        flow: FlowSource,
        fingerprint: &str,
        name: Option<&str>,
    ) -> &mut Self {
        let name =
            name.map_or_else(|| format!("{}@{}", segmenter.name(), flow.name()), str::to_owned);
        let board = if name.contains('@') { Board::Segmentation } else { Board::Both };
        let oracle = matches!(flow, FlowSource::GroundTruth);
        let runner = Runner::Segmenter { segmenter, flow };
        let fingerprint = fingerprint.into();
        self.push(Entry { name, runner, board, fingerprint, grid: None, oracle })
    }

    /// Adds an external row `name` scored from `files` (both boards, `external` flow source).
    pub fn external(&mut self, name: &str, files: ExternalFiles) -> &mut Self {
        self.push(Entry {
            name: name.to_owned(),
            runner: Runner::External(Arc::new(files)),
            board: Board::Both,
            fingerprint: format!("external {}", env!("SOURCE_HASH_SCORING")),
            grid: None,
            oracle: false,
        })
    }

    /// Adds a row whose parameters are cross-validated over `grid` before it runs: `name`
    /// (`seqransac@net-flow`, or a whole method's name), on `board`, reading the truth when
    /// `oracle`. `source_fingerprint` identifies its input (the flow source's fingerprint and
    /// the code); the chosen parameters join it once the row is tuned.
    pub fn tuned(
        &mut self,
        name: &str,
        grid: Grid,
        board: Board,
        source_fingerprint: &str,
        oracle: bool,
    ) -> &mut Self {
        let first: Vec<f64> = grid.axes.iter().map(|a| a.values[0]).collect();
        let (runner, _) = (grid.build)(&first);
        self.push(Entry {
            name: name.to_owned(),
            runner,
            board,
            fingerprint: source_fingerprint.to_owned(),
            grid: Some(grid),
            oracle,
        })
    }

    fn push(&mut self, entry: Entry) -> &mut Self {
        self.entries.retain(|e| e.name != entry.name);
        self.entries.push(entry);
        self
    }

    /// Every row, in registration order.
    pub fn entries(&self) -> &[Entry] {
        &self.entries
    }

    /// The rows named in `names` (all rows when `names` is empty), in registration order;
    /// an unknown name is an error listing the known ones.
    pub fn select(&self, names: &[String]) -> Result<Vec<Entry>, EvalError> {
        if let Some(unknown) = names.iter().find(|n| !self.entries.iter().any(|e| &e.name == *n)) {
            return Err(EvalError::Unknown {
                what: "method",
                name: unknown.clone(),
                known: self.entries.iter().map(|e| e.name.as_str()).collect::<Vec<_>>().join(", "),
            });
        }
        Ok(self
            .entries
            .iter()
            .filter(|e| names.is_empty() || names.contains(&e.name))
            .cloned()
            .collect())
    }
}
