//! Layer normalisation followed by ReLU as one operation with its own backward pass, for
//! training on the CPU (the flex backend).
//!
//! Every layer of a [`crate::pointnet::SharedMlp`] is `Linear`, layer norm, ReLU. burn's
//! autodiff records layer norm as the nine tensor operations it is made of (mean, centre,
//! square, mean, add, square root, divide, scale, shift), and ReLU as one more, so a layer on a
//! pair tensor of 16-67 MB made about ten passes over it forward and twice that backward:
//! a `perf` profile of a stage-3 step put 35% of it in those operations. Here the forward
//! pass is one sweep over the rows (each row's mean and variance, then the normalised,
//! scaled, shifted and clipped values), and the backward pass one more: it keeps only
//! references to the layer's input, `γ` and `β`, recomputes each row's statistics, and
//! writes the input's gradient (the standard layer-norm gradient
//! `r (ĝ - mean(ĝ) - x̂ mean(ĝ x̂))` with `ĝ = γ g` where the output is positive) while it
//! sums the gradients of `γ` and `β`. Rows are cut into blocks of [`ROWS_PER_TASK`] whatever
//! the thread count and the blocks' sums of the `γ` and `β` gradients are added in block
//! order, so the result does not depend on the number of threads.
//!
//! The operation gives the same values as burn's `LayerNorm` then `relu` up to rounding
//! (tests compare values and all three gradients). [`layer_norm_relu`] uses it only where
//! it is exact to say so: on the flex autodiff device, for `f32`, when the layer's weights
//! track gradients; inference, and every other backend, keeps burn's operations, so the
//! committed boards do not move by a rounding.

use burn::backend::autodiff::checkpoint::{base::Checkpointer, strategy::CheckpointStrategy};
use burn::backend::autodiff::grads::Gradients;
use burn::backend::autodiff::ops::{Backward, Ops, OpsKind};
use burn::backend::autodiff::Autodiff;
use burn::backend::{backend_extension, tensor::FloatTensor, Backend, Dispatch, Flex};
use burn::nn::LayerNorm;
use burn::prelude::*;
use burn::tensor::{activation, DType, TensorData};
use burn_flex::FlexTensor;
use rayon::prelude::*;

/// `LayerNormConfig`'s default ε, which every layer of the network uses (a test checks the
/// two agree).
pub const EPSILON: f32 = 1e-5;

/// Rows per block of work (and per partial sum of the `γ`, `β` gradients).
pub const ROWS_PER_TASK: usize = 64;

/// The fused operation as a backend extension: implemented for flex and for autodiff on flex.
#[backend_extension(Flex, Autodiff)]
pub trait NormReluBackend: Backend {
    /// `relu(γ (x - mean) / sqrt(var + ε) + β)` over the last dimension.
    fn layer_norm_relu(
        input: FloatTensor<Self>,
        gamma: FloatTensor<Self>,
        beta: FloatTensor<Self>,
    ) -> FloatTensor<Self>;
}

/// `relu(norm(x))` for one layer: fused on the flex autodiff device in training, burn's
/// `LayerNorm` and `relu` everywhere else.
///
/// # Shapes
/// `[..., channels]` -> `[..., channels]`
pub fn layer_norm_relu<const D: usize>(norm: &LayerNorm, x: Tensor<D>) -> Tensor<D> {
    match (&norm.beta, is_fused(norm, &x)) {
        (Some(beta), true) => Tensor::from_dispatch(Dispatch::layer_norm_relu(
            x.into_dispatch(),
            norm.gamma.val().into_dispatch(),
            beta.val().into_dispatch(),
        )),
        _ => activation::relu(norm.forward(x)),
    }
}

/// Whether [`layer_norm_relu`] takes the fused operation for this layer and input: `f32` on
/// the flex autodiff device, with `γ` tracking gradients and a `β`.
pub fn is_fused<const D: usize>(norm: &LayerNorm, x: &Tensor<D>) -> bool {
    norm.gamma.val().is_require_grad()
        && norm.beta.is_some()
        && x.dtype() == DType::F32
        && x.device().inner() == Device::flex()
}

impl NormReluBackend for Flex {
    fn layer_norm_relu(input: FlexTensor, gamma: FlexTensor, beta: FlexTensor) -> FlexTensor {
        let shape = input.layout().shape().to_vec();
        let (x, gamma, beta) = (F32Rows::new(input), F32Rows::new(gamma), F32Rows::new(beta));
        let out = forward(x.values(), gamma.values(), beta.values());
        FlexTensor::from_data(TensorData::new(out, shape))
    }
}

