//! Training settings ([`TrainConfig`], with the network's sizes in its `network` table),
//! read from TOML (`model/configs/<name>.toml`).
//!
//! Three configs ship with the crate and are built in by name: `paper` (the sizes of the
//! authors' release), `cpu` (narrower layers and smaller subsets, for
//! training on a laptop-class CPU) and `tiny` (for tests).

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::network::config::invalid;
pub use crate::network::config::{ConfigError, NetworkConfig};
pub use crate::network::NetModule;
pub use crate::train::batch::MatchingTarget;

/// Points of P and Q per training pair, and how the trainer feeds and schedules them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TrainConfig {
    /// Config name, used for output folders.
    pub name: String,
    /// Points per cloud N of the training and validation pairs.
    pub points: u32,
    /// Pairs per optimiser step.
    pub batch: usize,
    /// Adam's initial learning rate.
    pub learning_rate: f64,
    /// How the learning rate moves from `learning_rate` towards `min_learning_rate`:
    /// `step` (the default; every `decay_every_pairs` pairs it is multiplied by `decay`, over
    /// the whole run) or `cosine` (in every stage afresh: a linear warm-up over
    /// `warmup_pairs`, then half a cosine down to the floor at the stage's end).
    #[serde(default)]
    pub schedule: Schedule,
    /// Pairs of linear warm-up at the start of every stage (`cosine` only).
    #[serde(default)]
    pub warmup_pairs: u64,
    /// Factor applied to the learning rate every `decay_every_pairs` pairs (`step` only).
    #[serde(default = "no_decay")]
    pub decay: f64,
    /// Pairs between learning-rate decays (`step` only).
    #[serde(default = "never", skip_serializing_if = "is_never")]
    pub decay_every_pairs: u64,
    /// Smallest learning rate.
    pub min_learning_rate: f64,
    /// Pairs of stage 1 (correspondence and flow).
    pub stage1_pairs: u64,
    /// Pairs of stage 2 (hypotheses and support, on ground-truth flow).
    pub stage2_pairs: u64,
    /// Pairs of stage 3 (every loss, end to end).
    pub stage3_pairs: u64,
    /// Largest norm of each parameter's gradient; larger ones are scaled down (burn's
    /// per-parameter norm clipping), which keeps the Hungarian-matched segment loss from
    /// throwing training off when its matching switches.
    pub clip_gradient_norm: f32,
    /// Whether stage 3 back-propagates the segmentation losses into the flow and
    /// correspondence modules (the paper) or feeds the segmentation module a detached flow
    /// (the authors' release, which freezes the earlier modules; steadier on small batches).
    pub end_to_end: bool,
    /// Whether stage 2 stops the hypotheses' gradient at the support module's input, so
    /// the support loss trains the support module alone and the motion loss alone trains
    /// the hypothesis generator (the release's `tf.stop_gradient(pred_trans)`); false (the
    /// default) lets the support loss train the hypotheses too.
    #[serde(default)]
    pub stage2_detach_hypotheses: bool,
    /// Whether stage 3 trains the RPEN alone, on hypotheses and supports computed as
    /// constants, with the segment and continuation losses only (the release); false (the
    /// default) also trains the hypotheses and support with their stage-2 losses.
    #[serde(default)]
    pub stage3_rpen_only: bool,
    /// Whether the motion loss weighs every point's hypothesis equally, averaging its error
    /// over the points of its part (the release's row normalisation, so a part weighs as
    /// its point count), instead of averaging over all same-part point pairs (false, the
    /// default, where a part weighs as its point count squared).
    #[serde(default)]
    pub motion_loss_per_row: bool,
    /// Weight of the support loss `L_e` (the paper's λ_e, 0.5 by default; the release
    /// adds it with weight 1).
    #[serde(default = "half")]
    pub support_weight: f32,
    /// Adam's ε (1e-5 by default, burn's; TensorFlow's is 1e-8).
    #[serde(default = "burn_epsilon")]
    pub adam_epsilon: f32,
    /// Share of stage 3's pairs, drawn per pair from the seed, whose segmentation module is
    /// fed the ground-truth flow instead of the network's (0, the default: the network's
    /// flow for every pair, as in the paper). Mixing in the true flow keeps the module's
    /// training on clean motions from stage 2 while it adapts to the predicted flow.
    #[serde(default)]
    pub stage3_true_flow: f64,
    /// Weights a new run starts from instead of its seeded initialisation: a burn record of
    /// the same network sizes, e.g. `model/weights/cpu/model.bpk` to fine-tune the shipped
    /// network (with `stage1_pairs = 0` and so on). A resumed run takes its weights from the
    /// checkpoint and never reads this file again.
    #[serde(default)]
    pub init_weights: Option<PathBuf>,
    /// The modules taken from `init_weights`; the others start from the seeded
    /// initialisation (e.g. `["correspondence", "flow"]` to retrain the segmentation
    /// module from scratch on a trained flow). Empty (the default): every module.
    #[serde(default)]
    pub init_modules: Vec<NetModule>,
    /// Largest angle of the random rotation applied to both clouds of a training pair,
    /// degrees (180: any rotation).
    pub augment_rotation_deg: f64,
    /// Scanned pairs (SF2P and SP2P in turn, from new viewpoints) the stream adds after
    /// each full pair; the paper's mix is 5, and 0 (the default) trains on full shapes only.
    #[serde(default)]
    pub scanned_per_pair: u32,
    /// The matching loss's target: the nearest point of Q's subset of the same part
    /// (`same-part`, the default) or the nearest whatever its part (`nearest`, the release).
    #[serde(default, skip_serializing_if = "is_default")]
    pub matching_target: MatchingTarget,
    /// Whether the stream gives each cloud of a pair its own global pose (true, the default:
    /// a rotation of up to 15° and a translation each, so P and Q differ by a relative pose
    /// besides the articulation) or none (false: the release's stage-1 pairs, whose clouds
    /// differ by the articulation alone before the shared augmentation rotation). Each cloud
    /// is still normalised on its own.
    #[serde(default = "yes", skip_serializing_if = "is_true")]
    pub relative_pose: bool,
    /// Share of stage 1's pairs, drawn per pair from the seed, turned into residual pairs: P
    /// replaced by P moved by its true part motions and then by a small random rigid motion
    /// (rotation up to `residual_rotation_deg` about a random axis through the origin,
    /// translation up to `residual_translation` along each axis), so the flow to learn is
    /// what the iterations leave (0, the default: none).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub residual_pairs: f64,
    /// Largest rotation of a residual pair's perturbation, degrees.
    #[serde(default = "residual_rotation", skip_serializing_if = "is_residual_rotation")]
    pub residual_rotation_deg: f64,
    /// Largest translation of a residual pair's perturbation along each axis, normalised
    /// units.
    #[serde(default = "residual_translation", skip_serializing_if = "is_residual_translation")]
    pub residual_translation: f64,
    /// Seed of the training stream and the augmentation.
    pub seed: u64,
    /// Pairs in the fixed validation set (validation categories; a quarter each of SF2P and
    /// SP2P pairs when the stream trains on scans, see [`crate::train::validation::validation_pairs`]).
    pub validation_pairs: u32,
    /// Data-parallel replicas of a step: the batch is split into this many equal shards,
    /// each run forward and backward on its own thread, and their gradients are summed (each
    /// shard's loss weighted by its share of the batch). 1 runs the whole batch as one.
    /// Results depend on this number, never on the machine's thread count.
    #[serde(default = "one")]
    pub replicas: usize,
    /// Pairs between validations.
    pub validate_every_pairs: u64,
    /// Minutes between checkpoints.
    pub checkpoint_minutes: f64,
    /// Network sizes.
    pub network: NetworkConfig,
}

