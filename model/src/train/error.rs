//! Why training stopped early.

use std::path::PathBuf;

use crate::network::sampling::SamplingError;
use crate::train::checkpoint::CheckpointError;
use crate::train::log::LogError;
use crate::train::validation::ScoreError;
use crate::weights::WeightsError;

/// Why training stopped early.
#[derive(Debug, thiserror::Error)]
pub enum TrainError {
    /// A checkpoint could not be saved or restored.
    #[error("checkpoint: {0}")]
    Checkpoint(#[from] CheckpointError),
    /// The config's `init_weights` could not be read.
    #[error("init_weights: {0}")]
    InitWeights(#[from] WeightsError),
    /// The log could not be written.
    #[error("log: {0}")]
    Log(#[from] LogError),
    /// The training stream or validation set could not be generated.
    #[error("generator: {0}")]
    Generate(#[from] generator::generate::GenerateError),
    /// A batch could not be prepared or run.
    #[error("batch at step {step}: {source}")]
    Batch {
        /// The step.
        step: u64,
        /// What went wrong.
        #[source]
        source: SamplingError,
    },
    /// Validation failed.
    #[error("validation: {0}")]
    Validation(#[from] ScoreError),
    /// The loss is not finite.
    #[error(
        "the loss became {value} at step {step} (stage {stage}); lower learning_rate in the config"
    )]
    Diverged {
        /// The step.
        step: u64,
        /// The stage.
        stage: u8,
        /// The loss.
        value: f32,
    },
    /// The checkpoint belongs to another config.
    #[error("{dir} holds a checkpoint of a different config; pass another --checkpoints folder, or delete it to start over")]
    ConfigMismatch {
        /// The checkpoint folder.
        dir: PathBuf,
    },
}
