//! Support prediction: for hypothesis i and point j, how well the rigid motion of i explains
//! the flow at j, as a logit (the support matrix S, rows hypotheses, columns points). A
//! PointNetS per row: local features of (flow difference, relative position), pooled into a
//! row feature, joined back to each entry.

use burn::prelude::*;

use crate::network::config::NetworkConfig;
use crate::network::mlp::{Head, SharedMlp};
use crate::network::pool::max_pool;
use crate::network::segmentation::hypotheses::Hypotheses;

/// The support network.
#[derive(Module, Debug)]
pub struct SupportModule {
    local: SharedMlp,
    global: SharedMlp,
    head: Head,
}

impl SupportModule {
    /// The module with `config`'s sizes.
    pub fn new(config: &NetworkConfig, device: &Device) -> Self {
        let local = SharedMlp::new(6, &config.support_local, device);
        let l = local.output(6);
        let global = SharedMlp::new(l, &config.support_global, device);
        let g = global.output(l);
        Self { local, global, head: Head::new(l + g, &config.support_head, 1, device) }
    }

    /// Support logits of every point under every hypothesis.
    ///
    /// # Shapes
    /// `p, flow: [batch, s, 3]` -> `[batch, s (hypotheses), s (points)]`
    pub fn forward(&self, p: Tensor<3>, flow: Tensor<3>, hypotheses: &Hypotheses) -> Tensor<3> {
        let [batch, s, _] = p.dims();
        let x = p.clone().swap_dims(1, 2).unsqueeze_dim::<4>(1); // [batch, 1, 3, s]
        let moved = hypotheses.rotations.clone().matmul(x).swap_dims(2, 3); // [batch, s, s, 3]
        let moved = moved + hypotheses.translations.clone().unsqueeze_dim::<4>(2);
        let points = p.clone().unsqueeze_dim::<4>(1); // [batch, 1, s, 3]
        let difference = moved - points.clone() - flow.unsqueeze_dim::<4>(1);
        let relative = points - p.unsqueeze_dim::<4>(2); // [batch, s, s, 3]
        let local = self.local.forward(Tensor::cat(vec![difference, relative], 3)); // [batch, s, s, l]
        let global = self.global.forward(max_pool(local.clone())); // [batch, s, 1, g]
        let g = global.dims()[3];
        let joined = Tensor::cat(vec![local, global.expand([batch, s, s, g])], 3);
        self.head.forward(joined).reshape([batch, s, s])
    }
}
