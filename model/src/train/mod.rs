//! Stage-wise training (the paper's "Training procedure"): pairs streamed from the generator's
//! training split, one random rotation per pair applied to both clouds, Adam on the config's
//! schedule (step decay, or a warm-up and half a cosine per stage), a CSV log and loss-curve
//! PNG under the report folder, validation on a fixed set, checkpoints every few minutes, and
//! exact resumption from the last checkpoint. Its `step` module holds one step's arithmetic (the
//! per-pair draws, the batch's loss and gradients over data-parallel shards); [`batch`] turns
//! pairs into tensors with their truth on the subsets, [`losses`] and [`objective`] are each
//! stage's terms and weights, [`validation`] the fixed validation set and its scores,
//! [`config`] the training settings, [`checkpoint`], [`log`] and [`plot`] what a run
//! writes, and [`average`] the mean of several checkpoints' weights.

pub mod average;
pub mod batch;
pub mod checkpoint;
pub mod config;
pub mod error;
pub mod log;
pub mod losses;
pub mod objective;
pub mod plot;
mod step;
pub mod trainer;
pub mod validation;

pub use error::TrainError;
pub use step::{batch_gradients, Draws};
pub use trainer::{stream_config, Budget, Progress, RunPaths, Trainer};
