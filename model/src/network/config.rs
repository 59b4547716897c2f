//! The network's sizes ([`NetworkConfig`], the `[network]` table of a training config) and
//! what is wrong with a config ([`ConfigError`]).

use serde::{Deserialize, Serialize};

use crate::network::backbone::BackboneConfig;

/// Sizes of the whole network.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NetworkConfig {
    /// Farthest-point subset of each cloud the correspondence and flow modules work on.
    pub corr_points: usize,
    /// Farthest-point subset of P (a prefix of the correspondence subset) the segmentation
    /// module works on.
    pub seg_points: usize,
    /// Most segments the recurrent part extraction network produces.
    pub max_segments: usize,
    /// Channels of the per-point features of the correspondence module.
    pub feature_dim: usize,
    /// Feature extractor, shared by P and Q.
    pub features: BackboneConfig,
    /// Pairwise MLP widths on (feature of p_i, feature of q_j).
    pub pair: Vec<usize>,
    /// Hidden widths of the matching-score head (then one logit per pair).
    pub score: Vec<usize>,
    /// Hidden widths of the correspondence-mask head on the pair features pooled over Q.
    pub mask: Vec<usize>,
    /// PointNet widths on (q_j - p_i, matching probability) before pooling over Q.
    pub flow_pair: Vec<usize>,
    /// PointNet++ on P's positions and pooled pair features, ending in the flow.
    pub flow: BackboneConfig,
    /// PointNet++ on P's centred positions and flow, ending in 12 motion parameters.
    pub hypothesis: BackboneConfig,
    /// Support network: per (hypothesis, point) MLP widths before pooling.
    pub support_local: Vec<usize>,
    /// Support network: MLP widths on the pooled feature of each hypothesis.
    pub support_global: Vec<usize>,
    /// Support network: hidden widths of the head on (local, global), then one logit.
    pub support_head: Vec<usize>,
    /// RPEN: PointNet widths on (support, memory) per hypothesis row before pooling.
    pub rpen_pair: Vec<usize>,
    /// RPEN: widths of the global MLP over hypotheses (positions and row features).
    pub rpen_global: Vec<usize>,
    /// RPEN: widths of the per-hypothesis state `z_t` from (row feature, global).
    pub rpen_state: Vec<usize>,
    /// RPEN: hidden widths of the continuation and hypothesis-weight heads.
    pub rpen_head: Vec<usize>,
    /// Whether each hypothesis's `R̂ + I` is projected onto the rotations (true, the
    /// default, as the paper describes) or used as it is, a general linear map (false, the
    /// authors' release). P and Q are normalised separately, so a part's true motion is a
    /// similarity, which only the unprojected form fits exactly.
    #[serde(default = "yes")]
    pub hypothesis_projection: bool,
    /// Whether the flow module multiplies the matching probabilities by the subset size
    /// (true, the default: a uniform row has entries 1) or takes them as they are (false,
    /// the authors' release).
    #[serde(default = "yes")]
    pub flow_scaled_probabilities: bool,
    /// Whether the correspondence module's feature backbone runs on every point of both
    /// clouds, its features then gathered at the correspondence subsets (true: the authors'
    /// release), or on the subsets alone (false, the default).
    #[serde(default, skip_serializing_if = "is_false")]
    pub features_on_cloud: bool,
    /// Whether the flow module ends on every point of P (true: the release; its backbone's
    /// features are carried from the subset to every point by 3-NN weights `1/d²`, then a
    /// head gives the flow, and stage 1's flow loss covers every point of P) or on the
    /// subset (false, the default: the flow is predicted on the subset, interpolated by
    /// `1/d` outside the network, and the loss covers the subset's visible points).
    #[serde(default, skip_serializing_if = "is_false")]
    pub flow_on_cloud: bool,
    /// The normalisation of the pair MLPs (the correspondence module's pair MLP and score
    /// head, the flow module's pair MLP): see [`PairNorm`].
    #[serde(default, skip_serializing_if = "is_default")]
    pub pair_norm: PairNorm,
    /// Whether the correspondence mask reaches the flow module as a constant (true: the
    /// release's `tf.stop_gradient`, so the flow loss does not train the mask) or with its
    /// gradient (false, the default).
    #[serde(default, skip_serializing_if = "is_false")]
    pub flow_mask_detached: bool,
}

/// How the pair MLPs normalise each layer's output.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum PairNorm {
    /// Layer normalisation of every entry's channels on their own (the default): after it
    /// an entry's size no longer tells it from the others.
    #[default]
    Layer,
    /// Each channel normalised by its mean and variance over one pair's `m × m` entries
    /// (an instance norm of the pair grid): entries keep their relative size, as the
    /// release's batch normalisation (a fixed per-channel affine map at inference) does,
    /// with no running statistics.
    Pair,
}

fn yes() -> bool {
    true
}

fn is_false(v: &bool) -> bool {
    !v
}

fn is_default<T: Default + PartialEq>(v: &T) -> bool {
    *v == T::default()
}

/// What is wrong with a config.
#[derive(Debug, thiserror::Error)]
pub enum ConfigError {
    /// The file could not be read.
    #[error("cannot read config {path}: {source}")]
    Read {
        /// The file.
        path: String,
        /// The I/O error.
        #[source]
        source: std::io::Error,
    },
    /// The file is not valid TOML for a config.
    #[error("config {path} is not a valid training config: {source}")]
    Parse {
        /// The file (or built-in name).
        path: String,
        /// The parser's error, which names the field.
        #[source]
        source: Box<toml::de::Error>,
    },
    /// A value is out of range.
    #[error("config field `{field}`: {problem}")]
    Invalid {
        /// The field.
        field: &'static str,
        /// What is wrong.
        problem: String,
    },
}

pub(crate) fn invalid(field: &'static str, problem: impl Into<String>) -> ConfigError {
    ConfigError::Invalid { field, problem: problem.into() }
}

impl NetworkConfig {
    /// Checks sizes that would otherwise fail deep inside a forward pass.
    pub fn validate(&self) -> Result<(), ConfigError> {
        if self.seg_points == 0 || self.seg_points > self.corr_points {
            return Err(invalid("network.seg_points", "must be in 1..=corr_points"));
        }
        if self.max_segments < 1 {
            return Err(invalid("network.max_segments", "must be at least 1"));
        }
        for (field, widths) in [
            ("network.pair", &self.pair),
            ("network.flow_pair", &self.flow_pair),
            ("network.support_local", &self.support_local),
            ("network.rpen_pair", &self.rpen_pair),
            ("network.rpen_global", &self.rpen_global),
            ("network.rpen_state", &self.rpen_state),
        ] {
            if widths.is_empty() || widths.contains(&0) {
                return Err(invalid(field, "needs at least one layer, all widths positive"));
            }
        }
        for (field, backbone, points) in [
            ("network.features", &self.features, self.corr_points),
            ("network.flow", &self.flow, self.corr_points),
            ("network.hypothesis", &self.hypothesis, self.corr_points),
        ] {
            if backbone.levels.is_empty() {
                return Err(invalid(field, "needs at least one set abstraction level"));
            }
            if backbone.propagation.len() != backbone.levels.len() + 1 {
                return Err(invalid(field, "needs one propagation entry per level, plus one"));
            }
            let mut available = points;
            for level in &backbone.levels {
                if level.centres < 3 || level.centres > available || level.scales.is_empty() {
                    return Err(invalid(
                        field,
                        format!(
                            "level centres must be in 3..={available} (the points it receives) with at least one scale"
                        ),
                    ));
                }
                available = level.centres;
            }
        }
        Ok(())
    }
}
