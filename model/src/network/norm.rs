//! A shared-MLP layer's bias, layer normalisation and ReLU as one operation with its own
//! backward pass, for training on the CPU (the flex backend).
//!
//! Every layer of a [`crate::network::pointnet::SharedMlp`] is `Linear`, layer norm, ReLU. burn's
//! autodiff records the bias as a broadcast addition, layer norm as the nine tensor
//! operations it is made of (mean, centre, square, mean, add, square root, divide, scale,
//! shift) and ReLU as one more, so a layer on a pair tensor of 16-67 MB made about eleven
//! passes over it forward and twice that backward: a `perf` profile of a stage-3 step put
//! about a third of it in operations of those kinds. Here the matrix product runs alone (one product on the
//! flattened rows), and the rest is one sweep over the rows forward (each row plus the
//! bias, its mean and variance, then the normalised, scaled, shifted and clipped values)
//! and one backward: it keeps only the product's output and the three parameter vectors,
//! recomputes each row's statistics, and writes the input's gradient over the output's
//! (the standard layer-norm gradient `r (ĝ - mean(ĝ) - x̂ mean(ĝ x̂))` with `ĝ = γ g` where
//! the output is positive) while it sums the gradients of the bias, `γ` and `β`. Rows are
//! cut into blocks of [`ROWS_PER_TASK`] whatever the thread count, and the blocks' sums are
//! added in block order, so the result does not depend on the number of threads; the loops
//! are compiled for AVX2 and FMA as well and picked at run time (`pulp`).
//!
//! The operation gives the same values as burn's `Linear`, `LayerNorm` and `relu` up to
//! rounding (a test compares the values and all five gradients). [`linear_norm_relu`] uses
//! it only on the flex autodiff device, for `f32`, when the layer's weights track
//! gradients: inference, and every other backend, keeps burn's operations, so the committed
//! boards do not move by a rounding.

use burn::backend::autodiff::checkpoint::{base::Checkpointer, strategy::CheckpointStrategy};
use burn::backend::autodiff::grads::Gradients;
use burn::backend::autodiff::ops::{Backward, Ops, OpsKind};
use burn::backend::autodiff::Autodiff;
use burn::backend::{backend_extension, tensor::FloatTensor, Backend, Dispatch, Flex};
use burn::nn::{LayerNorm, Linear};
use burn::prelude::*;
use burn::tensor::{activation, DType, TensorData};
use burn_flex::FlexTensor;
use rayon::prelude::*;

use crate::network::pointnet::linear;

/// `LayerNormConfig`'s default ε, which every layer of the network uses (a test checks the
/// two agree).
pub const EPSILON: f32 = 1e-5;

/// Rows per block of work (and per partial sum of the `γ`, `β` gradients).
pub const ROWS_PER_TASK: usize = 64;

/// The fused operation as a backend extension: implemented for flex and for autodiff on flex.
#[backend_extension(Flex, Autodiff)]
pub trait NormReluBackend: Backend {
    /// `relu(γ (y - mean) / sqrt(var + ε) + β)` with `y = input + bias`, over the last
    /// dimension.
    fn layer_norm_relu(
        input: FloatTensor<Self>,
        bias: FloatTensor<Self>,
        gamma: FloatTensor<Self>,
        beta: FloatTensor<Self>,
    ) -> FloatTensor<Self>;
}