impl<C: CheckpointStrategy> NormReluBackend for Autodiff<Flex, C> {
    fn layer_norm_relu(
        input: FloatTensor<Self>,
        gamma: FloatTensor<Self>,
        beta: FloatTensor<Self>,
    ) -> FloatTensor<Self> {
        /// The backward step; its state is the layer's input, `γ` and `β`.
        #[derive(Debug)]
        struct NormRelu;

        impl Backward<Flex, 3> for NormRelu {
            type State = (FlexTensor, FlexTensor, FlexTensor);

            fn backward(
                self,
                ops: Ops<Self::State, 3>,
                grads: &mut Gradients,
                _checkpointer: &mut Checkpointer,
            ) {
                let [node_x, node_gamma, node_beta] = ops.parents;
                let grad = grads.consume::<Flex>(&ops.node);
                let (input, gamma, beta) = ops.state;
                let channels = gamma.layout().shape().to_vec();
                let (x, gamma, beta) =
                    (F32Rows::new(input), F32Rows::new(gamma), F32Rows::new(beta));
                // The input's gradient overwrites the output's (copied first if shared).
                let mut dx = grad.to_contiguous();
                let (start, end) = dx.layout().contiguous_offsets().unwrap_or((0, 0));
                let (dgamma, dbeta) = backward(
                    x.values(),
                    gamma.values(),
                    beta.values(),
                    &mut dx.storage_mut::<f32>()[start..end],
                );
                let tensor = |values: Vec<f32>, shape: &[usize]| {
                    FlexTensor::from_data(TensorData::new(values, shape.to_vec()))
                };
                if let Some(node) = node_x {
                    grads.register::<Flex>(node.id, dx);
                }
                if let Some(node) = node_gamma {
                    grads.register::<Flex>(node.id, tensor(dgamma, &channels));
                }
                if let Some(node) = node_beta {
                    grads.register::<Flex>(node.id, tensor(dbeta, &channels));
                }
            }
        }

        let guards = [input.node(), gamma.node(), beta.node()];
        let (x, gamma, beta) =
            (input.into_primitive(), gamma.into_primitive(), beta.into_primitive());
        let output = Flex::layer_norm_relu(x.clone(), gamma.clone(), beta.clone());
        match NormRelu.prepare::<C>(guards).compute_bound().stateful() {
            OpsKind::Tracked(prep) => prep.finish((x, gamma, beta), output),
            OpsKind::UnTracked(prep) => prep.finish(output),
        }
    }
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

/// The forward pass on rows of `gamma.len()` values.
pub fn forward(x: &[f32], gamma: &[f32], beta: &[f32]) -> Vec<f32> {
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
                    let (mean, r) = statistics(row);
                    for (((o, &v), &g), &b) in o.iter_mut().zip(row).zip(gamma).zip(beta) {
                        *o = ((v - mean) * r * g + b).max(0.0);
                    }
                }
            })
        },
    );
    out
}

/// The backward pass: overwrites the output's gradient `grad` with the input's, and returns
/// the gradients of `γ` and `β`.
pub fn backward(x: &[f32], gamma: &[f32], beta: &[f32], grad: &mut [f32]) -> (Vec<f32>, Vec<f32>) {
    let c = gamma.len();
    if c == 0 {
        return (Vec::new(), Vec::new());
    }
    let block = ROWS_PER_TASK * c;
    let arch = pulp::Arch::new();
    let partial: Vec<(Vec<f32>, Vec<f32>)> = grad
        .par_chunks_mut(block)
        .zip(x.par_chunks(block))
        .map(|(grad, x)| {
            arch.dispatch(|| {
                let (mut dgamma, mut dbeta) = (vec![0.0f32; c], vec![0.0f32; c]);
                let (mut xhat, mut ghat) = (vec![0.0f32; c], vec![0.0f32; c]);
                for (g, row) in grad.chunks_exact_mut(c).zip(x.chunks_exact(c)) {
                    let (mean, r) = statistics(row);
                    // x̂, the output's gradient where the output is positive (ReLU), and the
                    // γ, β gradients of this row.
                    for (((((((xh, gh), dg), db), &v), &g), &ga), &be) in xhat
                        .iter_mut()
                        .zip(ghat.iter_mut())
                        .zip(dgamma.iter_mut())
                        .zip(dbeta.iter_mut())
                        .zip(row)
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
                    for ((dx, &gh), &xh) in g.iter_mut().zip(&ghat).zip(&xhat) {
                        *dx = r * (gh - m1 - xh * m2);
                    }
                }
                (dgamma, dbeta)
            })
        })
        .collect();
    let (mut dgamma, mut dbeta) = (vec![0.0f32; c], vec![0.0f32; c]);
    for (pg, pb) in &partial {
        dgamma.iter_mut().zip(pg).for_each(|(a, b)| *a += b);
        dbeta.iter_mut().zip(pb).for_each(|(a, b)| *a += b);
    }
    (dgamma, dbeta)
}

