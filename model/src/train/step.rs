//! One optimiser step's arithmetic: the augmentation rotation and the stage-3 flow choice
//! of every pair (each drawn from the seed, per step and pair), and the batch's loss and
//! gradients, computed as one batch or as data-parallel shards on long-lived threads.

use std::time::Instant;

use burn::module::{ModuleMapper, Param};
use burn::optim::{GradientsAccumulator, GradientsParams};
use burn::prelude::*;
use pairs::math::{Isometry3, Matrix3, Rotation3, Vector3};
use pairs::Pair;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

use crate::network::sampling::SamplingError;
use crate::network::PartInductionNet;
use crate::train::batch::{BatchOptions, TrainingBatch};
use crate::train::config::TrainConfig;
use crate::train::log::StepPhases;
use crate::train::objective::{stage_loss, LossTerms, Objective};

/// The augmentation rotation of pair `index` of step `step`: a uniformly random axis and an
/// angle uniform in `[0, max_deg]`.
pub(super) fn augmentation(config: &TrainConfig, step: u64, index: usize) -> Matrix3 {
    let mut rng = ChaCha8Rng::seed_from_u64(config.seed ^ step.wrapping_mul(0x9E37_79B9_7F4A_7C15));
    rng.set_stream(index as u64);
    let axis = loop {
        let v = Vector3::new(
            rng.random_range(-1.0f32..1.0),
            rng.random_range(-1.0f32..1.0),
            rng.random_range(-1.0f32..1.0),
        );
        let n = v.norm();
        if n > 0.1 && n <= 1.0 {
            break v / n;
        }
    };
    let angle = rng.random_range(0.0..=config.augment_rotation_deg as f32).to_radians();
    *Rotation3::from_scaled_axis(axis * angle).matrix()
}

/// Whether pair `index` of step `step` feeds stage 3's segmentation module the true flow: a
/// draw with probability `stage3_true_flow`, from its own stream of the seed (so the
/// augmentation's draws stay as they were).
pub(super) fn fed_true_flow(config: &TrainConfig, step: u64, index: usize) -> bool {
    if config.stage3_true_flow <= 0.0 {
        return false;
    }
    let mut rng = ChaCha8Rng::seed_from_u64(config.seed ^ step.wrapping_mul(0xD1B5_4A32_D192_ED03));
    rng.set_stream(index as u64);
    rng.random_bool(config.stage3_true_flow.min(1.0))
}

/// The residual perturbation of pair `index` of step `step`, if the draw (probability
/// `residual_pairs`, from its own stream of the seed) makes it a residual pair: a rotation
/// uniform in `[0, residual_rotation_deg]` about a random axis and a translation uniform in
/// `±residual_translation` per axis.
pub(super) fn residual(config: &TrainConfig, step: u64, index: usize) -> Option<Isometry3> {
    if config.residual_pairs <= 0.0 {
        return None;
    }
    let mut rng = ChaCha8Rng::seed_from_u64(config.seed ^ step.wrapping_mul(0xA24B_AED4_963E_E407));
    rng.set_stream(index as u64);
    if !rng.random_bool(config.residual_pairs.min(1.0)) {
        return None;
    }
    let axis = loop {
        let v = Vector3::new(
            rng.random_range(-1.0f32..1.0),
            rng.random_range(-1.0f32..1.0),
            rng.random_range(-1.0f32..1.0),
        );
        let n = v.norm();
        if n > 0.1 && n <= 1.0 {
            break v / n;
        }
    };
    let angle = rng.random_range(0.0..=config.residual_rotation_deg as f32).to_radians();
    let t = config.residual_translation as f32;
    let shift = if t > 0.0 {
        Vector3::new(rng.random_range(-t..=t), rng.random_range(-t..=t), rng.random_range(-t..=t))
    } else {
        Vector3::zeros()
    };
    Some(Isometry3::new(shift, axis * angle))
}

/// What a step drew for each pair of its batch (entries missing from `true_flow` and
/// `residuals`: off).
#[derive(Debug, Clone, Copy)]
pub struct Draws<'a> {
    /// The augmentation rotation of each pair.
    pub rotations: &'a [Matrix3],
    /// Which pairs feed the segmentation module the true flow ([`fed_true_flow`]).
    pub true_flow: &'a [bool],
    /// Which pairs are residual pairs, with their perturbation ([`residual`]).
    pub residuals: &'a [Option<Isometry3>],
}

