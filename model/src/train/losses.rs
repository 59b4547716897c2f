//! The paper's training losses ("Multi-task objective function") as pure tensor functions.
//! Each returns a scalar tensor (shape `[1]`) averaged over the pairs of the batch; the
//! weights of the paper (λ_a = λ_b = λ_c = λ_d = 1, λ_e = 0.5, λ_f = λ_g = 1) are applied by
//! the caller ([`crate::train::objective`]).

use burn::prelude::*;
use burn::tensor::{activation, Bool, TensorData};
use pairs::metrics::max_assignment;

/// Binary cross-entropy of `logits` against 0/1 `targets`, elementwise, in the stable form
/// `max(x, 0) - x y + log(1 + exp(-|x|))`.
pub fn bce_with_logits<const D: usize>(logits: Tensor<D>, targets: Tensor<D>) -> Tensor<D> {
    logits.clone().clamp_min(0.0) - logits.clone() * targets + logits.abs().neg().exp().log1p()
}

/// `sum(values * weights) / max(sum(weights), 1)`: a mean over the weighted entries.
fn weighted_mean<const D: usize>(values: Tensor<D>, weights: Tensor<D>) -> Tensor<1> {
    (values * weights.clone()).sum() / weights.sum().clamp_min(1.0)
}

/// Correspondence loss `L_a + L_b`: softmax cross-entropy of each matched point's true
/// match among the points of Q, and binary cross-entropy of the correspondence mask.
///
/// `matched` selects the points whose `targets` entry is meaningful (those with a true match
/// among the given points of Q); `mask` is the correspondence mask's target.
///
/// # Shapes
/// `logits: [batch, n, m]`, `targets: [batch, n]` (indices into m), `matched: [batch, n]`,
/// `mask_logits: [batch, n]`, `mask: [batch, n]` (1 has a correspondence, 0 not) -> `[1]`
pub fn correspondence_loss(
    logits: Tensor<3>,
    targets: Tensor<2, Int>,
    matched: Tensor<2>,
    mask_logits: Tensor<2>,
    mask: Tensor<2>,
) -> Tensor<1> {
    let picked = activation::log_softmax(logits, 2).gather(2, targets.unsqueeze_dim::<3>(2)); // [batch, n, 1]
    let l_a = weighted_mean(picked.squeeze_dim::<2>(2).neg(), matched);
    let l_b = bce_with_logits(mask_logits, mask).mean();
    l_a + l_b
}

/// Flow loss: the mean squared error of the flow over the points that have a
/// correspondence (`visible` 1); points without one have no defined flow.
///
/// # Shapes
/// `predicted, truth: [batch, n, 3]`, `visible: [batch, n]` -> `[1]`
pub fn flow_loss(predicted: Tensor<3>, truth: Tensor<3>, visible: Tensor<2>) -> Tensor<1> {
    let squared = (predicted - truth).powf_scalar(2.0).sum_dim(2).squeeze_dim::<2>(2); // [batch, n]
    weighted_mean(squared, visible)
}

/// `same[b, i, j]` = 1 where points i and j of pair b belong to the same part.
///
/// # Shapes
/// `parts: [batch, n]` -> `[batch, n, n]`
pub fn same_part(parts: Tensor<2, Int>) -> Tensor<3> {
    let a = parts.clone().unsqueeze_dim::<3>(2); // [batch, n, 1]
    let b = parts.unsqueeze_dim::<3>(1); // [batch, 1, n]
    let [batch, n, _] = a.dims();
    let same: Tensor<3, Bool> = a.expand([batch, n, n]).equal(b.expand([batch, n, n]));
    same.float()
}

/// Rigid-motion loss: for every point i's hypothesis `(R_i, t_i)` and every point j of the
/// same part, `||q_j - (R_i p_j + t_i)||²`, averaged over such (i, j) with both matched;
/// `per_row` first averages over j within each row i and then over the rows (the release's
/// row-normalised weights), so that every hypothesis counts once and a part weighs as its
/// point count rather than its square.
///
/// # Shapes
/// `rotations: [batch, n, 3, 3]`, `translations: [batch, n, 3]`, `p: [batch, n, 3]`,
/// `q: [batch, n, 3]` (each point's true position in Q), `parts: [batch, n]`,
/// `matched: [batch, n]` -> `[1]`
pub fn motion_loss(
    rotations: Tensor<4>,
    translations: Tensor<3>,
    p: Tensor<3>,
    q: Tensor<3>,
    parts: Tensor<2, Int>,
    matched: Tensor<2>,
    per_row: bool,
) -> Tensor<1> {
    let moved = rotations.matmul(p.swap_dims(1, 2).unsqueeze_dim::<4>(1)); // [batch, n, 3, n]
    let moved = moved.swap_dims(2, 3) + translations.unsqueeze_dim::<4>(2); // [batch, n, n, 3]
    let error = (q.unsqueeze_dim::<4>(1) - moved).powf_scalar(2.0).sum_dim(3).squeeze_dim::<3>(3); // [batch, n, n]
    let both = matched.clone().unsqueeze_dim::<3>(2) * matched.unsqueeze_dim::<3>(1); // [batch, n, n]
    let weights = same_part(parts) * both;
    if per_row {
        let rows = weights.clone().sum_dim(2).clamp_min(1.0); // [batch, n, 1]
        weighted_mean(error, weights / rows)
    } else {
        weighted_mean(error, weights)
    }
}

