//! What a method sees (`PairInput`), what it returns (`Prediction`) and the `Method` trait that
//! baselines and the network implement.

use crate::joint_estimate::JointEstimate;
use crate::math::{Real, Vector3};
use crate::pair::PairInput;
use crate::parts::SegmentId;
use crate::transform::Similarity;

/// What every method returns for a pair.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Prediction {
    /// Flow on P, Q's normalised units; `None` for pure segmenters.
    pub flow: Option<Vec<Vector3>>,
    /// Segment id of every point of P.
    pub segments_p: Vec<SegmentId>,
    /// Segment id of every point of Q (same ids as P); empty if the method does not segment Q.
    pub segments_q: Vec<SegmentId>,
    /// Rigid (or similarity) motion of each segment, P's to Q's normalised frame; may be empty.
    pub motions: Vec<Similarity>,
    /// Soft correspondence mask on P in `[0, 1]`, if the method estimates one.
    pub corr_mask: Option<Vec<Real>>,
    /// Soft segment probabilities on P, row per point, if the method has them.
    pub segment_probs: Option<Vec<Vec<Real>>>,
    /// The joint that moves each segment (`None` for a segment without one), P's normalised
    /// frame, if the method estimates joints itself; otherwise the scorer estimates them
    /// from `motions` ([`crate::joint_estimate`]).
    pub joints: Option<Vec<Option<JointEstimate>>>,
}

/// Why a method could not produce a prediction for a pair.
#[derive(Debug, thiserror::Error)]
#[error("method {method} failed on pair {pair}: {source}")]
pub struct MethodError {
    /// The method's name.
    pub method: String,
    /// The pair's id.
    pub pair: String,
    /// The method's own error.
    #[source]
    pub source: Box<dyn std::error::Error + Send + Sync>,
}

impl MethodError {
    /// Wraps a method's own error with the method's name and the pair's id.
    pub fn new(
        method: &str,
        pair: &str,
        source: impl Into<Box<dyn std::error::Error + Send + Sync>>,
    ) -> Self {
        Self { method: method.to_owned(), pair: pair.to_owned(), source: source.into() }
    }
}

/// A part-induction method: segments, flow and motions from a pair without its ground truth.
pub trait Method: Send + Sync {
    /// Short stable name used in leaderboards.
    fn name(&self) -> &str;

    /// Predicts segments, flow and motions for one pair.
    fn predict(&self, input: &PairInput) -> Result<Prediction, MethodError>;

    /// Whether the method refines its answer over passes that are worth scoring one by one
    /// (the network's iterative procedure, the paper's Table 4); the evaluator then calls
    /// [`Method::predict_passes`] instead of [`Method::predict`]. `false` by default.
    fn iterative(&self) -> bool {
        false
    }

    /// Every pass's prediction, the first one first; the last must be what
    /// [`Method::predict`] returns. By default the one prediction of `predict`.
    fn predict_passes(&self, input: &PairInput) -> Result<Vec<Prediction>, MethodError> {
        Ok(vec![self.predict(input)?])
    }
}

/// A segmenter over a given flow: segments P (and Q) from P, Q and a flow on P, so one
/// segmentation algorithm can run on any flow source (ground truth, the network's, a flow
/// baseline's). The evaluator combines segmenters with flow sources by name.
pub trait Segmenter: Send + Sync {
    /// Short stable name used in leaderboards (without the flow source).
    fn name(&self) -> &str;

    /// Segments the pair given `flow` on P (Q's normalised units, one vector per point of P).
    fn segment(&self, input: &PairInput, flow: &[Vector3]) -> Result<Prediction, MethodError>;
}
