//! From pairs to tensors: the farthest-point subsets each module works on, the ground truth
//! on those subsets (flow, correspondence targets, parts), and the training augmentation.

use burn::prelude::*;
use burn::tensor::TensorData;
use pairs::math::{Matrix3, Vector3};
use pairs::Pair;

use crate::network::input::{points_tensor, Prepared};
use crate::network::sampling::{distance2, SamplingError};
use crate::train::config::NetworkConfig;

/// The ground truth of a batch on its subsets, as tensors for the losses.
#[derive(Debug, Clone)]
pub struct Truth {
    /// Flow on P's correspondence subset, `[batch, m, 3]`.
    pub flow: Tensor<3>,
    /// 1 where P's subset point has a correspondence in Q, `[batch, m]`.
    pub visible: Tensor<2>,
    /// 1 where it also has a same-part point in Q's subset to match, `[batch, m]`.
    pub matched: Tensor<2>,
    /// Index into Q's subset of the match target, `[batch, m]` (0 where unmatched).
    pub targets: Tensor<2, Int>,
    /// Parts `0..K` on P's segmentation subset, `[batch, s]`.
    pub parts: Tensor<2, Int>,
    /// K of every pair (parts present in the segmentation subset).
    pub parts_per_pair: Vec<usize>,
}

/// A training batch: the subsets' positions and their truth.
#[derive(Debug, Clone)]
pub struct TrainingBatch {
    /// P's correspondence subsets, `[batch, m, 3]`.
    pub p: Tensor<3>,
    /// Q's correspondence subsets, `[batch, m, 3]`.
    pub q: Tensor<3>,
    /// Their ground truth.
    pub truth: Truth,
}

impl TrainingBatch {
    /// Builds the batch of `pairs`, each rotated by its `rotations` entry.
    pub fn new(
        pairs: &[Pair],
        rotations: &[Matrix3],
        config: &NetworkConfig,
        device: &Device,
    ) -> Result<Self, SamplingError> {
        let (m, s) = (config.corr_points, config.seg_points);
        let mut prepared = Vec::with_capacity(pairs.len());
        let (mut flow, mut visible, mut matched, mut targets, mut parts) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let mut parts_per_pair = Vec::new();
        for (pair, rotation) in pairs.iter().zip(rotations) {
            let prep = Prepared::new(pair.input(), m, rotation)?;
            let truth = pair.truth();
            let true_flow =
                truth.flow.as_deref().ok_or_else(|| SamplingError::NoFlow(pair.id().into()))?;
            for &i in &prep.p_subset {
                let f: Vector3 = rotation * true_flow[i];
                flow.extend([f.x, f.y, f.z]);
                let moved = [prep.p[i][0] + f.x, prep.p[i][1] + f.y, prep.p[i][2] + f.z];
                let target = truth.corr_mask[i]
                    .then(|| {
                        prep.q_subset
                            .iter()
                            .enumerate()
                            .filter(|(_, &j)| truth.part_q[j] == truth.part_p[i])
                            .min_by(|(_, &a), (_, &b)| {
                                distance2(&prep.q[a], &moved)
                                    .total_cmp(&distance2(&prep.q[b], &moved))
                            })
                            .map(|(k, _)| k)
                    })
                    .flatten();
                visible.push(if truth.corr_mask[i] { 1.0f32 } else { 0.0 });
                matched.push(if target.is_some() { 1.0f32 } else { 0.0 });
                targets.push(target.unwrap_or(0) as i64);
            }
            let mut ids: Vec<u8> = Vec::new();
            for &i in &prep.p_subset[..s] {
                let part = truth.part_p[i];
                let id = ids.iter().position(|&x| x == part).unwrap_or_else(|| {
                    ids.push(part);
                    ids.len() - 1
                });
                parts.push(id as i64);
            }
            parts_per_pair.push(ids.len());
            prepared.push(prep);
        }
        let b = pairs.len();
        let floats2 = |v: Vec<f32>| Tensor::<2>::from_data(TensorData::new(v, [b, m]), device);
        let truth = Truth {
            flow: Tensor::from_data(TensorData::new(flow, [b, m, 3]), device),
            visible: floats2(visible),
            matched: floats2(matched),
            targets: Tensor::from_data(TensorData::new(targets, [b, m]), device),
            parts: Tensor::from_data(TensorData::new(parts, [b, s]), device),
            parts_per_pair,
        };
        let p: Vec<_> = prepared.iter().map(Prepared::p_points).collect();
        let q: Vec<_> = prepared.iter().map(Prepared::q_points).collect();
        Ok(Self { p: points_tensor(&p, device), q: points_tensor(&q, device), truth })
    }
}