/// One layer of a shared MLP, `relu(norm(layer(x)))`: on the flex autodiff device in
/// training, one matrix product on the flattened rows and then the fused operation (which
/// also adds the layer's bias); burn's `Linear`, `LayerNorm` and `relu` everywhere else.
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
            let y = x.reshape([rows, dims[D - 1]]).matmul(layer.weight.val());
            dims[D - 1] = y.dims()[1];
            let out: Tensor<2> = Tensor::from_dispatch(Dispatch::layer_norm_relu(
                y.into_dispatch(),
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
/// on the flex autodiff device, weights tracking gradients, a bias and a `β`.
pub fn is_fused<const D: usize>(layer: &Linear, norm: &LayerNorm, x: &Tensor<D>) -> bool {
    layer.weight.val().is_require_grad()
        && layer.bias.is_some()
        && norm.beta.is_some()
        && x.dtype() == DType::F32
        && x.device().inner() == Device::flex()
}

impl NormReluBackend for Flex {
    fn layer_norm_relu(
        input: FlexTensor,
        bias: FlexTensor,
        gamma: FlexTensor,
        beta: FlexTensor,
    ) -> FlexTensor {
        let shape = input.layout().shape().to_vec();
        let x = F32Rows::new(input);
        let (bias, gamma, beta) = (F32Rows::new(bias), F32Rows::new(gamma), F32Rows::new(beta));
        let channels = Channels { bias: bias.values(), gamma: gamma.values(), beta: beta.values() };
        FlexTensor::from_data(TensorData::new(forward(x.values(), &channels), shape))
    }
}

impl<C: CheckpointStrategy> NormReluBackend for Autodiff<Flex, C> {
    fn layer_norm_relu(
        input: FloatTensor<Self>,
        bias: FloatTensor<Self>,
        gamma: FloatTensor<Self>,
        beta: FloatTensor<Self>,
    ) -> FloatTensor<Self> {
        /// The backward step; its state is the input and the three parameter vectors.
        #[derive(Debug)]
        struct NormRelu;

        impl Backward<Flex, 4> for NormRelu {
            type State = [FlexTensor; 4];

            fn backward(
                self,
                ops: Ops<Self::State, 4>,
                grads: &mut Gradients,
                _checkpointer: &mut Checkpointer,
            ) {
                let [node_x, node_bias, node_gamma, node_beta] = ops.parents;
                let grad = grads.consume::<Flex>(&ops.node);
                let [input, bias, gamma, beta] = ops.state;
                let shape = gamma.layout().shape().to_vec();
                let x = F32Rows::new(input);
                let (bias, gamma, beta) =
                    (F32Rows::new(bias), F32Rows::new(gamma), F32Rows::new(beta));
                let channels =
                    Channels { bias: bias.values(), gamma: gamma.values(), beta: beta.values() };
                // The input's gradient overwrites the output's (copied first if shared).
                let mut dx = F32Rows::new(grad);
                let sums = backward(x.values(), &channels, dx.values_mut());
                if let Some(node) = node_x {
                    grads.register::<Flex>(node.id, dx.tensor);
                }
                for (node, values) in [node_bias, node_gamma, node_beta].into_iter().zip(sums) {
                    if let Some(node) = node {
                        let tensor = FlexTensor::from_data(TensorData::new(values, shape.clone()));
                        grads.register::<Flex>(node.id, tensor);
                    }
                }
            }
        }

        let guards = [input.node(), bias.node(), gamma.node(), beta.node()];
        let state = [input, bias, gamma, beta].map(|t| t.into_primitive());
        let [x, bias, gamma, beta] = state.clone();
        let output = Flex::layer_norm_relu(x, bias, gamma, beta);
        match NormRelu.prepare::<C>(guards).compute_bound().stateful() {
            OpsKind::Tracked(prep) => prep.finish(state, output),
            OpsKind::UnTracked(prep) => prep.finish(output),
        }
    }
}

/// The per-channel parameters of one fused layer: the linear layer's bias and the norm's
/// `γ` and `β`, each as long as a row.
#[derive(Debug, Clone, Copy)]
pub struct Channels<'a> {
    /// Added to every row first.
    pub bias: &'a [f32],
    /// Scale after normalising.
    pub gamma: &'a [f32],
    /// Shift after scaling.
    pub beta: &'a [f32],
}

/// A flex tensor made contiguous, read as `f32`s.
struct F32Rows {
    tensor: FlexTensor,
    range: std::ops::Range<usize>,
}

impl F32Rows {
    fn new(tensor: FlexTensor) -> Self {
        let tensor = tensor.to_contiguous();
        let (start, end) = tensor.layout().contiguous_offsets().unwrap_or((0, 0));
        Self { tensor, range: start..end }
    }

    fn values(&self) -> &[f32] {
        &self.tensor.storage::<f32>()[self.range.clone()]
    }

    /// The values to write in place (copied first if the storage is shared).
    fn values_mut(&mut self) -> &mut [f32] {
        &mut self.tensor.storage_mut::<f32>()[self.range.clone()]
    }
}

/// Lanes of the partial sums: the loops below add eight independent running sums (added
/// together at the end, always in the same order), which the compiler turns into SIMD
/// instructions; one running sum would be a chain of dependent additions.
const LANES: usize = 8;

/// `Σ f(a_i, b_i)` over two equally long slices, in [`LANES`] partial sums.
#[inline]
fn lane_sum(a: &[f32], b: &[f32], f: impl Fn(f32, f32) -> f32) -> f32 {
    let mut acc = [0.0f32; LANES];
    let (ca, cb) = (a.chunks_exact(LANES), b.chunks_exact(LANES));
    let tail: f32 = ca.remainder().iter().zip(cb.remainder()).map(|(&x, &y)| f(x, y)).sum();
    for (ca, cb) in ca.zip(cb) {
        for ((acc, &x), &y) in acc.iter_mut().zip(ca).zip(cb) {
            *acc += f(x, y);
        }
    }
    acc.iter().sum::<f32>() + tail
}

/// One row's mean and `1 / sqrt(var + ε)` (two passes: the variance of the centred values).
#[inline]
fn statistics(row: &[f32]) -> (f32, f32) {
    let n = row.len() as f32;
    let mean = lane_sum(row, row, |v, _| v) / n;
    let var = lane_sum(row, row, |v, _| (v - mean) * (v - mean)) / n;
    (mean, 1.0 / (var + EPSILON).sqrt())
}

/// The forward pass on rows of `channels.gamma.len()` values.
pub fn forward(x: &[f32], channels: &Channels) -> Vec<f32> {
    let Channels { bias, gamma, beta } = *channels;
    let c = gamma.len();
    let mut out = vec![0.0f32; x.len()];
    if c == 0 {
        return out;
    }
    let arch = pulp::Arch::new();
    out.par_chunks_mut(ROWS_PER_TASK * c).zip(x.par_chunks(ROWS_PER_TASK * c)).for_each(
        |(out, x)| {
            arch.dispatch(|| {
                for (o, row) in out.chunks_exact_mut(c).zip(x.chunks_exact(c)) {
                    // The row plus the bias, written to the output and normalised in place.
                    for ((o, &v), &b) in o.iter_mut().zip(row).zip(bias) {
                        *o = v + b;
                    }
                    let (mean, r) = statistics(o);
                    for ((o, &g), &b) in o.iter_mut().zip(gamma).zip(beta) {
                        *o = ((*o - mean) * r * g + b).max(0.0);
                    }
                }
            })
        },
    );
    out
}

/// The backward pass: overwrites the output's gradient `grad` with the input's, and returns
/// the gradients of the bias, `γ` and `β`.
pub fn backward(x: &[f32], channels: &Channels, grad: &mut [f32]) -> [Vec<f32>; 3] {
    let Channels { bias, gamma, beta } = *channels;
    let c = gamma.len();
    if c == 0 {
        return [Vec::new(), Vec::new(), Vec::new()];
    }
    let block = ROWS_PER_TASK * c;
    let arch = pulp::Arch::new();
    let partial: Vec<[Vec<f32>; 3]> = grad
        .par_chunks_mut(block)
        .zip(x.par_chunks(block))
        .map(|(grad, x)| {
            arch.dispatch(|| {
                let [mut dbias, mut dgamma, mut dbeta] = [0; 3].map(|_| vec![0.0f32; c]);
                let [mut y, mut xhat, mut ghat] = [0; 3].map(|_| vec![0.0f32; c]);
                for (g, row) in grad.chunks_exact_mut(c).zip(x.chunks_exact(c)) {
                    for ((y, &v), &b) in y.iter_mut().zip(row).zip(bias) {
                        *y = v + b;
                    }
                    let (mean, r) = statistics(&y);
                    // x̂, the output's gradient where the output is positive (ReLU), and the
                    // γ, β gradients of this row.
                    for (((((((xh, gh), dg), db), &v), &g), &ga), &be) in xhat
                        .iter_mut()
                        .zip(ghat.iter_mut())
                        .zip(dgamma.iter_mut())
                        .zip(dbeta.iter_mut())
                        .zip(&y)
                        .zip(g.iter())
                        .zip(gamma)
                        .zip(beta)
                    {
                        let h = (v - mean) * r;
                        let g = if h * ga + be > 0.0 { g } else { 0.0 };
                        *dg += g * h;
                        *db += g;
                        *xh = h;
                        *gh = g * ga;
                    }
                    let m1 = lane_sum(&ghat, &ghat, |g, _| g) / c as f32;
                    let m2 = lane_sum(&ghat, &xhat, |g, h| g * h) / c as f32;
                    for (((dx, d), &gh), &xh) in
                        g.iter_mut().zip(dbias.iter_mut()).zip(&ghat).zip(&xhat)
                    {
                        *dx = r * (gh - m1 - xh * m2);
                        *d += *dx;
                    }
                }
                [dbias, dgamma, dbeta]
            })
        })
        .collect();
    let mut sums = [0; 3].map(|_| vec![0.0f32; c]);
    for block in &partial {
        for (sum, part) in sums.iter_mut().zip(block) {
            sum.iter_mut().zip(part).for_each(|(a, b)| *a += b);
        }
    }
    sums
}

#[cfg(test)]
mod tests;