/// The loss of a batch, its terms, the gradients and the time of each phase (the optimiser's
/// left at zero, for the caller): the whole batch at once, or split
/// into `replicas` equal shards run on their own threads, each on a replica of the
/// network whose parameters are fresh autodiff leaves (so the shards' graphs stay
/// apart), each shard's loss weighted by its share of the batch, and the gradients summed
/// in shard order (the same sum whatever the machine's thread count).
pub fn batch_gradients(
    net: &PartInductionNet,
    config: &TrainConfig,
    device: &Device,
    pairs: &[Pair],
    draws: Draws<'_>,
    stage: u8,
) -> Result<(f32, LossTerms, GradientsParams, StepPhases), SamplingError> {
    let Draws { rotations, true_flow, residuals } = draws;
    let options = BatchOptions { target: config.matching_target };
    let shards = config.replicas.clamp(1, pairs.len().max(1));
    // One shard: its batch, forward pass and loss, and backward pass (the loss scaled by
    // `share`), each timed.
    let run = |net: &PartInductionNet,
               pairs: &[Pair],
               rotations: &[Matrix3],
               (marks, residuals): (&[bool], &[Option<Isometry3>]),
               share: f32| {
        let mut phases = StepPhases::default();
        let clock = Instant::now();
        let batch =
            TrainingBatch::with(pairs, rotations, residuals, options, &config.network, device)?;
        phases.batch = clock.elapsed().as_secs_f64();
        let clock = Instant::now();
        let (loss, terms) = stage_loss(net, &batch, stage, &Objective::of(config), marks)?;
        let value = loss.clone().into_scalar::<f32>();
        phases.forward = clock.elapsed().as_secs_f64();
        let clock = Instant::now();
        let grads = GradientsParams::from_grads((loss * share).backward(), net);
        phases.backward = clock.elapsed().as_secs_f64();
        Ok::<_, SamplingError>((value, terms, grads, phases))
    };
    if shards == 1 {
        return run(net, pairs, rotations, (true_flow, residuals), 1.0);
    }
    let size = pairs.len().div_ceil(shards);
    let jobs: Vec<_> = pairs
        .chunks(size)
        .zip(rotations.chunks(size))
        .enumerate()
        .map(|(k, (chunk, rots))| {
            let marks = true_flow.get(k * size..).unwrap_or(&[]);
            let moved = residuals.get(k * size..).unwrap_or(&[]);
            (net.clone().map(&mut FreshLeaves), chunk, rots, (marks, moved))
        })
        .collect();
    // The shards run on long-lived threads: a thread that exits makes the allocator hand its
    // memory back to the kernel, and the next step would page-fault it in again.
    type Shard = Result<(f32, LossTerms, GradientsParams, StepPhases), SamplingError>;
    let results: Vec<Shard> = replica_pool().install(|| {
        jobs.into_par_iter()
            .map(|(replica, chunk, rots, marks)| {
                let share = chunk.len() as f32 / pairs.len() as f32;
                let (value, terms, grads, phases) = run(&replica, chunk, rots, marks, share)?;
                Ok((value * share, terms.scaled(share), grads, phases))
            })
            .collect()
    });
    let mut accumulator = GradientsAccumulator::<PartInductionNet>::new();
    let (mut value, mut terms, mut phases) = (0.0, LossTerms::default(), StepPhases::default());
    for result in results {
        let (v, t, grads, p) = result?;
        value += v;
        terms = terms.plus(&t);
        phases = phases.max(p);
        accumulator.accumulate(net, grads);
    }
    Ok((value, terms, accumulator.grads(), phases))
}

/// The threads that run a step's shards: one per core (at least two), kept for the process's
/// life. Results do not depend on their number: each shard is computed on one thread and the
/// shards' gradients are summed in shard order.
fn replica_pool() -> &'static rayon::ThreadPool {
    static POOL: std::sync::OnceLock<rayon::ThreadPool> = std::sync::OnceLock::new();
    POOL.get_or_init(|| {
        let threads = std::thread::available_parallelism().map_or(2, usize::from).max(2);
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .thread_name(|i| format!("replica-{i}"))
            .build()
            .expect("the replica threads start")
    })
}

/// Maps every parameter to a new autodiff leaf holding the same values (same parameter id),
/// for a replica whose graph must not share nodes with another thread's.
struct FreshLeaves;

impl ModuleMapper for FreshLeaves {
    fn map_float<const D: usize>(&mut self, param: Param<Tensor<D>>) -> Param<Tensor<D>> {
        param.map(|t| {
            let grad = t.is_require_grad();
            let fresh = t.detach();
            if grad {
                fresh.require_grad()
            } else {
                fresh
            }
        })
    }
}
