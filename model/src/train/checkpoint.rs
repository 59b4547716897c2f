//! Training checkpoints: the network, Adam's state and the trainer's position, written to
//! temporary names and renamed into place so an interrupted save never leaves a checkpoint
//! that looks complete. A checkpoint folder is a weights folder ([`crate::weights`]): its
//! `config.toml` and `model.bpk` are the latest weights, its `best/` those of the best
//! validation so far.

use std::path::{Path, PathBuf};

use burn::optim::ModuleOptimizer;
use burn::prelude::*;
use serde::{Deserialize, Serialize};

use pairs::atomic::{at, replace_with, FileError};

use crate::network::PartInductionNet;
use crate::train::config::TrainConfig;
use crate::weights::{self, WeightsError};

/// The best validation scores so far and when they were reached.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Best {
    /// Stage of training at the validation.
    pub stage: u8,
    /// Training pairs seen.
    pub pairs: u64,
    /// Validation EPE.
    pub epe: f64,
    /// Validation Rand index.
    pub rand_index: f64,
    /// Validation IoU.
    pub iou: f64,
    /// Validation support IoU on the true flow (absent in checkpoints written before it
    /// was measured).
    #[serde(default)]
    pub support_iou: Option<f64>,
}

impl Best {
    /// Whether `self` beats `other`, by the stage's own metric: a later stage wins; within
    /// stage 1 a lower EPE, within stage 2 (the segmentation module on the true flow) a
    /// higher support IoU (a measured one beats none), within stage 3 a higher IoU.
    pub fn beats(&self, other: &Best) -> bool {
        if self.stage != other.stage {
            return self.stage > other.stage;
        }
        match self.stage {
            1 => self.epe < other.epe,
            2 => self.support_iou.is_some_and(|s| other.support_iou.is_none_or(|o| s > o)),
            _ => self.iou > other.iou,
        }
    }
}

/// Where the trainer is: enough to resume exactly.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrainState {
    /// The config the run was started with; a resume must use the same.
    pub config: TrainConfig,
    /// Optimiser steps taken.
    pub step: u64,
    /// Training pairs consumed.
    pub pairs: u64,
    /// The next object of the training stream.
    pub next_object: u32,
    /// Wall-clock seconds spent training, over all sessions.
    pub seconds: f64,
    /// Best validation so far.
    pub best: Option<Best>,
}

/// Why a checkpoint could not be written or read.
#[derive(Debug, thiserror::Error)]
pub enum CheckpointError {
    /// File system error.
    #[error(transparent)]
    Io(#[from] FileError),
    /// The weights (or the optimiser's record) could not be written or read.
    #[error(transparent)]
    Weights(#[from] WeightsError),
    /// The state file is not valid.
    #[error("{path}: {source}")]
    State {
        /// The file.
        path: PathBuf,
        /// The parser's error.
        #[source]
        source: serde_json::Error,
    },
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> CheckpointError + '_ {
    move |e| at(path)(e).into()
}

fn record(path: &Path) -> impl FnOnce(burn::store::RecordError) -> CheckpointError + '_ {
    move |e| WeightsError::Record { path: path.to_path_buf(), message: e.to_string() }.into()
}

/// The files of a checkpoint folder.
#[derive(Debug, Clone)]
pub struct CheckpointDir {
    root: PathBuf,
}

impl CheckpointDir {
    /// The folder `root` (created on the first save).
    pub fn new(root: impl Into<PathBuf>) -> Self {
        Self { root: root.into() }
    }

    /// The folder.
    pub fn root(&self) -> &Path {
        &self.root
    }

    /// The latest weights' parameters (the folder itself is their weights folder).
    pub fn model(&self) -> PathBuf {
        self.root.join(weights::MODEL_FILE)
    }

    /// The weights folder of the best validation so far.
    pub fn best(&self) -> PathBuf {
        self.root.join("best")
    }

    /// Where checkpoints written before `best/` kept the best weights' parameters.
    fn old_best(&self) -> PathBuf {
        self.root.join("best.bpk")
    }

    fn optimizer(&self) -> PathBuf {
        self.root.join("optimizer.bpk")
    }

    fn state(&self) -> PathBuf {
        self.root.join("state.json")
    }

