//! The Recurrent Part Extraction Network: decodes the support matrix into soft segments one
//! step at a time, with a memory of the points already taken and a continuation score.
//!
//! Step t: `z_t = PairNet([S row, e_{t-1}])`, hypothesis weights `s_t = softmax(g(z_t))`,
//! segment `y_t = Sᵀ s_t`, continuation logit `r_t` from `z_t` pooled over hypotheses, memory
//! `e_t = (1 - e_{t-1}) ⊙ y_t + e_{t-1}`.

use burn::prelude::*;
use burn::tensor::activation;

use crate::network::config::NetworkConfig;
use crate::network::mlp::{Head, SharedMlp};
use crate::network::pool::max_pool;

/// What the RPEN outputs for `steps` steps.
#[derive(Debug, Clone)]
pub struct Segments {
    /// Soft segment of every step, `[batch, steps, s]`, entries in `[0, 1]`.
    pub segments: Tensor<3>,
    /// Continuation logit of every step, `[batch, steps]`.
    pub continuation: Tensor<2>,
}

/// The recurrent part extraction network.
#[derive(Module, Debug)]
pub struct RpenModule {
    pair: SharedMlp,
    global: SharedMlp,
    state: SharedMlp,
    continuation: Head,
    weight: Head,
}

impl RpenModule {
    /// The module with `config`'s sizes.
    pub fn new(config: &NetworkConfig, device: &Device) -> Self {
        let pair = SharedMlp::new(2, &config.rpen_pair, device);
        let h = pair.output(2);
        let global = SharedMlp::new(3 + h, &config.rpen_global, device);
        let g = global.output(3 + h);
        let state = SharedMlp::new(h + g, &config.rpen_state, device);
        let z = state.output(h + g);
        Self {
            pair,
            global,
            state,
            continuation: Head::new(z, &config.rpen_head, 1, device),
            weight: Head::new(z, &config.rpen_head, 1, device),
        }
    }

    /// Runs `steps` steps on support probabilities `support` (rows hypotheses).
    ///
    /// # Shapes
    /// `p: [batch, s, 3]`, `support: [batch, s, s]` -> segments `[batch, steps, s]`,
    /// continuation `[batch, steps]`
    pub fn forward(&self, p: Tensor<3>, support: Tensor<3>, steps: usize) -> Segments {
        let [batch, s, _] = support.dims();
        let mut memory = Tensor::<2>::zeros([batch, s], &support.device());
        let (mut segments, mut continuation) = (Vec::new(), Vec::new());
        for _ in 0..steps {
            let e = memory.clone().reshape([batch, 1, s, 1]).expand([batch, s, s, 1]);
            let input = Tensor::cat(vec![support.clone().unsqueeze_dim::<4>(3), e], 3);
            let rows = max_pool(self.pair.forward(input)).squeeze_dim::<3>(2); // [batch, s, h]
            let global =
                max_pool(self.global.forward(Tensor::cat(vec![p.clone(), rows.clone()], 2))); // [batch, 1, g]
            let g = global.dims()[2];
            let z = self.state.forward(Tensor::cat(vec![rows, global.expand([batch, s, g])], 2)); // [batch, s, z]
            continuation.push(self.continuation.forward(max_pool(z.clone())).reshape([batch, 1]));
            let weights = activation::softmax(self.weight.forward(z).reshape([batch, 1, s]), 2);
            let y = weights.matmul(support.clone()).reshape([batch, s]); // [batch, s]
            memory = (memory.clone().neg() + 1.0) * y.clone() + memory;
            segments.push(y.unsqueeze_dim::<3>(1));
        }
        Segments { segments: Tensor::cat(segments, 1), continuation: Tensor::cat(continuation, 1) }
    }
}
