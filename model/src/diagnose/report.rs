//! What a diagnosis reports: its settings, one row per oracle substitution, the scale
//! summary, and why it can fail.

use pairs::PartId;

use crate::inference::labels::HardLabelParams;
use crate::train::validation::ScoreError;

/// Settings of [`diagnose`](crate::diagnose::diagnose).
#[derive(Debug, Clone, PartialEq)]
pub struct DiagnoseParams {
    /// Thresholds τ of the residual rule, normalised units; one row per value.
    pub thresholds: Vec<f32>,
    /// Subset sizes at which the true flow is sampled and interpolated back.
    pub flow_samples: Vec<usize>,
    /// Subset sizes (of P and of Q alike) of the matching floor: each subset point of P
    /// sent to the point of Q's subset nearest its true destination.
    pub matching_samples: Vec<usize>,
    /// Whether to run the iterative procedure (`net-iter`) on each pair, from the network's
    /// first pass and from the true labels (the slowest rows: about 4 passes a pair each).
    pub iterations: bool,
    /// The graph cut of the subset-ceiling rows.
    pub hard: HardLabelParams,
}

impl Default for DiagnoseParams {
    /// τ from 0.01 to 0.08 (doubling), the true flow at 128 and 256 points (the `cpu` and
    /// the release's correspondence subsets), the matching floor at 128, 256 and 512 points,
    /// the iterative procedure's rows, the evaluator's graph cut.
    fn default() -> Self {
        Self {
            thresholds: vec![0.01, 0.02, 0.04, 0.08],
            flow_samples: vec![128, 256],
            matching_samples: vec![128, 256, 512],
            iterations: true,
            hard: HardLabelParams::default(),
        }
    }
}

/// One row of the table: what was substituted, and the scores that apply to it.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// What the row measures.
    pub name: String,
    /// Support IoU of the support matrix (rows on the segmentation module's input).
    pub support_iou: Option<f64>,
    /// Matched IoU of the pass over every ground-truth part of every pair.
    pub iou: Option<f64>,
    /// End-point error of the flow, averaged over pairs.
    pub epe: Option<f64>,
}

/// The per-pair scale of the part motions: `|s - 1|` summarised over the pairs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScaleSummary {
    /// Median of `|s - 1|`.
    pub median: f64,
    /// 90th percentile of `|s - 1|`.
    pub p90: f64,
    /// Largest `|s - 1|`.
    pub max: f64,
}

/// The whole diagnosis of a set of pairs.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagnosis {
    /// Pairs scored.
    pub pairs: usize,
    /// The rows, in the order of the module docs.
    pub rows: Vec<Row>,
    /// The pairs' motion scales.
    pub scale: ScaleSummary,
}

impl Diagnosis {
    /// The table as CSV (`row,support_iou,iou,epe`; empty where a score does not apply).
    pub fn to_csv(&self) -> String {
        let cell = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v:.4}"));
        let mut out = String::from("row,support_iou,iou,epe\n");
        for r in &self.rows {
            out += &format!(
                "\"{}\",{},{},{}\n",
                r.name,
                cell(r.support_iou),
                cell(r.iou),
                cell(r.epe)
            );
        }
        let s = self.scale;
        out +=
            &format!("\"|s - 1| median / p90 / max\",{:.4},{:.4},{:.4}\n", s.median, s.p90, s.max);
        out
    }
}

/// Why a diagnosis failed.
#[derive(Debug, thiserror::Error)]
pub enum DiagnoseError {
    /// The network or a metric failed on a pair.
    #[error(transparent)]
    Score(#[from] ScoreError),
    /// A true part has too few points to fit its motion.
    #[error("pair {pair}: no motion fits part {part}")]
    Fit {
        /// The pair's id.
        pair: String,
        /// The part.
        part: PartId,
    },
    /// Nothing to diagnose.
    #[error("no pairs to diagnose")]
    Empty,
}