    /// Saves `net` as the best weights so far.
    pub fn save_best(
        &self,
        net: &PartInductionNet,
        config: &TrainConfig,
    ) -> Result<(), CheckpointError> {
        Ok(weights::save(&self.best(), net, config)?)
    }

    /// The saved state, if there is a checkpoint.
    pub fn load_state(&self) -> Result<Option<TrainState>, CheckpointError> {
        let path = self.state();
        if !path.exists() {
            return Ok(None);
        }
        let text = std::fs::read_to_string(&path).map_err(io(&path))?;
        serde_json::from_str(&text)
            .map(Some)
            .map_err(|source| CheckpointError::State { path, source })
    }

    /// Restores the network and optimiser of the saved checkpoint of `config`. A checkpoint
    /// written before checkpoints were weights folders gets its `config.toml`, and its
    /// `best.bpk` becomes `best/`.
    pub fn load(
        &self,
        config: &TrainConfig,
        optimizer: ModuleOptimizer,
        device: &Device,
    ) -> Result<(PartInductionNet, ModuleOptimizer), CheckpointError> {
        weights::write_config(&self.root, config)?;
        let old = self.old_best();
        if old.is_file() {
            let best = self.best();
            std::fs::create_dir_all(&best).map_err(io(&best))?;
            weights::write_config(&best, config)?;
            let to = best.join(weights::MODEL_FILE);
            std::fs::rename(&old, &to).map_err(io(&to))?;
        }
        let net = weights::read_record(&config.network, &self.model(), device)?;
        let path = self.optimizer();
        let optimizer = optimizer.load(&path).map_err(record(&path))?;
        Ok((net, optimizer))
    }

    /// Saves network, optimiser and state; the state is written last, so a checkpoint is
    /// complete exactly when its state names it.
    pub fn save(
        &self,
        net: &PartInductionNet,
        optimizer: &ModuleOptimizer,
        state: &TrainState,
    ) -> Result<(), CheckpointError> {
        std::fs::create_dir_all(&self.root).map_err(io(&self.root))?;
        weights::write_config(&self.root, &state.config)?;
        weights::write_record(net, &self.model())?;
        replace_with(&self.optimizer(), |tmp| optimizer.save(tmp).map_err(record(tmp)))?;
        let text = serde_json::to_string_pretty(state).expect("the state serialises");
        replace_with(&self.state(), |tmp| std::fs::write(tmp, text).map_err(io(tmp)))
    }
}

#[cfg(test)]
mod tests {
    use super::Best;

    fn best(stage: u8, epe: f64, iou: f64, support_iou: Option<f64>) -> Best {
        Best { stage, pairs: 0, epe, rand_index: 0.5, iou, support_iou }
    }

    #[test]
    fn each_stage_is_judged_by_its_own_metric() {
        // A later stage wins whatever its scores.
        assert!(best(2, 0.9, 0.1, None).beats(&best(1, 0.1, 0.9, None)));
        // Stage 1: EPE.
        assert!(best(1, 0.05, 0.1, None).beats(&best(1, 0.06, 0.9, None)));
        assert!(!best(1, 0.06, 0.9, None).beats(&best(1, 0.05, 0.1, None)));
        // Stage 2: support IoU; a measured one beats a checkpoint from before it was.
        assert!(best(2, 0.1, 0.2, Some(0.6)).beats(&best(2, 0.1, 0.2, Some(0.5))));
        assert!(!best(2, 0.1, 0.2, Some(0.5)).beats(&best(2, 0.1, 0.2, Some(0.6))));
        assert!(best(2, 0.1, 0.2, Some(0.1)).beats(&best(2, 0.1, 0.2, None)));
        assert!(!best(2, 0.1, 0.2, None).beats(&best(2, 0.1, 0.2, Some(0.1))));
        // Stage 3: IoU.
        assert!(best(3, 0.2, 0.5, None).beats(&best(3, 0.1, 0.4, Some(0.9))));
    }

    #[test]
    fn a_best_written_before_the_support_iou_still_reads() {
        let old = r#"{"stage":2,"pairs":110000,"epe":0.069,"rand_index":0.513,"iou":0.227}"#;
        let read: Best = serde_json::from_str(old).expect("old record reads");
        assert_eq!(read.support_iou, None);
        assert_eq!(read.pairs, 110_000);
    }
}
