//! The fused shared-MLP layer's CPU kernel ([`super::norm`] dispatches to it on the flex
//! backend): rows cut into blocks of [`ROWS_PER_TASK`], each block's matrix product (faer),
//! bias, layer normalisation, scale, shift and ReLU in one sweep, and the backward pass that
//! recomputes each row's statistics. The blocks' shares of the parameter gradients are added
//! in block order, so the result does not depend on the number of threads.

use burn_flex::FlexTensor;
use faer::linalg::matmul::matmul;
use faer::{Accum, MatMut, MatRef, Par};
use rayon::prelude::*;

use crate::network::norm::EPSILON;

/// Rows per block of work (and per partial sum of the weight, bias, `γ` and `β` gradients).
pub const ROWS_PER_TASK: usize = 256;

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
pub(crate) struct F32Rows {
    pub(crate) tensor: FlexTensor,
    range: std::ops::Range<usize>,
}

impl F32Rows {
    pub(crate) fn new(tensor: FlexTensor) -> Self {
        let tensor = tensor.to_contiguous();
        let (start, end) = tensor.layout().contiguous_offsets().unwrap_or((0, 0));
        Self { tensor, range: start..end }
    }

    pub(crate) fn values(&self) -> &[f32] {
        &self.tensor.storage::<f32>()[self.range.clone()]
    }

