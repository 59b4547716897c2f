//! Max-pooling over a set (the second-to-last dimension of a tensor whose last one is the
//! channels) as one operation with its own backward pass, on the CPU (the flex backend).
//!
//! Every PointNet in the network pools this way: over the pairs of a point (`[batch, m, m,
//! C]` in the correspondence, flow, support and RPEN modules), over a ball's members, over
//! all points. burn's `max_dim` on the flex backend reduces a strided axis one output value
//! at a time, and its autodiff records the maximum's indices as an `i64` tensor and scatters
//! the gradient back with a general `scatter_add`: a `perf` profile of the single pass put a
//! fifth of it in that reduction. Here each output row is the running maximum of contiguous
//! rows of channels (SIMD over the channels, the loops compiled for AVX2 as well and picked
//! at run time), in parallel over the sets, and the backward pass writes each channel's
//! gradient into the row that won it.
//!
//! The maximum is exact, so the values are burn's bit for bit (a test); where several rows
//! tie, the first one gets the gradient. Every other backend, and a set of no rows, keeps
//! burn's `max_dim`.

use std::sync::Arc;

use burn::backend::autodiff::checkpoint::{base::Checkpointer, strategy::CheckpointStrategy};
use burn::backend::autodiff::grads::Gradients;
use burn::backend::autodiff::ops::{Backward, Ops, OpsKind};
use burn::backend::autodiff::Autodiff;
use burn::backend::{backend_extension, tensor::FloatTensor, Backend, Dispatch, Flex};
use burn::prelude::*;
use burn::tensor::{DType, TensorData};
use burn_flex::FlexTensor;
use rayon::prelude::*;

use crate::network::fused::F32Rows;

/// Sets per block of parallel work.
const SETS_PER_TASK: usize = 16;

/// The pooling as a backend extension: implemented for flex and for autodiff on flex.
#[backend_extension(Flex, Autodiff)]
pub trait PoolBackend: Backend {
    /// The maximum over the second-to-last dimension, kept with size 1.
    fn max_pool(input: FloatTensor<Self>) -> FloatTensor<Self>;
}

/// `x.max_dim(D - 2)`: the maximum over the second-to-last dimension (kept, with size 1),
/// as one operation on the flex device for `f32`.
///
/// # Shapes
/// `[..., rows, channels]` -> `[..., 1, channels]`
pub fn max_pool<const D: usize>(x: Tensor<D>) -> Tensor<D> {
    if is_pooled(&x) {
        Tensor::from_dispatch(Dispatch::max_pool(x.into_dispatch()))
    } else {
        x.max_dim(D - 2)
    }
}

/// Whether [`max_pool`] takes the fused operation: `f32` on the flex device (with or without
/// autodiff), rank 2 or more, at least one row.
pub fn is_pooled<const D: usize>(x: &Tensor<D>) -> bool {
    D >= 2 && x.dims()[D - 2] > 0 && x.dtype() == DType::F32 && x.device().inner() == Device::flex()
}

/// A tensor's shape read as `[sets, rows, channels]` (every leading dimension is a set).
fn sets_rows_channels(shape: &[usize]) -> [usize; 3] {
    let d = shape.len();
    [shape[..d - 2].iter().product(), shape[d - 2], shape[d - 1]]
}

/// The pooled tensor, and the winning row of every output value when `indices`.
fn pool(input: FlexTensor, indices: bool) -> (FlexTensor, Vec<u32>) {
    let shape = input.layout().shape().to_vec();
    let [_, rows, channels] = sets_rows_channels(&shape);
    let x = F32Rows::new(input);
    let (values, winners) = forward(x.values(), rows, channels, indices);
    let mut out_shape = shape;
    let d = out_shape.len();
    out_shape[d - 2] = 1;
    (FlexTensor::from_data(TensorData::new(values, out_shape)), winners)
}

impl PoolBackend for Flex {
    fn max_pool(input: FlexTensor) -> FlexTensor {
        pool(input, false).0
    }
}

