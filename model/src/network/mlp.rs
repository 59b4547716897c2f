//! Shared MLPs (PointNet, Qi et al. 2017): the same `Linear`, norm and ReLU layers applied
//! to every point or pair, and the heads that end them without a ReLU.
//!
//! Departure from the authors' release: no batch normalisation inside the shared MLPs
//! (training here runs on small CPU batches, where its statistics are noisy); layer
//! normalisation, or the per-pair channel norm of [`PairNorm`], stands in.

use burn::nn::{Initializer, LayerNorm, LayerNormConfig, Linear, LinearConfig};
use burn::prelude::*;
use burn::tensor::activation;

use crate::network::config::PairNorm;
use crate::network::norm::{linear, linear_norm_relu, EPSILON};

/// A `Linear` layer that feeds a ReLU, initialised after He et al. (variance `2 / fan_in`)
/// so that activations keep their scale through deep stacks without batch normalisation
/// (burn's default, variance `1 / (3 fan_in)`, shrinks them sixfold per layer, and pair
/// features collapse to constants).
pub fn relu_layer(input: usize, output: usize) -> LinearConfig {
    LinearConfig::new(input, output).with_initializer(Initializer::KaimingUniform {
        gain: std::f64::consts::SQRT_2,
        fan_out_only: false,
    })
}

/// A shared MLP: the same `Linear` + layer norm + ReLU layers applied to every point (or
/// pair).
///
/// Layer normalisation stands in for the release's batch normalisation: without either,
/// features stay small and nearly equal across points, and the matching logits (which must
/// tell points a few hundredths apart) take thousands of steps to leave the uniform
/// solution. Layer norm needs no batch statistics, so training and inference agree.
#[derive(Module, Debug)]
pub struct SharedMlp {
    layers: Vec<Linear>,
    norms: Vec<LayerNorm>,
    /// Normalise over a pair's grid of entries instead of each entry's channels
    /// ([`PairNorm::Pair`]; the parameters are the same, `γ` and `β` per channel).
    #[module(skip)]
    pair_norm: bool,
}

impl SharedMlp {
    /// Layers of `widths` after an input of `input` channels.
    pub fn new(input: usize, widths: &[usize], device: &Device) -> Self {
        Self::with_norm(input, widths, PairNorm::Layer, device)
    }

    /// Like [`SharedMlp::new`] with the normalisation `norm` (which only changes a pair MLP
    /// on `[batch, m, m, channels]` inputs).
    pub fn with_norm(input: usize, widths: &[usize], norm: PairNorm, device: &Device) -> Self {
        let dims = std::iter::once(input).chain(widths.iter().copied());
        let layers =
            dims.clone().zip(widths.iter()).map(|(a, &b)| relu_layer(a, b).init(device)).collect();
        let norms = widths.iter().map(|&w| LayerNormConfig::new(w).init(device)).collect();
        Self { layers, norms, pair_norm: norm == PairNorm::Pair }
    }

    /// Output channels (the input's if there are no layers).
    pub fn output(&self, input: usize) -> usize {
        self.layers.last().map_or(input, |l| l.weight.dims()[1])
    }

    /// Applies every layer to the last dimension.
    ///
    /// # Shapes
    /// `[..., input]` -> `[..., output]`
    pub fn forward<const D: usize>(&self, x: Tensor<D>) -> Tensor<D> {
        if self.pair_norm && D == 4 {
            return self.layers.iter().zip(&self.norms).fold(x, |x, (layer, norm)| {
                activation::relu(pair_normalised(linear(layer, x), norm))
            });
        }
        self.layers
            .iter()
            .zip(&self.norms)
            .fold(x, |x, (layer, norm)| linear_norm_relu(layer, norm, x))
    }
}

/// `γ (y - mean) / sqrt(var + ε) + β` with each channel's mean and variance taken over
/// dimensions 1 and 2 (one pair's `m × m` entries) of `y: [batch, m, m, c]`, as one
/// reduction over the flattened `m²` entries.
fn pair_normalised<const D: usize>(y: Tensor<D>, norm: &LayerNorm) -> Tensor<D> {
    let dims = y.dims();
    let (b, c) = (dims[0], dims[D - 1]);
    let flat: Tensor<3> = y.reshape([b as i32, -1, c as i32]);
    let mean = flat.clone().mean_dim(1);
    let centred = flat - mean;
    let var = (centred.clone() * centred.clone()).mean_dim(1);
    let gamma = norm.gamma.val().reshape([1, 1, c]);
    let scaled = centred * ((var + EPSILON).sqrt().recip() * gamma);
    let out = match &norm.beta {
        Some(beta) => scaled + beta.val().reshape([1, 1, c]),
        None => scaled,
    };
    out.reshape(dims)
}

/// A shared MLP (`Linear` + ReLU layers) ending in one `Linear` layer without activation:
/// the output head of a module (logits, flow, motion parameters).
#[derive(Module, Debug)]
pub struct Head {
    hidden: SharedMlp,
    out: Linear,
}

impl Head {
    /// Hidden layers of `widths` after `input` channels, then `output` channels from a
    /// zero-initialised layer: the head starts out predicting 0 (uniform logits, zero flow,
    /// identity motions), so early training does not push its hidden units to die.
    pub fn new(input: usize, widths: &[usize], output: usize, device: &Device) -> Self {
        Self::with_output(
            input,
            widths,
            LinearConfig::new(0, output).with_initializer(Initializer::Zeros),
            device,
        )
    }

    /// Like [`Head::new`] but with burn's default initialisation of the output layer, for
    /// heads whose outputs feed further layers (features).
    pub fn dense(input: usize, widths: &[usize], output: usize, device: &Device) -> Self {
        Self::with_output(input, widths, LinearConfig::new(0, output), device)
    }

    /// Like [`Head::new`] with the hidden layers normalised by `norm` (a pair head).
    pub fn with_norm(
        input: usize,
        widths: &[usize],
        output: usize,
        norm: PairNorm,
        device: &Device,
    ) -> Self {
        let hidden = SharedMlp::with_norm(input, widths, norm, device);
        let out = LinearConfig::new(hidden.output(input), output)
            .with_initializer(Initializer::Zeros)
            .init(device);
        Self { hidden, out }
    }

    fn with_output(input: usize, widths: &[usize], out: LinearConfig, device: &Device) -> Self {
        let hidden = SharedMlp::new(input, widths, device);
        let out = LinearConfig { d_input: hidden.output(input), ..out }.init(device);
        Self { hidden, out }
    }

    /// # Shapes
    /// `[..., input]` -> `[..., output]`
    pub fn forward<const D: usize>(&self, x: Tensor<D>) -> Tensor<D> {
        linear(&self.out, self.hidden.forward(x))
    }
}