    /// The values to write in place (copied first if the storage is shared).
    pub(crate) fn values_mut(&mut self) -> &mut [f32] {
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

/// The number of rows of `width` values in `values` (0 for rows of no values).
fn rows_of(values: &[f32], width: usize) -> usize {
    values.len().checked_div(width).unwrap_or(0)
}

/// `out = x · w` for `x: [rows, input]` and `w: [input, output]`, all row-major, on this
/// thread.
fn product(out: &mut [f32], x: &[f32], w: MatRef<'_, f32>) {
    let (input, output) = (w.nrows(), w.ncols());
    let rows = rows_of(x, input);
    matmul(
        MatMut::from_row_major_slice_mut(out, rows, output),
        Accum::Replace,
        MatRef::from_row_major_slice(x, rows, input),
        w,
        1.0,
        Par::Seq,
    );
}

/// Adds the bias to every row of `rows`, then normalises, scales, shifts and clips it, in
/// place.
#[inline]
fn normalise(rows: &mut [f32], channels: &Channels) {
    let Channels { bias, gamma, beta } = *channels;
    for o in rows.chunks_exact_mut(gamma.len()) {
        for (o, &b) in o.iter_mut().zip(bias) {
            *o += b;
        }
        let (mean, r) = statistics(o);
        for ((o, &g), &b) in o.iter_mut().zip(gamma).zip(beta) {
            *o = ((*o - mean) * r * g + b).max(0.0);
        }
    }
}

/// The forward pass on the rows of `x` (`weight.len() / channels` values each) with the
/// row-major weight `[input, output]`: the output, and with `keep` the product `x · weight`
/// (before the bias) that [`backward`] needs (empty otherwise). Each block of
/// [`ROWS_PER_TASK`] rows is multiplied and normalised while it is in cache.
pub fn forward(x: &[f32], weight: &[f32], channels: &Channels, keep: bool) -> (Vec<f32>, Vec<f32>) {
    let c = channels.gamma.len();
    let input = rows_of(weight, c);
    let rows = rows_of(x, input);
    let mut out = vec![0.0f32; rows * c];
    let mut kept = vec![0.0f32; if keep { rows * c } else { 0 }];
    if rows * c == 0 {
        return (out, kept);
    }
    let w = MatRef::from_row_major_slice(weight, input, c);
    let arch = pulp::Arch::new();
    let block = |out: &mut [f32], x: &[f32], kept: Option<&mut [f32]>| {
        product(out, x, w);
        if let Some(kept) = kept {
            kept.copy_from_slice(out);
        }
        arch.dispatch(|| normalise(out, channels));
    };
    let (xs, outs) = (x.par_chunks(ROWS_PER_TASK * input), out.par_chunks_mut(ROWS_PER_TASK * c));
    if keep {
        outs.zip(kept.par_chunks_mut(ROWS_PER_TASK * c))
            .zip(xs)
            .for_each(|((out, kept), x)| block(out, x, Some(kept)));
    } else {
        outs.zip(xs).for_each(|(out, x)| block(out, x, None));
    }
    (out, kept)
}

/// The backward pass of one block of rows through the normalisation: overwrites the output's
/// gradient `grad` with the product's, and returns the block's gradients of the bias, `γ`
/// and `β`.
fn normalise_backward(z: &[f32], channels: &Channels, grad: &mut [f32]) -> [Vec<f32>; 3] {
    let Channels { bias, gamma, beta } = *channels;
    let c = gamma.len();
    let [mut dbias, mut dgamma, mut dbeta] = [0; 3].map(|_| vec![0.0f32; c]);
    let [mut y, mut xhat, mut ghat] = [0; 3].map(|_| vec![0.0f32; c]);
    for (g, row) in grad.chunks_exact_mut(c).zip(z.chunks_exact(c)) {
        for ((y, &v), &b) in y.iter_mut().zip(row).zip(bias) {
            *y = v + b;
        }
        let (mean, r) = statistics(&y);
        // x̂, the output's gradient where the output is positive (ReLU), and the γ, β
        // gradients of this row.
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
        for (((dx, d), &gh), &xh) in g.iter_mut().zip(dbias.iter_mut()).zip(&ghat).zip(&xhat) {
            *dx = r * (gh - m1 - xh * m2);
            *d += *dx;
        }
    }
    [dbias, dgamma, dbeta]
}

/// The backward pass, from the layer's input `x`, row-major weight and kept product (see
/// [`forward`]) and the output's gradient `grad` (overwritten with the product's): the
/// gradients of the input (empty unless `input_gradient`), the weight, the bias, `γ` and
/// `β`. Each block of [`ROWS_PER_TASK`] rows goes through the normalisation and both matrix
/// products while it is in cache; the blocks' parameter gradients are added in block order,
/// so the result does not depend on the thread count.
pub fn backward(
    x: &[f32],
    weight: &[f32],
    z: &[f32],
    channels: &Channels,
    grad: &mut [f32],
    input_gradient: bool,
) -> [Vec<f32>; 5] {
    let c = channels.gamma.len();
    let input = rows_of(weight, c);
    let rows = rows_of(z, c);
    let mut dx = vec![0.0f32; if input_gradient { rows * input } else { 0 }];
    let mut sums = [input * c, c, c, c].map(|n| vec![0.0f32; n]);
    if rows * c == 0 {
        let [dw, db, dg, dbe] = sums;
        return [dx, dw, db, dg, dbe];
    }
    let w = MatRef::from_row_major_slice(weight, input, c);
    let arch = pulp::Arch::new();
    let block = |grad: &mut [f32], z: &[f32], x: &[f32], dx: Option<&mut [f32]>| {
        let [db, dg, dbe] = arch.dispatch(|| normalise_backward(z, channels, grad));
        let r = rows_of(z, c);
        let dz = MatRef::from_row_major_slice(grad, r, c);
        if let Some(dx) = dx {
            matmul(
                MatMut::from_row_major_slice_mut(dx, r, input),
                Accum::Replace,
                dz,
                w.transpose(),
                1.0,
                Par::Seq,
            );
        }
        let mut dw = vec![0.0f32; input * c];
        matmul(
            MatMut::from_row_major_slice_mut(&mut dw, input, c),
            Accum::Replace,
            MatRef::from_row_major_slice(x, r, input).transpose(),
            dz,
            1.0,
            Par::Seq,
        );
        [dw, db, dg, dbe]
    };
    let (grads, zs) = (grad.par_chunks_mut(ROWS_PER_TASK * c), z.par_chunks(ROWS_PER_TASK * c));
    let xs = x.par_chunks(ROWS_PER_TASK * input);
    let partial: Vec<[Vec<f32>; 4]> = if input_gradient {
        grads
            .zip(zs)
            .zip(xs)
            .zip(dx.par_chunks_mut(ROWS_PER_TASK * input))
            .map(|(((g, z), x), dx)| block(g, z, x, Some(dx)))
            .collect()
    } else {
        grads.zip(zs).zip(xs).map(|((g, z), x)| block(g, z, x, None)).collect()
    };
    for block in &partial {
        for (sum, part) in sums.iter_mut().zip(block) {
            sum.iter_mut().zip(part).for_each(|(a, b)| *a += b);
        }
    }
    let [dw, db, dg, dbe] = sums;
    [dx, dw, db, dg, dbe]
}