impl<C: CheckpointStrategy> PoolBackend for Autodiff<Flex, C> {
    fn max_pool(input: FloatTensor<Self>) -> FloatTensor<Self> {
        /// The backward step; its state is the winning rows and the input's shape.
        #[derive(Debug)]
        struct MaxPool;

        impl Backward<Flex, 1> for MaxPool {
            type State = (Arc<Vec<u32>>, Vec<usize>);

            fn backward(
                self,
                ops: Ops<Self::State, 1>,
                grads: &mut Gradients,
                _checkpointer: &mut Checkpointer,
            ) {
                let [node] = ops.parents;
                let grad = grads.consume::<Flex>(&ops.node);
                let (winners, shape) = ops.state;
                if let Some(node) = node {
                    let [_, rows, channels] = sets_rows_channels(&shape);
                    let dx = backward(F32Rows::new(grad).values(), &winners, rows, channels);
                    grads.register::<Flex>(
                        node.id,
                        FlexTensor::from_data(TensorData::new(dx, shape)),
                    );
                }
            }
        }

        let guards = [input.node()];
        let x = input.into_primitive();
        let shape = x.layout().shape().to_vec();
        match MaxPool.prepare::<C>(guards).compute_bound().stateful() {
            OpsKind::Tracked(prep) => {
                let (output, winners) = pool(x, true);
                prep.finish((Arc::new(winners), shape), output)
            }
            OpsKind::UnTracked(prep) => prep.finish(pool(x, false).0),
        }
    }
}

/// The forward pass on `[sets, rows, channels]` values (`rows` at least 1): the maximum of
/// every set's rows, `[sets, channels]`, and with `indices` the row each value came from
/// (the first of equal ones).
pub fn forward(x: &[f32], rows: usize, channels: usize, indices: bool) -> (Vec<f32>, Vec<u32>) {
    let sets = x.len().checked_div(rows * channels).unwrap_or(0);
    let mut out = vec![0.0f32; sets * channels];
    let mut winners = vec![0u32; if indices { sets * channels } else { 0 }];
    if sets == 0 {
        return (out, winners);
    }
    let arch = pulp::Arch::new();
    let block = SETS_PER_TASK * channels;
    let inputs = x.par_chunks(SETS_PER_TASK * rows * channels);
    if indices {
        out.par_chunks_mut(block).zip(winners.par_chunks_mut(block)).zip(inputs).for_each(
            |((out, winners), x)| {
                arch.dispatch(|| {
                    for ((out, winners), set) in out
                        .chunks_exact_mut(channels)
                        .zip(winners.chunks_exact_mut(channels))
                        .zip(x.chunks_exact(rows * channels))
                    {
                        let (first, rest) = set.split_at(channels);
                        out.copy_from_slice(first);
                        for (j, row) in rest.chunks_exact(channels).enumerate() {
                            let j = j as u32 + 1;
                            for ((m, w), &v) in out.iter_mut().zip(winners.iter_mut()).zip(row) {
                                if v > *m {
                                    *m = v;
                                    *w = j;
                                }
                            }
                        }
                    }
                })
            },
        );
    } else {
        out.par_chunks_mut(block).zip(inputs).for_each(|(out, x)| {
            arch.dispatch(|| {
                for (out, set) in
                    out.chunks_exact_mut(channels).zip(x.chunks_exact(rows * channels))
                {
                    let (first, rest) = set.split_at(channels);
                    out.copy_from_slice(first);
                    for row in rest.chunks_exact(channels) {
                        for (m, &v) in out.iter_mut().zip(row) {
                            if v > *m {
                                *m = v;
                            }
                        }
                    }
                }
            })
        });
    }
    (out, winners)
}

/// The backward pass: the gradient `grad` of the pooled `[sets, channels]` values written into
/// the rows that won them, zero elsewhere: `[sets, rows, channels]`.
pub fn backward(grad: &[f32], winners: &[u32], rows: usize, channels: usize) -> Vec<f32> {
    let mut dx = vec![0.0f32; grad.len() * rows];
    if channels == 0 || rows == 0 {
        return dx;
    }
    dx.par_chunks_mut(rows * channels)
        .zip(grad.par_chunks(channels).zip(winners.par_chunks(channels)))
        .for_each(|(dx, (grad, winners))| {
            for (c, (&g, &w)) in grad.iter().zip(winners).enumerate() {
                dx[w as usize * channels + c] = g;
            }
        });
    dx
}

#[cfg(test)]
mod tests;
