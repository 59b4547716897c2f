//! The flow module (PairNet): per pair (q_j - p_i, matching probability) through a PointNet
//! pooled over Q, then a PointNet++ on P giving the deformation flow: on P's subset, or (with
//! `flow_on_cloud`, as the authors' release) carried from the subset to every point of P by
//! `1/d²` interpolation of its features and a head there.

use burn::prelude::*;

use crate::network::backbone::Backbone;
use crate::network::config::NetworkConfig;
use crate::network::input::PairTensors;
use crate::network::mlp::{Head, SharedMlp};
use crate::network::pointnet::interpolate_features;
use crate::network::pool::max_pool;
use crate::network::sampling::SamplingError;

/// Hidden widths of the head on every point of P (`flow_on_cloud`): the release's last
/// layers before its 3 outputs.
const CLOUD_HEAD: [usize; 1] = [64];

/// Channels the flow backbone hands to every point of P (`flow_on_cloud`).
const CLOUD_FEATURES: usize = 64;

/// The flow module.
#[derive(Module, Debug)]
pub struct FlowModule {
    pair: SharedMlp,
    points: Backbone,
    /// The head on every point of P (`flow_on_cloud`); none on the subset.
    cloud: Option<Head>,
    #[module(skip)]
    scaled: bool,
    #[module(skip)]
    mask_detached: bool,
}

impl FlowModule {
    /// The module with `config`'s sizes.
    pub fn new(config: &NetworkConfig, device: &Device) -> Self {
        let pair = SharedMlp::with_norm(4, &config.flow_pair, config.pair_norm, device);
        let width = pair.output(4);
        let (points, cloud) = if config.flow_on_cloud {
            (
                config.flow.init(width, CLOUD_FEATURES, false, device),
                Some(Head::new(CLOUD_FEATURES, &CLOUD_HEAD, 3, device)),
            )
        } else {
            (config.flow.init(width, 3, true, device), None)
        };
        Self {
            pair,
            points,
            cloud,
            scaled: config.flow_scaled_probabilities,
            mask_detached: config.flow_mask_detached,
        }
    }

    /// Whether the flow comes out on every point of P (`flow_on_cloud`) rather than on its
    /// subset.
    pub fn on_cloud(&self) -> bool {
        self.cloud.is_some()
    }

    /// Whether the correspondence mask enters as a constant (`flow_mask_detached`).
    pub fn mask_detached(&self) -> bool {
        self.mask_detached
    }

    /// The flow on P from the refined matching matrix. With `flow_scaled_probabilities` the
    /// matching probabilities are multiplied by `m` so that a uniform row has entries 1 (a
    /// departure from the release, which feeds them raw; it keeps the input scale
    /// independent of the subset size).
    ///
    /// # Shapes
    /// `input.p, input.q: [batch, m, 3]`, `matching: [batch, m, m]` -> `[batch, m, 3]`, or
    /// `[batch, n, 3]` on every point of P with `flow_on_cloud` (`input.clouds` present)
    pub fn forward(
        &self,
        input: &PairTensors,
        matching: Tensor<3>,
    ) -> Result<Tensor<3>, SamplingError> {
        let (p, q) = (input.p.clone(), input.q.clone());
        let m = p.dims()[1];
        let offsets = q.unsqueeze_dim::<4>(1) - p.clone().unsqueeze_dim::<4>(2); // [batch, m, m, 3]
        let scale = if self.scaled { m as f32 } else { 1.0 };
        let input_pairs = Tensor::cat(vec![offsets, matching.unsqueeze_dim::<4>(3) * scale], 3);
        let pooled = max_pool(self.pair.forward(input_pairs)).squeeze_dim::<3>(2); // [batch, m, w]
        let out = self.points.forward(p.clone(), Some(pooled))?;
        match &self.cloud {
            None => Ok(out),
            Some(head) => {
                let clouds = input.clouds.as_ref().ok_or(SamplingError::NoClouds)?;
                let dense = interpolate_features(&clouds.p, &p, out, 2)?; // [batch, n, c]
                Ok(head.forward(dense))
            }
        }
    }
}
