//! The trainer: the run's paths and budget, the stream it draws pairs from, and the loop of
//! steps, validations and checkpoints ([`Trainer`]).

use std::path::PathBuf;
use std::time::Instant;

use burn::grad_clipping::GradientClippingConfig;
use burn::optim::{AdamConfig, ModuleOptimizer};
use burn::prelude::*;
use generator::config::GeneratorConfig;
use generator::stream::TrainingStream;
use pairs::math::Matrix3;
use pairs::Pair;

use crate::network::PartInductionNet;
use crate::train::checkpoint::{Best, CheckpointDir, TrainState};
use crate::train::config::TrainConfig;
use crate::train::log::{Log, StepRow, ValidationRow};
use crate::train::validation::{score, validation_pairs};
use crate::weights;

use crate::train::step::{augmentation, batch_gradients, fed_true_flow, residual, Draws};
use crate::train::TrainError;

/// Where a run writes.
#[derive(Debug, Clone)]
pub struct RunPaths {
    /// Checkpoints (weights, optimiser state, position).
    pub checkpoints: CheckpointDir,
    /// Report folder: `log.csv`, `validation.csv`, `loss.png`.
    pub reports: PathBuf,
}

impl RunPaths {
    /// The default folders for a config: `checkpoints/<name>` and `reports/training/<name>`.
    pub fn for_config(config: &TrainConfig) -> Self {
        Self {
            checkpoints: CheckpointDir::new(PathBuf::from("checkpoints").join(&config.name)),
            reports: PathBuf::from("reports/training").join(&config.name),
        }
    }
}

/// How much of a run one call of [`Trainer::run`] may do (the default: all of it).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Budget {
    /// Most optimiser steps.
    pub steps: Option<u64>,
    /// Most wall-clock time; the step under way when it runs out is finished.
    pub time: Option<std::time::Duration>,
}

impl Budget {
    /// At most `steps` steps.
    pub fn steps(steps: u64) -> Self {
        Self { steps: Some(steps), time: None }
    }
}

/// What the caller sees after every step, for progress display.
#[derive(Debug, Clone, Copy)]
pub struct Progress<'a> {
    /// The step just taken.
    pub row: &'a StepRow,
    /// Total pairs of the run.
    pub total_pairs: u64,
    /// The latest validation, if any.
    pub validation: Option<&'a ValidationRow>,
}

/// The generator settings of the training stream: every pair from a new object, so a batch
/// mixes objects.
pub fn stream_config(config: &TrainConfig) -> GeneratorConfig {
    GeneratorConfig {
        points: config.points,
        seed: config.seed,
        states_per_object: 2,
        pairs_per_object: 1,
        scanned_per_pair: config.scanned_per_pair,
        ..pose_of(config, GeneratorConfig::training())
    }
}

/// `base` without the global poses when the config trains without a relative pose.
fn pose_of(config: &TrainConfig, base: GeneratorConfig) -> GeneratorConfig {
    if config.relative_pose {
        base
    } else {
        GeneratorConfig { pose_rotation_deg: 0.0, pose_translation: 0.0, ..base }
    }
}

/// Where training pairs come from.
enum Source {
    /// The generator's endless training stream.
    Stream(TrainingStream),
    /// A fixed set, cycled in order (overfitting tests, fine-tuning on a small set).
    Fixed(Vec<Pair>),
}

/// A training run: network, optimiser, data and logs.
pub struct Trainer {
    config: TrainConfig,
    paths: RunPaths,
    device: Device,
    net: PartInductionNet,
    optimizer: ModuleOptimizer,
    state: TrainState,
    source: Source,
    validation: Vec<Pair>,
    log: Log,
}

impl std::fmt::Debug for Trainer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Trainer")
            .field("config", &self.config.name)
            .field("state", &self.state)
            .finish()
    }
}

