//! The flow module (PairNet): per pair (q_j - p_i, matching probability) through a PointNet
//! pooled over Q, then a PointNet++ on P giving the deformation flow.

use burn::prelude::*;

use crate::network::backbone::Backbone;
use crate::network::config::NetworkConfig;
use crate::network::pointnet::SharedMlp;
use crate::network::pool::max_pool;
use crate::network::sampling::SamplingError;

/// The flow module.
#[derive(Module, Debug)]
pub struct FlowModule {
    pair: SharedMlp,
    points: Backbone,
    #[module(skip)]
    scaled: bool,
}

impl FlowModule {
    /// The module with `config`'s sizes.
    pub fn new(config: &NetworkConfig, device: &Device) -> Self {
        let pair = SharedMlp::new(4, &config.flow_pair, device);
        let width = pair.output(4);
        Self {
            pair,
            points: config.flow.init(width, 3, true, device),
            scaled: config.flow_scaled_probabilities,
        }
    }

    /// The flow on P from the refined matching matrix. With `flow_scaled_probabilities` the
    /// matching probabilities are multiplied by `m` so that a uniform row has entries 1 (a
    /// departure from the release, which feeds them raw; it keeps the input scale
    /// independent of the subset size).
    ///
    /// # Shapes
    /// `p, q: [batch, m, 3]`, `matching: [batch, m, m]` -> `[batch, m, 3]`
    pub fn forward(
        &self,
        p: Tensor<3>,
        q: Tensor<3>,
        matching: Tensor<3>,
    ) -> Result<Tensor<3>, SamplingError> {
        let m = p.dims()[1];
        let offsets = q.unsqueeze_dim::<4>(1) - p.clone().unsqueeze_dim::<4>(2); // [batch, m, m, 3]
        let scale = if self.scaled { m as f32 } else { 1.0 };
        let input = Tensor::cat(vec![offsets, matching.unsqueeze_dim::<4>(3) * scale], 3);
        let pooled = max_pool(self.pair.forward(input)).squeeze_dim::<3>(2); // [batch, m, w]
        self.points.forward(p, Some(pooled))
    }
}