/// Support loss `L_e`: binary cross-entropy of the support matrix against "same part".
///
/// # Shapes
/// `logits: [batch, n, n]`, `parts: [batch, n]` -> `[1]`
pub fn support_loss(logits: Tensor<3>, parts: Tensor<2, Int>) -> Tensor<1> {
    bce_with_logits(logits, same_part(parts)).mean()
}

/// Segment loss `L_f` in a non-negative form: for every ground-truth part, one minus the
/// relaxed IoU of the predicted soft segment matched to it by the Hungarian algorithm (0 if
/// none is), summed over parts and averaged over pairs. With K parts only the first K steps
/// take part in the matching (the paper's sum over `t = 1..K`): the steps after them exist
/// to learn to stop, and inference reads segments from the first steps, up to the stop. This is the paper's
/// `-Σ IoU` plus the number of parts, a constant: the gradients are the same, and a perfect
/// prediction costs 0. Parts are `0..K` per pair.
///
/// # Shapes
/// `segments: [batch, steps, n]` (probabilities), `parts: [batch, n]` -> `[1]`
pub fn segment_loss(segments: Tensor<3>, parts: Tensor<2, Int>) -> Tensor<1> {
    let [batch, steps, n] = segments.dims();
    let device = segments.device();
    let ids: Vec<i64> =
        parts.to_data().convert::<i64>().try_to_vec().expect("int data converts to i64");
    let k = ids.iter().copied().max().map_or(1, |m| m as usize + 1);
    let parts_per_pair: Vec<usize> = ids
        .chunks(n.max(1))
        .map(|pair| pair.iter().copied().max().map_or(0, |m| m as usize + 1))
        .collect();
    let parts_total: usize = parts_per_pair.iter().sum();
    let truth = one_hot(parts, k); // [batch, n, k]
    let inter = segments.clone().matmul(truth.clone()); // [batch, steps, k]
    let size_y = segments.sum_dim(2); // [batch, steps, 1]
    let size_t = truth.sum_dim(1); // [batch, 1, k]
    let iou = inter.clone() / (size_y + size_t - inter + 1e-6); // [batch, steps, k]
    let values: Vec<f32> = iou.to_data().convert::<f32>().try_to_vec().expect("f32");
    let mut chosen = vec![0.0f32; batch * steps * k];
    for (b, &parts_here) in parts_per_pair.iter().enumerate() {
        let rows = parts_here.min(steps);
        let block: Vec<f64> =
            values[b * steps * k..][..rows * k].iter().map(|&v| f64::from(v)).collect();
        for (t, j) in max_assignment(&block, rows, k).into_iter().enumerate() {
            if let Some(j) = j {
                chosen[b * steps * k + t * k + j] = 1.0;
            }
        }
    }
    let chosen = Tensor::<3>::from_data(TensorData::new(chosen, [batch, steps, k]), &device);
    ((iou * chosen).sum().neg() + parts_total as f32) / batch as f32
}

/// Continuation loss `L_g`: with K parts, steps 0..K-2 should continue (1) and steps K-1
/// onwards stop (0), as binary cross-entropy averaged over steps and pairs.
///
/// # Shapes
/// `logits: [batch, steps]`, `parts_per_pair: [batch]` -> `[1]`
pub fn continuation_loss(logits: Tensor<2>, parts_per_pair: &[usize]) -> Tensor<1> {
    let [batch, steps] = logits.dims();
    let targets: Vec<f32> = (0..batch * steps)
        .map(|i| if (i % steps) + 1 < parts_per_pair[i / steps] { 1.0 } else { 0.0 })
        .collect();
    let targets =
        Tensor::<2>::from_data(TensorData::new(targets, [batch, steps]), &logits.device());
    bce_with_logits(logits, targets).mean()
}