impl Trainer {
    /// Starts a run on the training stream, or resumes it from the checkpoint in `paths`
    /// (which must be of the same config). `device` is the autodiff device to train on.
    pub fn new(config: TrainConfig, paths: RunPaths, device: Device) -> Result<Self, TrainError> {
        Self::with_source(config, paths, device, None)
    }

    /// Like [`Trainer::new`], but cycles through `pairs` instead of the stream and validates
    /// on them too.
    pub fn on_pairs(
        config: TrainConfig,
        paths: RunPaths,
        device: Device,
        pairs: Vec<Pair>,
    ) -> Result<Self, TrainError> {
        Self::with_source(config, paths, device, Some(pairs))
    }

    fn with_source(
        config: TrainConfig,
        paths: RunPaths,
        device: Device,
        fixed: Option<Vec<Pair>>,
    ) -> Result<Self, TrainError> {
        let optimizer = AdamConfig::new()
            .with_epsilon(config.adam_epsilon)
            .with_grad_clipping(Some(GradientClippingConfig::Norm(config.clip_gradient_norm)))
            .init();
        let (net, optimizer, state) = match paths.checkpoints.load_state()? {
            Some(state) => {
                if state.config != config {
                    return Err(TrainError::ConfigMismatch {
                        dir: paths.checkpoints.root().to_path_buf(),
                    });
                }
                let (net, optimizer) = paths.checkpoints.load(&config, optimizer, &device)?;
                tracing::info!(step = state.step, pairs = state.pairs, "resuming from checkpoint");
                (net, optimizer, state)
            }
            None => {
                let net = match &config.init_weights {
                    Some(path) => {
                        tracing::info!(weights = %path.display(), "starting from weights");
                        let loaded = weights::read_record(&config.network, path, &device)?;
                        if config.init_modules.is_empty() {
                            loaded
                        } else {
                            PartInductionNet::seeded(&config.network, &device, config.seed)
                                .with_modules_from(loaded, &config.init_modules)
                        }
                    }
                    None => PartInductionNet::seeded(&config.network, &device, config.seed),
                };
                let state = TrainState {
                    config: config.clone(),
                    step: 0,
                    pairs: 0,
                    next_object: 0,
                    seconds: 0.0,
                    best: None,
                };
                (net, optimizer, state)
            }
        };
        let log = Log::open(&paths.reports, state.step)?;
        let (source, validation) = match fixed {
            Some(pairs) => (Source::Fixed(pairs.clone()), pairs),
            None => (
                Source::Stream(TrainingStream::starting_at(
                    stream_config(&config),
                    state.next_object,
                )?),
                validation_pairs(
                    config.points,
                    config.validation_pairs,
                    config.scanned_per_pair > 0,
                )?,
            ),
        };
        Ok(Self { config, paths, device, net, optimizer, state, source, validation, log })
    }

    /// The network being trained.
    pub fn network(&self) -> &PartInductionNet {
        &self.net
    }

    /// Where the run stands.
    pub fn state(&self) -> &TrainState {
        &self.state
    }

