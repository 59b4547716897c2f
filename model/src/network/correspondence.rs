//! The correspondence proposal module: shared PointNet++ features on P and Q, a pairwise MLP
//! giving a matching logit for every (p_i, q_j), and a correspondence mask from the pair
//! features pooled over Q.

use burn::nn::Linear;
use burn::prelude::*;
use burn::tensor::activation;

use crate::network::backbone::Backbone;
use crate::network::config::NetworkConfig;
use crate::network::input::{gather_points, PairTensors};
use crate::network::mlp::{relu_layer, Head, SharedMlp};
use crate::network::norm::linear;
use crate::network::pool::max_pool;
use crate::network::sampling::SamplingError;

/// What the module outputs for a batch of pairs.
#[derive(Debug, Clone)]
pub struct Correspondence {
    /// Matching logits `c_ij`, `[batch, m, m]` (softmax over j gives M).
    pub logits: Tensor<3>,
    /// Correspondence-mask logits per point of P, `[batch, m]`.
    pub mask_logits: Tensor<2>,
}

impl Correspondence {
    /// The refined matching matrix `M̂ = softmax_j(c_ij) · sigmoid(c_i)`, `[batch, m, m]`.
    pub fn refined(&self) -> Tensor<3> {
        self.refined_with(false)
    }

    /// [`Correspondence::refined`], with the mask as a constant when `mask_detached` (the
    /// release's `tf.stop_gradient` on the visibility probability).
    pub fn refined_with(&self, mask_detached: bool) -> Tensor<3> {
        let mask = activation::sigmoid(self.mask_logits.clone());
        let mask = if mask_detached { mask.detach() } else { mask };
        activation::softmax(self.logits.clone(), 2) * mask.unsqueeze_dim::<3>(2)
    }
}

/// The correspondence proposal module.
#[derive(Module, Debug)]
pub struct CorrespondenceModule {
    features: Backbone,
    pair_p: Linear,
    pair_q: Linear,
    pair: SharedMlp,
    score: Head,
    mask: Head,
    /// The backbone runs on the whole clouds (`features_on_cloud`).
    #[module(skip)]
    on_cloud: bool,
}

impl CorrespondenceModule {
    /// The module with `config`'s sizes.
    pub fn new(config: &NetworkConfig, device: &Device) -> Self {
        let first = config.pair[0];
        let pair = SharedMlp::with_norm(first, &config.pair[1..], config.pair_norm, device);
        let width = pair.output(first);
        Self {
            features: config.features.init(0, config.feature_dim, false, device),
            // The first pair layer on concat(u_i, u_j) is W_p u_i + W_q u_j: computed per
            // point, then broadcast over pairs.
            pair_p: relu_layer(config.feature_dim, first).init(device),
            pair_q: relu_layer(config.feature_dim, first).with_bias(false).init(device),
            pair,
            score: Head::with_norm(width, &config.score, 1, config.pair_norm, device),
            mask: Head::new(width, &config.mask, 1, device),
            on_cloud: config.features_on_cloud,
        }
    }

    /// Whether the module reads the whole clouds of [`PairTensors`].
    pub fn on_cloud(&self) -> bool {
        self.on_cloud
    }

    /// The features are computed on the subsets, or on the whole clouds and gathered at the
    /// subsets (`features_on_cloud`; `input.clouds` must then be present).
    ///
    /// # Shapes
    /// `input.p, input.q: [batch, m, 3]` -> logits `[batch, m, m]`, mask logits `[batch, m]`
    pub fn forward(&self, input: &PairTensors) -> Result<Correspondence, SamplingError> {
        let [batch, m, _] = input.p.dims();
        let (u_p, u_q) = match (&input.clouds, self.on_cloud) {
            (Some(clouds), true) => {
                let both = self
                    .features
                    .forward(Tensor::cat(vec![clouds.p.clone(), clouds.q.clone()], 0), None)?; // [2 batch, n, d]
                let f_p = both.clone().narrow(0, 0, batch);
                let f_q = both.narrow(0, batch, batch);
                (
                    gather_points(f_p, clouds.p_subset.clone()),
                    gather_points(f_q, clouds.q_subset.clone()),
                )
            }
            (None, true) => return Err(SamplingError::NoClouds),
            _ => {
                let both = self
                    .features
                    .forward(Tensor::cat(vec![input.p.clone(), input.q.clone()], 0), None)?; // [2 batch, m, d]
                (both.clone().narrow(0, 0, batch), both.narrow(0, batch, batch))
            }
        };
        let a = linear(&self.pair_p, u_p).unsqueeze_dim::<4>(2); // [batch, m, 1, w]
        let b = linear(&self.pair_q, u_q).unsqueeze_dim::<4>(1); // [batch, 1, m, w]
        let h = self.pair.forward(activation::relu(a + b)); // [batch, m, m, w]
        let logits = self.score.forward(h.clone()).reshape([batch, m, m]);
        let mask_logits = self.mask.forward(max_pool(h)).reshape([batch, m]);
        Ok(Correspondence { logits, mask_logits })
    }
}