/// A learning-rate schedule (see [`TrainConfig::learning_rate_at`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Schedule {
    /// Multiply by `decay` every `decay_every_pairs` pairs, down to the floor.
    #[default]
    Step,
    /// Per stage: linear warm-up over `warmup_pairs`, then a half cosine down to the floor.
    Cosine,
}

fn yes() -> bool {
    true
}

fn is_true(v: &bool) -> bool {
    *v
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

fn is_default<T: Default + PartialEq>(v: &T) -> bool {
    *v == T::default()
}

fn residual_rotation() -> f64 {
    5.0
}

fn is_residual_rotation(v: &f64) -> bool {
    *v == residual_rotation()
}

fn residual_translation() -> f64 {
    0.02
}

fn is_residual_translation(v: &f64) -> bool {
    *v == residual_translation()
}

fn half() -> f32 {
    0.5
}

fn burn_epsilon() -> f32 {
    1e-5
}

fn no_decay() -> f64 {
    1.0
}

fn never() -> u64 {
    u64::MAX
}

fn is_never(v: &u64) -> bool {
    *v == never()
}

fn one() -> usize {
    1
}

/// The configs built into the crate, by name.
pub const BUILT_IN: [(&str, &str); 3] = [
    ("paper", include_str!("../../configs/paper.toml")),
    ("cpu", include_str!("../../configs/cpu.toml")),
    ("tiny", include_str!("../../configs/tiny.toml")),
];

impl TrainConfig {
    /// Parses and checks a config from TOML text; `origin` names it in errors.
    pub fn from_toml(text: &str, origin: &str) -> Result<Self, ConfigError> {
        let config: Self = toml::from_str(text)
            .map_err(|e| ConfigError::Parse { path: origin.to_string(), source: Box::new(e) })?;
        config.validate()?;
        Ok(config)
    }

    /// Reads a config file, or a built-in config by name (`paper`, `cpu`, `tiny`).
    pub fn load(path_or_name: &str) -> Result<Self, ConfigError> {
        if let Some((name, text)) = BUILT_IN.iter().find(|(n, _)| *n == path_or_name) {
            return Self::from_toml(text, name);
        }
        let text = std::fs::read_to_string(Path::new(path_or_name))
            .map_err(|source| ConfigError::Read { path: path_or_name.to_string(), source })?;
        Self::from_toml(&text, path_or_name)
    }

    /// The config as TOML text that [`TrainConfig::from_toml`] reads back equal (what a
    /// weights folder's `config.toml` holds when the trainer writes it).
    pub fn to_toml(&self) -> Result<String, toml::ser::Error> {
        toml::to_string(self)
    }

    /// A built-in config by name; panics on an unknown name (for tests and examples).
    pub fn built_in(name: &str) -> Self {
        let (_, text) = BUILT_IN.iter().find(|(n, _)| *n == name).expect("a built-in config");
        Self::from_toml(text, name).expect("built-in configs are valid")
    }

    /// Checks every field.
    pub fn validate(&self) -> Result<(), ConfigError> {
        if self.name.is_empty()
            || !self.name.chars().all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
        {
            return Err(invalid("name", "must be non-empty ASCII letters, digits, '-' or '_'"));
        }
        if (self.points as usize) < self.network.corr_points {
            return Err(invalid("points", "must be at least network.corr_points"));
        }
        if self.batch == 0 {
            return Err(invalid("batch", "must be at least 1"));
        }
        if self.replicas == 0 || !self.batch.is_multiple_of(self.replicas) {
            return Err(invalid("replicas", "must be at least 1 and divide batch"));
        }
        for (field, v) in [
            ("learning_rate", self.learning_rate),
            ("decay", self.decay),
            ("min_learning_rate", self.min_learning_rate),
            ("checkpoint_minutes", self.checkpoint_minutes),
            ("clip_gradient_norm", f64::from(self.clip_gradient_norm)),
            ("support_weight", f64::from(self.support_weight)),
            ("adam_epsilon", f64::from(self.adam_epsilon)),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(invalid(field, "must be a positive number"));
            }
        }
        if !(0.0..=180.0).contains(&self.augment_rotation_deg) {
            return Err(invalid("augment_rotation_deg", "must be in [0, 180]"));
        }
        if !(0.0..=1.0).contains(&self.stage3_true_flow) {
            return Err(invalid("stage3_true_flow", "must be in [0, 1]"));
        }
        if !(0.0..=1.0).contains(&self.residual_pairs) {
            return Err(invalid("residual_pairs", "must be in [0, 1]"));
        }
        if !(0.0..=180.0).contains(&self.residual_rotation_deg) {
            return Err(invalid("residual_rotation_deg", "must be in [0, 180]"));
        }
        if !(self.residual_translation >= 0.0 && self.residual_translation.is_finite()) {
            return Err(invalid("residual_translation", "must be finite and non-negative"));
        }
        if self.decay_every_pairs == 0 || self.validate_every_pairs == 0 {
            return Err(invalid("decay_every_pairs", "pair counts must be positive"));
        }
        if !self.init_modules.is_empty() && self.init_weights.is_none() {
            return Err(invalid("init_modules", "needs init_weights to take the modules from"));
        }
        if self.stage1_pairs + self.stage2_pairs + self.stage3_pairs == 0 {
            return Err(invalid("stage3_pairs", "at least one stage needs pairs"));
        }
        self.network.validate()
    }

    /// Total pairs of all stages.
    pub fn total_pairs(&self) -> u64 {
        self.stage1_pairs + self.stage2_pairs + self.stage3_pairs
    }

    /// The training stage (1, 2 or 3) after `pairs` training pairs.
    pub fn stage_at(&self, pairs: u64) -> u8 {
        if pairs < self.stage1_pairs {
            1
        } else if pairs < self.stage1_pairs + self.stage2_pairs {
            2
        } else {
            3
        }
    }

    /// The first pair and the length of the stage that pair `pairs` belongs to.
    fn stage_span(&self, pairs: u64) -> (u64, u64) {
        match self.stage_at(pairs) {
            1 => (0, self.stage1_pairs),
            2 => (self.stage1_pairs, self.stage2_pairs),
            _ => (self.stage1_pairs + self.stage2_pairs, self.stage3_pairs),
        }
    }

    /// The learning rate of the step that starts after `pairs` training pairs.
    pub fn learning_rate_at(&self, pairs: u64) -> f64 {
        let (peak, floor) = (self.learning_rate, self.min_learning_rate);
        match self.schedule {
            Schedule::Step => {
                let decays = i32::try_from(pairs / self.decay_every_pairs).unwrap_or(i32::MAX);
                (peak * self.decay.powi(decays)).max(floor)
            }
            Schedule::Cosine => {
                let (start, length) = self.stage_span(pairs);
                let t = pairs - start;
                let warmup = self.warmup_pairs.min(length);
                if t < warmup {
                    // From peak / warmup at the first step up to the peak.
                    return (peak * (t + 1) as f64 / warmup as f64).max(floor.min(peak));
                }
                let progress = (t - warmup) as f64 / (length - warmup).max(1) as f64;
                floor + (peak - floor) * 0.5 * (1.0 + (std::f64::consts::PI * progress).cos())
            }
        }
    }
}

#[cfg(test)]
mod tests;
