//! From pairs to tensors: the farthest-point subsets each module works on, the ground truth
//! on those subsets (flow, correspondence targets, parts), and the training augmentation.

use burn::prelude::*;
use burn::tensor::TensorData;
use pairs::math::{Matrix3, Point3, Vector3};
use pairs::{Pair, PairInput};

use crate::network::sampling::{distance2, farthest_point_sampling, SamplingError};
use crate::train::config::NetworkConfig;

/// A pair's clouds as plain points, optionally rotated, with their farthest-point subsets.
#[derive(Debug, Clone)]
pub struct Prepared {
    /// P's points.
    pub p: Vec<[f32; 3]>,
    /// Q's points.
    pub q: Vec<[f32; 3]>,
    /// Indices of P's correspondence subset (its first `seg_points` are the segmentation
    /// subset: a farthest-point sequence's prefix is itself a farthest-point sample).
    pub p_subset: Vec<usize>,
    /// Indices of Q's correspondence subset.
    pub q_subset: Vec<usize>,
}

fn plain(p: &Point3, rotation: &Matrix3) -> [f32; 3] {
    let v = rotation * p.coords;
    [v.x, v.y, v.z]
}

impl Prepared {
    /// Picks subsets of `m` points of `input`; `rotation` is applied to both clouds.
    pub fn new(input: &PairInput, m: usize, rotation: &Matrix3) -> Result<Self, SamplingError> {
        let p: Vec<[f32; 3]> = input.p.points.iter().map(|x| plain(x, rotation)).collect();
        let q: Vec<[f32; 3]> = input.q.points.iter().map(|x| plain(x, rotation)).collect();
        let p_subset = farthest_point_sampling(&p, m)?;
        let q_subset = farthest_point_sampling(&q, m)?;
        Ok(Self { p, q, p_subset, q_subset })
    }

    /// P's subset points.
    pub fn p_points(&self) -> Vec<[f32; 3]> {
        self.p_subset.iter().map(|&i| self.p[i]).collect()
    }

    /// Q's subset points.
    pub fn q_points(&self) -> Vec<[f32; 3]> {
        self.q_subset.iter().map(|&i| self.q[i]).collect()
    }
}

/// `[batch, m, 3]` from point lists of equal length.
pub fn points_tensor(clouds: &[Vec<[f32; 3]>], device: &Device) -> Tensor<3> {
    let m = clouds.first().map_or(0, Vec::len);
    let flat: Vec<f32> = clouds.iter().flatten().flatten().copied().collect();
    Tensor::from_data(TensorData::new(flat, [clouds.len(), m, 3]), device)
}

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
            for &i in &prep.p_subset {
                let f: Vector3 = rotation * truth.flow[i];
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