    /// Takes one optimiser step on the next batch of the stream.
    pub fn step(&mut self) -> Result<StepRow, TrainError> {
        let started = Instant::now();
        let mut pairs = Vec::with_capacity(self.config.batch);
        match &mut self.source {
            Source::Stream(stream) => {
                for pair in stream.by_ref().take(self.config.batch) {
                    let pair = pair?;
                    self.state.next_object = pair.provenance().object_id + 1;
                    pairs.push(pair);
                }
            }
            Source::Fixed(set) => {
                let start = self.state.pairs as usize;
                pairs.extend((0..self.config.batch).map(|i| set[(start + i) % set.len()].clone()));
            }
        }
        let step = self.state.step;
        let rotations: Vec<Matrix3> =
            (0..pairs.len()).map(|i| augmentation(&self.config, step, i)).collect();
        let stage = self.config.stage_at(self.state.pairs);
        let true_flow: Vec<bool> =
            (0..pairs.len()).map(|i| fed_true_flow(&self.config, step, i)).collect();
        // Residual pairs teach the flow module what the iterations leave; in stages 2 and 3
        // the segmentation module learns from the flow, which on a residual pair no longer
        // tells the parts apart.
        let residuals: Vec<_> = (0..pairs.len())
            .map(|i| if stage == 1 { residual(&self.config, step, i) } else { None })
            .collect();
        let (value, terms, grads, mut phases) = batch_gradients(
            &self.net,
            &self.config,
            &self.device,
            &pairs,
            Draws { rotations: &rotations, true_flow: &true_flow, residuals: &residuals },
            stage,
        )
        .map_err(|source| TrainError::Batch { step, source })?;
        if !value.is_finite() {
            return Err(TrainError::Diverged { step, stage, value });
        }
        let lr = self.config.learning_rate_at(self.state.pairs);
        let clock = Instant::now();
        self.net = self.optimizer.step(lr, self.net.clone(), grads);
        phases.optimizer = clock.elapsed().as_secs_f64();
        self.state.step += 1;
        self.state.pairs += pairs.len() as u64;
        let seconds = started.elapsed().as_secs_f64();
        self.state.seconds += seconds;
        let row = StepRow {
            step: self.state.step,
            pairs: self.state.pairs,
            stage,
            learning_rate: lr,
            loss: value,
            terms,
            seconds,
            phases,
        };
        self.log.step(&row)?;
        Ok(row)
    }

    /// Scores the current network on the validation set, logs it, and keeps the weights if
    /// they are the best so far.
    pub fn validate(&mut self) -> Result<ValidationRow, TrainError> {
        let net = self.net.valid();
        let scores = score(&net, &self.validation)?;
        let stage = self.config.stage_at(self.state.pairs.saturating_sub(1));
        let best = Best {
            stage,
            pairs: self.state.pairs,
            epe: scores.epe,
            rand_index: scores.rand_index,
            iou: scores.iou,
            support_iou: Some(scores.support_iou),
        };
        if self.state.best.is_none_or(|b| best.beats(&b)) {
            self.paths.checkpoints.save_best(&net, &self.config)?;
            self.state.best = Some(best);
        }
        let row = ValidationRow { step: self.state.step, pairs: self.state.pairs, stage, scores };
        self.log.validation(&row)?;
        Ok(row)
    }

    /// Writes a checkpoint and redraws the loss curve.
    pub fn checkpoint(&mut self) -> Result<(), TrainError> {
        self.paths.checkpoints.save(&self.net, &self.optimizer, &self.state)?;
        self.log.plot()?;
        Ok(())
    }

    /// Trains until the config's last stage ends or the `budget` is spent, validating and
    /// checkpointing on schedule (and once more at the end); `progress` is called after
    /// every step.
    pub fn run(
        &mut self,
        budget: Budget,
        mut progress: impl FnMut(Progress<'_>),
    ) -> Result<(), TrainError> {
        let started = Instant::now();
        let total = self.config.total_pairs();
        let every = self.config.validate_every_pairs;
        let interval = std::time::Duration::from_secs_f64(self.config.checkpoint_minutes * 60.0);
        let mut last_save = Instant::now();
        let mut latest: Option<ValidationRow> = None;
        let mut taken = 0;
        while self.state.pairs < total
            && budget.steps.is_none_or(|m| taken < m)
            && budget.time.is_none_or(|t| started.elapsed() < t)
        {
            let before = self.state.pairs;
            let row = self.step()?;
            taken += 1;
            let crossed = before / every != row.pairs / every
                || self.config.stage_at(before) != self.config.stage_at(row.pairs)
                || row.pairs >= total;
            if crossed {
                latest = Some(self.validate()?);
            }
            if last_save.elapsed() >= interval {
                self.checkpoint()?;
                last_save = Instant::now();
            }
            progress(Progress { row: &row, total_pairs: total, validation: latest.as_ref() });
        }
        self.checkpoint()
    }
}
