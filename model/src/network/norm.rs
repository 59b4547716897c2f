//! A shared-MLP layer (matrix product, bias, layer normalisation, ReLU) as one operation with
//! its own backward pass, for training and inference on the CPU (the flex backend).
//!
//! Every layer of a [`crate::network::pointnet::SharedMlp`] is `Linear` ([`linear`]), layer norm, ReLU. burn's
//! autodiff records the bias as a broadcast addition, layer norm as the nine tensor
//! operations it is made of (mean, centre, square, mean, add, square root, divide, scale,
//! shift) and ReLU as one more, so a layer on a pair tensor of 16-67 MB made about eleven
//! passes over it forward and twice that backward: a `perf` profile of a stage-3 step put
//! about a third of it in operations of those kinds. And burn's matrix product on the flex
//! backend allocates its output zeroed and then copies it once more (to align it), and its
//! weight gradient is one long product that two threads share badly.
//!
//! Here ([`super::fused`]) the rows are cut into blocks of [`ROWS_PER_TASK`](super::fused::ROWS_PER_TASK), whatever the thread count, and
//! each block goes through the whole layer while it is in cache. Forward: the block's
//! product with the weight (faer, on the block's thread), then one sweep over its rows (each
//! row plus the bias, its mean and variance, then the normalised, scaled, shifted and
//! clipped values). Backward: it keeps the input, the product and the parameters, recomputes
//! each row's statistics and writes the product's gradient over the output's (the standard
//! layer-norm gradient `r (ĝ - mean(ĝ) - x̂ mean(ĝ x̂))` with `ĝ = γ g` where the output is
//! positive), then takes the input's gradient (a product with the weight's transpose) and
//! the block's share of the weight's, bias's, `γ`'s and `β`'s. The blocks' shares are added
//! in block order, so the result does not depend on the number of threads; the loops are
//! compiled for AVX2 and FMA as well and picked at run time (`pulp`).
//!
//! The operation gives the same values as burn's `Linear`, `LayerNorm` and `relu` up to
//! rounding (a test compares the values and all five gradients). [`linear_norm_relu`] uses
//! it on the flex device, with or without autodiff, for `f32`: in training and in inference,
//! so the committed boards are computed with it; every other backend keeps burn's operations.

use burn::backend::autodiff::checkpoint::{base::Checkpointer, strategy::CheckpointStrategy};
use burn::backend::autodiff::grads::Gradients;
use burn::backend::autodiff::ops::{Backward, Ops, OpsKind};
use burn::backend::autodiff::Autodiff;
use burn::backend::{backend_extension, tensor::FloatTensor, Backend, Dispatch, Flex};
use burn::nn::{LayerNorm, Linear};
use burn::prelude::*;
use burn::tensor::{activation, DType, TensorData};
use burn_flex::FlexTensor;

use crate::network::fused::{backward, forward, Channels, F32Rows};

/// `LayerNormConfig`'s default ε, which every layer of the network uses (a test checks the
/// two agree).
pub const EPSILON: f32 = 1e-5;

/// `layer` applied to the last dimension of `x`, as one matrix product on the flattened rows
/// (`[rows, input] x [input, output]`): burn's `Linear` on a rank-3 or rank-4 tensor runs one
/// small product per leading index (a thousand `[128, C]` products for a pair tensor, and as
/// many again in the backward pass, each followed by a reduction of the weight gradient),
/// where one product does the same arithmetic in less time (stage 1 steps 1.2x faster,
/// the single pass about as much). The two can round the last bit of an output differently
/// (the blocking of the product depends on the row count); the committed boards are computed
/// with this one.
///
/// # Shapes
/// `[..., input]` -> `[..., output]`
pub fn linear<const D: usize>(layer: &Linear, x: Tensor<D>) -> Tensor<D> {
    let mut dims = x.dims();
    if D <= 2 {
        return layer.forward(x);
    }
    let rows: usize = dims[..D - 1].iter().product();
    let y = layer.forward(x.reshape([rows, dims[D - 1]]));
    dims[D - 1] = y.dims()[1];
    y.reshape(dims)
}

/// The fused operation as a backend extension: implemented for flex and for autodiff on flex.
#[backend_extension(Flex, Autodiff)]
pub trait NormReluBackend: Backend {
    /// `relu(γ (y - mean) / sqrt(var + ε) + β)` with `y = input · weight + bias`, over the
    /// last dimension (`input: [rows, in]`, `weight: [in, out]`).
    fn linear_norm_relu(
        input: FloatTensor<Self>,
        weight: FloatTensor<Self>,
        bias: FloatTensor<Self>,
        gamma: FloatTensor<Self>,
        beta: FloatTensor<Self>,
    ) -> FloatTensor<Self>;
}