#[cfg(test)]
mod tests {
    use super::*;
    use burn::module::Param;
    use burn::nn::LayerNormConfig;
    use burn::tensor::Distribution;

    /// Values and the gradients of input, γ and β, through `f`, for the loss
    /// `sum(out * weights)`.
    fn run(
        norm: &LayerNorm,
        x: &Tensor<3>,
        weights: &Tensor<3>,
        f: fn(&LayerNorm, Tensor<3>) -> Tensor<3>,
    ) -> [Vec<f32>; 4] {
        let x = x.clone().require_grad();
        let out = f(norm, x.clone());
        let grads = (out.clone() * weights.clone()).sum().backward();
        let read = |t: Option<Tensor<1>>| {
            t.expect("a gradient").to_data().try_to_vec::<f32>().expect("f32")
        };
        [
            out.to_data().try_to_vec::<f32>().expect("f32"),
            x.grad(&grads).expect("input gradient").to_data().try_to_vec::<f32>().expect("f32"),
            read(norm.gamma.grad(&grads)),
            read(norm.beta.as_ref().and_then(|b| b.grad(&grads))),
        ]
    }

    fn reference(norm: &LayerNorm, x: Tensor<3>) -> Tensor<3> {
        activation::relu(norm.forward(x))
    }

    #[test]
    fn matches_layer_norm_then_relu_in_values_and_gradients() {
        let device = Device::flex().autodiff();
        // 300 rows: more than one block, and a last block that is not full.
        let x = Tensor::<3>::random([3, 100, 24], Distribution::Normal(0.5, 2.0), &device);
        let weights = Tensor::<3>::random([3, 100, 24], Distribution::Normal(0.0, 1.0), &device);
        let mut norm = LayerNormConfig::new(24).init(&device);
        // γ and β away from 1 and 0, so that every term of the gradient matters.
        norm.gamma =
            Param::from_tensor(Tensor::random([24], Distribution::Uniform(0.5, 1.5), &device));
        norm.beta =
            Some(Param::from_tensor(Tensor::random([24], Distribution::Normal(0.0, 0.5), &device)));
        assert!(is_fused(&norm, &x));
        let fused = run(&norm, &x, &weights, layer_norm_relu);
        let expected = run(&norm, &x, &weights, reference);
        for (name, (a, b)) in ["output", "input grad", "gamma grad", "beta grad"]
            .iter()
            .zip(fused.iter().zip(&expected))
        {
            assert_eq!(a.len(), b.len(), "{name}");
            let scale = b.iter().fold(1.0f32, |m, v| m.max(v.abs()));
            let worst = a.iter().zip(b).map(|(a, b)| (a - b).abs()).fold(0.0, f32::max);
            assert!(worst <= 2e-5 * scale, "{name}: differs by {worst} (scale {scale})");
        }
        // Some outputs are clipped, some are not: both branches of the ReLU are tested.
        let zeros = fused[0].iter().filter(|&&v| v == 0.0).count();
        assert!(zeros > 100 && zeros < fused[0].len() - 100, "{zeros} zeros");
    }

    #[test]
    fn inference_keeps_burns_operations_bit_for_bit() {
        let device = Device::flex();
        let x = Tensor::<2>::random([70, 16], Distribution::Normal(0.0, 1.0), &device);
        let norm = LayerNormConfig::new(16).init(&device);
        assert!(!is_fused(&norm, &x));
        let a: Vec<f32> =
            layer_norm_relu(&norm, x.clone()).to_data().try_to_vec::<f32>().expect("f32");
        let b: Vec<f32> =
            activation::relu(norm.forward(x)).to_data().try_to_vec::<f32>().expect("f32");
        assert_eq!(a, b);
    }

    #[test]
    fn epsilon_is_layer_norms_default() {
        assert_eq!(LayerNormConfig::new(4).epsilon as f32, EPSILON);
    }

    #[test]
    fn gradients_do_not_depend_on_the_thread_count() {
        let x: Vec<f32> =
            (0..(5 * ROWS_PER_TASK + 3) * 8).map(|i| ((i * 37 % 101) as f32).sin()).collect();
        let grad: Vec<f32> = x.iter().map(|v| (v * 3.0).cos()).collect();
        let (gamma, beta) = (vec![0.9f32; 8], vec![0.1f32; 8]);
        let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("pool");
        let (mut da, mut db) = (grad.clone(), grad);
        let a = one.install(|| backward(&x, &gamma, &beta, &mut da));
        let three = rayon::ThreadPoolBuilder::new().num_threads(3).build().expect("pool");
        let b = three.install(|| backward(&x, &gamma, &beta, &mut db));
        assert_eq!((a, da), (b, db));
    }
}
