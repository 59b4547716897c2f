//! What runs a row: the ground truth itself, a whole method, a prediction file, or a
//! segmenter on a flow source's flow.

use std::sync::Arc;

use pairs::{Method, Segmenter};

use crate::rows::external::ExternalFiles;

/// Where a segmenter's input flow comes from.
#[derive(Clone)]
pub enum FlowSource {
    /// The ground-truth flow (an oracle row).
    GroundTruth,
    /// The flow a method predicts (`net-flow`: the network's).
    Method(Arc<dyn Method>),
}

impl FlowSource {
    /// The name used after `@` in row names and in the `flow_source` column.
    pub fn name(&self) -> String {
        match self {
            Self::GroundTruth => "gt-flow".into(),
            Self::Method(m) => method_flow_name(m.name()),
        }
    }
}

/// The flow source name of a method's flow (`net` -> `net-flow`).
pub fn method_flow_name(method: &str) -> String {
    format!("{method}-flow")
}

/// How the runner gets a prediction for a row.
#[derive(Clone)]
pub enum Runner {
    /// The ground truth itself, read by the runner: the sanity row that must score EPE 0,
    /// RI 1 and IoU 1. No [`Method`] can do this, because a method only sees the input.
    Oracle,
    /// A whole method on the pair.
    Method(Arc<dyn Method>),
    /// Predictions read from a prediction file per dataset ([`crate::rows::external`]): a method
    /// that ran outside the evaluator.
    External(Arc<ExternalFiles>),
    /// A segmenter on a flow source's flow.
    Segmenter {
        /// The segmenter.
        segmenter: Arc<dyn Segmenter>,
        /// Its input flow.
        flow: FlowSource,
    },
}