/// One layer of a shared MLP, `relu(norm(layer(x)))`: on the flex device (in training and
/// inference), the fused operation on the flattened rows; burn's `Linear`, `LayerNorm` and
/// `relu` everywhere else.
///
/// # Shapes
/// `[..., input]` -> `[..., output]`
pub fn linear_norm_relu<const D: usize>(
    layer: &Linear,
    norm: &LayerNorm,
    x: Tensor<D>,
) -> Tensor<D> {
    match (&layer.bias, &norm.beta, is_fused(layer, norm, &x)) {
        (Some(bias), Some(beta), true) => {
            let mut dims = x.dims();
            let rows: usize = dims[..D - 1].iter().product();
            dims[D - 1] = layer.weight.dims()[1];
            let out: Tensor<2> = Tensor::from_dispatch(Dispatch::linear_norm_relu(
                x.reshape([rows, layer.weight.dims()[0]]).into_dispatch(),
                layer.weight.val().into_dispatch(),
                bias.val().into_dispatch(),
                norm.gamma.val().into_dispatch(),
                beta.val().into_dispatch(),
            ));
            out.reshape(dims)
        }
        _ => activation::relu(norm.forward(linear(layer, x))),
    }
}

/// Whether [`linear_norm_relu`] takes the fused operation for this layer and input: `f32`
/// on the flex device (with or without autodiff), a bias and a `β`.
pub fn is_fused<const D: usize>(layer: &Linear, norm: &LayerNorm, x: &Tensor<D>) -> bool {
    layer.bias.is_some()
        && norm.beta.is_some()
        && x.dtype() == DType::F32
        && layer.weight.dims()[0] > 0
        && x.device().inner() == Device::flex()
}

impl NormReluBackend for Flex {
    fn linear_norm_relu(
        input: FlexTensor,
        weight: FlexTensor,
        bias: FlexTensor,
        gamma: FlexTensor,
        beta: FlexTensor,
    ) -> FlexTensor {
        let rows = input.layout().shape()[0];
        let [x, weight, bias, gamma, beta] = [input, weight, bias, gamma, beta].map(F32Rows::new);
        let channels = Channels { bias: bias.values(), gamma: gamma.values(), beta: beta.values() };
        let (out, _) = forward(x.values(), weight.values(), &channels, false);
        FlexTensor::from_data(TensorData::new(out, [rows, channels.gamma.len()]))
    }
}

impl<C: CheckpointStrategy> NormReluBackend for Autodiff<Flex, C> {
    fn linear_norm_relu(
        input: FloatTensor<Self>,
        weight: FloatTensor<Self>,
        bias: FloatTensor<Self>,
        gamma: FloatTensor<Self>,
        beta: FloatTensor<Self>,
    ) -> FloatTensor<Self> {
        /// The backward step; its state is the input, the product (before the bias) and the
        /// four parameters.
        #[derive(Debug)]
        struct LinearNormRelu;

        impl Backward<Flex, 5> for LinearNormRelu {
            type State = [FlexTensor; 6];

            fn backward(
                self,
                ops: Ops<Self::State, 5>,
                grads: &mut Gradients,
                _checkpointer: &mut Checkpointer,
            ) {
                let [node_x, node_weight, node_bias, node_gamma, node_beta] = ops.parents;
                let grad = grads.consume::<Flex>(&ops.node);
                let [input, weight, product, bias, gamma, beta] = ops.state;
                let shapes = [&input, &weight, &bias].map(|t| t.layout().shape().to_vec());
                let [x, weight, product, bias, gamma, beta] =
                    [input, weight, product, bias, gamma, beta].map(F32Rows::new);
                let channels =
                    Channels { bias: bias.values(), gamma: gamma.values(), beta: beta.values() };
                // The product's gradient overwrites the output's (copied first if shared).
                let mut dz = F32Rows::new(grad);
                let [dx, dw, dbias, dgamma, dbeta] = backward(
                    x.values(),
                    weight.values(),
                    product.values(),
                    &channels,
                    dz.values_mut(),
                    node_x.is_some(),
                );
                let [x_shape, w_shape, c_shape] = shapes;
                let shaped = [x_shape, w_shape, c_shape.clone(), c_shape.clone(), c_shape];
                let nodes = [node_x, node_weight, node_bias, node_gamma, node_beta];
                for ((node, values), shape) in
                    nodes.into_iter().zip([dx, dw, dbias, dgamma, dbeta]).zip(shaped)
                {
                    if let Some(node) = node {
                        let tensor = FlexTensor::from_data(TensorData::new(values, shape));
                        grads.register::<Flex>(node.id, tensor);
                    }
                }
            }
        }

        let guards = [input.node(), weight.node(), bias.node(), gamma.node(), beta.node()];
        let [input, weight, bias, gamma, beta] =
            [input, weight, bias, gamma, beta].map(|t| t.into_primitive());
        match LinearNormRelu.prepare::<C>(guards).compute_bound().stateful() {
            OpsKind::Tracked(prep) => {
                let rows = input.layout().shape()[0];
                let [x, w, b, g, be] = [input, weight, bias, gamma, beta].map(F32Rows::new);
                let channels = Channels { bias: b.values(), gamma: g.values(), beta: be.values() };
                let (out, product) = forward(x.values(), w.values(), &channels, true);
                let c = channels.gamma.len();
                let tensor = |values| FlexTensor::from_data(TensorData::new(values, [rows, c]));
                // The contiguous tensors, so that the backward pass does not copy them again.
                let state = [x.tensor, w.tensor, tensor(product), b.tensor, g.tensor, be.tensor];
                prep.finish(state, tensor(out))
            }
            OpsKind::UnTracked(prep) => {
                prep.finish(Flex::linear_norm_relu(input, weight, bias, gamma, beta))
            }
        }
    }
}

#[cfg(test)]
mod tests;
