//! Metrics shared by the evaluator and the model's trainer (docs/METRICS.md gives each
//! formula and convention): flow errors ([`flow`]), segmentation scores
//! ([`segmentation`]), the errors of matched parts' motions ([`motion`]) and of the joints
//! estimated from them ([`joints`]). Every function is pure and checks its inputs' lengths.
//! [`pair`] puts them together into the one score of a pair ([`score_pair`]) and [`sets`]
//! into the score of a set of K views ([`score_set`]); the evaluator's rows and iteration
//! passes and the trainer's validation all use these two. [`conventions`] gives joint
//! errors the way PARIS and DigitalTwinArt report them.

pub mod conventions;
pub mod flow;
pub mod joints;
pub mod motion;
pub mod pair;
pub mod render_joints;
pub mod segmentation;
pub mod sets;

pub use flow::{end_point_errors, epe, pcc, pcc_at, pcc_auc, PCC_STEP, PCC_THRESHOLDS};
pub use joints::{joint_errors, joint_errors_of, line_to_line_distance, JointError, JointScores};
pub use motion::{motion_errors, segment_count, MotionErrors};
pub use pair::{check_prediction, score_pair, FlowScore, PairScore, ScoreError, SegmentScore};
pub use segmentation::{matched_iou, max_assignment, rand_index, PartMatching};
pub use sets::{score_set, score_set_prediction, SetScore, SetScores};

/// Inputs a metric cannot score.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum MetricError {
    /// A prediction and its ground truth differ in length.
    #[error("{what}: prediction has {predicted} entries, ground truth {truth}")]
    LengthMismatch {
        /// Which quantity (`flow`, `segments`).
        what: &'static str,
        /// Entries predicted.
        predicted: usize,
        /// Entries in the ground truth.
        truth: usize,
    },
    /// Nothing to score.
    #[error("{0}: no points")]
    Empty(&'static str),
    /// A predicted value is NaN or infinite.
    #[error("{what}: entry {index} is not finite")]
    NotFinite {
        /// Which quantity.
        what: &'static str,
        /// First bad entry.
        index: usize,
    },
}

/// Checks that `predicted` and `truth` have one equal, non-zero length.
fn check_lengths(what: &'static str, predicted: usize, truth: usize) -> Result<(), MetricError> {
    if predicted != truth {
        return Err(MetricError::LengthMismatch { what, predicted, truth });
    }
    if truth == 0 {
        return Err(MetricError::Empty(what));
    }
    Ok(())
}