/// One-hot encoding of ids `0..k` along a new last dimension.
///
/// # Shapes
/// `ids: [batch, n]` -> `[batch, n, k]`
fn one_hot(ids: Tensor<2, Int>, k: usize) -> Tensor<3> {
    let [batch, n] = ids.dims();
    let classes = Tensor::<1, Int>::arange(0..k as i64, &ids.device())
        .reshape([1, 1, k])
        .expand([batch, n, k]);
    ids.unsqueeze_dim::<3>(2).expand([batch, n, k]).equal(classes).float()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn device() -> Device {
        Device::flex()
    }

    fn floats<const D: usize>(values: Vec<f32>, shape: [usize; D]) -> Tensor<D> {
        Tensor::from_data(TensorData::new(values, shape), &device())
    }

    fn ints(values: Vec<i64>, shape: [usize; 2]) -> Tensor<2, Int> {
        Tensor::from_data(TensorData::new(values, shape), &device())
    }

    fn scalar(t: Tensor<1>) -> f32 {
        t.into_scalar::<f32>()
    }

    #[test]
    fn uninformed_logits_cost_log_of_the_choices() {
        let l = correspondence_loss(
            floats(vec![0.0; 8], [1, 2, 4]),
            ints(vec![3, 1], [1, 2]),
            floats(vec![1.0, 0.0], [1, 2]),
            floats(vec![0.0; 2], [1, 2]),
            floats(vec![1.0, 0.0], [1, 2]),
        );
        assert!((scalar(l) - (4f32.ln() + 2f32.ln())).abs() < 1e-5);
        let s = support_loss(floats(vec![0.0; 4], [1, 2, 2]), ints(vec![0, 1], [1, 2]));
        assert!((scalar(s) - 2f32.ln()).abs() < 1e-5);
        // Confident and right costs almost nothing.
        let right = bce_with_logits(floats(vec![20.0, -20.0], [2]), floats(vec![1.0, 0.0], [2]));
        assert!(scalar(right.sum()) < 1e-6);
    }

    #[test]
    fn flow_loss_counts_visible_points_only() {
        let predicted = floats(vec![1.0, 0.0, 0.0, 9.0, 9.0, 9.0], [1, 2, 3]);
        let truth = floats(vec![0.0; 6], [1, 2, 3]);
        assert_eq!(scalar(flow_loss(predicted, truth, floats(vec![1.0, 0.0], [1, 2]))), 1.0);
    }

    #[test]
    fn motion_loss_is_zero_for_the_true_motion_and_grows_with_its_error() {
        let p = floats(vec![0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 2.0, 0.0], [1, 3, 3]);
        let eye: Vec<f32> =
            (0..3).flat_map(|_| [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]).collect();
        let rotations = floats(eye, [1, 3, 3, 3]);
        let parts = ints(vec![0, 0, 1], [1, 3]);
        let matched = floats(vec![1.0; 3], [1, 3]);
        let exact = motion_loss(
            rotations.clone(),
            floats(vec![0.0; 9], [1, 3, 3]),
            p.clone(),
            p.clone(),
            parts.clone(),
            matched.clone(),
            false,
        );
        assert_eq!(scalar(exact), 0.0);
        // Every hypothesis off by one unit along x: each same-part pair costs 1.
        let shifted: Vec<f32> = (0..3).flat_map(|_| [1.0, 0.0, 0.0]).collect();
        let off = motion_loss(
            rotations.clone(),
            floats(shifted, [1, 3, 3]),
            p.clone(),
            p.clone(),
            parts.clone(),
            matched.clone(),
            false,
        );
        assert!((scalar(off) - 1.0).abs() < 1e-6);
        // Only the lone point 2's hypothesis off by one: one of the five same-part pairs
        // costs 1 (pair average 1/5), but one of the three rows does (row average 1/3).
        let lone = floats(vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0], [1, 3, 3]);
        let loss = |per_row| {
            scalar(motion_loss(
                rotations.clone(),
                lone.clone(),
                p.clone(),
                p.clone(),
                parts.clone(),
                matched.clone(),
                per_row,
            ))
        };
        assert!((loss(false) - 0.2).abs() < 1e-6, "{}", loss(false));
        assert!((loss(true) - 1.0 / 3.0).abs() < 1e-6, "{}", loss(true));
    }

    #[test]
    fn segment_loss_matches_segments_to_parts_in_any_order() {
        // Parts {0, 1} and {2}; the segments come in the other order, plus an empty one.
        let segments = floats(vec![0.0, 0.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0], [1, 3, 3]);
        let parts = ints(vec![0, 0, 1], [1, 3]);
        assert!(scalar(segment_loss(segments, parts.clone())).abs() < 1e-4);
        // A right segment after the first K steps does not count.
        let late = floats(vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0], [1, 3, 3]);
        assert!((scalar(segment_loss(late, parts.clone())) - 2.0).abs() < 1e-4);
        // Half of part 0 in one segment: IoU 1/2 for it, 1 for part 1.
        let partial = floats(vec![1.0, 0.0, 0.0, 0.0, 0.0, 1.0], [1, 2, 3]);
        assert!((scalar(segment_loss(partial, parts)) - 0.5).abs() < 1e-4);
    }

    #[test]
    fn continuation_targets_stop_after_the_last_part() {
        // Three parts: continue, continue, stop, stop.
        let good = floats(vec![20.0, 20.0, -20.0, -20.0], [1, 4]);
        assert!(scalar(continuation_loss(good, &[3])) < 1e-6);
        let bad = floats(vec![-20.0, 20.0, -20.0, -20.0], [1, 4]);
        assert!((scalar(continuation_loss(bad, &[3])) - 5.0).abs() < 1e-3);
    }
}
