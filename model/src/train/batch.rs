//! From pairs to tensors: the farthest-point subsets each module works on, the ground truth
//! on those subsets (flow, correspondence targets, parts), and the training augmentation
//! (a rotation of both clouds; optionally a residual pair, P replaced by P moved by its true
//! part motions and a small rigid perturbation).

use std::borrow::Cow;

use burn::prelude::*;
use burn::tensor::TensorData;
use pairs::math::{Isometry3, Matrix3, Point3, Vector3};
use pairs::{Pair, PairInput};
use serde::{Deserialize, Serialize};

use crate::network::input::{PairTensors, Prepared};
use crate::network::sampling::{distance2, SamplingError};
use crate::train::config::NetworkConfig;

/// The target of the matching loss for a point `p_i` of P's subset with a correspondence.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum MatchingTarget {
    /// The point of Q's subset nearest `p_i + f_i` among those of `p_i`'s part (the default;
    /// a point whose part has no point in Q's subset is not matched).
    #[default]
    SamePart,
    /// The point of Q's subset nearest `p_i + f_i`, whatever its part (the authors' release).
    Nearest,
}

/// The ground truth of a batch on its subsets, as tensors for the losses.
#[derive(Debug, Clone)]
pub struct Truth {
    /// Flow on P's correspondence subset, `[batch, m, 3]`.
    pub flow: Tensor<3>,
    /// Flow on every point of P, `[batch, n, 3]` (for a network whose flow comes out there,
    /// `flow_on_cloud`).
    pub flow_cloud: Option<Tensor<3>>,
    /// 1 where P's subset point has a correspondence in Q, `[batch, m]`.
    pub visible: Tensor<2>,
    /// 1 where it also has a match target in Q's subset, `[batch, m]`.
    pub matched: Tensor<2>,
    /// Index into Q's subset of the match target, `[batch, m]` (0 where unmatched).
    pub targets: Tensor<2, Int>,
    /// Parts `0..K` on P's segmentation subset, `[batch, s]`.
    pub parts: Tensor<2, Int>,
    /// K of every pair (parts present in the segmentation subset).
    pub parts_per_pair: Vec<usize>,
}

/// A training batch: the subsets' positions (and whole clouds where the network reads them)
/// and their truth.
#[derive(Debug, Clone)]
pub struct TrainingBatch {
    /// The network's input.
    pub input: PairTensors,
    /// Its ground truth.
    pub truth: Truth,
}

/// How a batch is made from its pairs beyond their rotations.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct BatchOptions {
    /// The matching loss's target.
    pub target: MatchingTarget,
}

/// P of `input` replaced by its points moved by the true flow and then by `perturbation`
/// (a residual pair: what the iterations hand the network), with the flow that remains.
fn residual_pair(
    input: &PairInput,
    flow: &[Vector3],
    perturbation: &Isometry3,
) -> (PairInput, Vec<Vector3>) {
    let mut moved = input.clone();
    let (points, remaining): (Vec<Point3>, Vec<Vector3>) = input
        .p
        .points
        .iter()
        .zip(flow)
        .map(|(x, f)| {
            let target = x + f;
            let start = perturbation * target;
            (start, target - start)
        })
        .unzip();
    moved.p.points = points;
    (moved, remaining)
}

impl TrainingBatch {
    /// Builds the batch of `pairs`, each rotated by its `rotations` entry, with the release's
    /// defaults off ([`BatchOptions::default`]) and no residual pair.
    pub fn new(
        pairs: &[Pair],
        rotations: &[Matrix3],
        config: &NetworkConfig,
        device: &Device,
    ) -> Result<Self, SamplingError> {
        Self::with(pairs, rotations, &[], BatchOptions::default(), config, device)
    }

    /// Builds the batch of `pairs`, each rotated by its `rotations` entry; pair `i` becomes a
    /// residual pair where `residuals[i]` holds a perturbation (missing entries: none).
    pub fn with(
        pairs: &[Pair],
        rotations: &[Matrix3],
        residuals: &[Option<Isometry3>],
        options: BatchOptions,
        config: &NetworkConfig,
        device: &Device,
    ) -> Result<Self, SamplingError> {
        let (m, s) = (config.corr_points, config.seg_points);
        let clouds = config.features_on_cloud || config.flow_on_cloud;
        let mut prepared = Vec::with_capacity(pairs.len());
        let (mut flow, mut flow_cloud, mut visible, mut matched, mut targets, mut parts) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let mut parts_per_pair = Vec::new();
        for (k, (pair, rotation)) in pairs.iter().zip(rotations).enumerate() {
            let truth = pair.truth();
            let true_flow =
                truth.flow.as_deref().ok_or_else(|| SamplingError::NoFlow(pair.id().into()))?;
            let (input, true_flow) = match residuals.get(k).copied().flatten() {
                Some(perturbation) => {
                    let (input, remaining) = residual_pair(pair.input(), true_flow, &perturbation);
                    (Cow::Owned(input), Cow::Owned(remaining))
                }
                None => (Cow::Borrowed(pair.input()), Cow::Borrowed(true_flow)),
            };
            let prep = Prepared::new(&input, m, rotation)?;
            if config.flow_on_cloud {
                for f in true_flow.iter() {
                    let f: Vector3 = rotation * f;
                    flow_cloud.extend([f.x, f.y, f.z]);
                }
            }
            for &i in &prep.p_subset {
                let f: Vector3 = rotation * true_flow[i];
                flow.extend([f.x, f.y, f.z]);
                let moved = [prep.p[i][0] + f.x, prep.p[i][1] + f.y, prep.p[i][2] + f.z];
                let target = truth.corr_mask[i]
                    .then(|| {
                        prep.q_subset
                            .iter()
                            .enumerate()
                            .filter(|(_, &j)| {
                                options.target == MatchingTarget::Nearest
                                    || truth.part_q[j] == truth.part_p[i]
                            })
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
        let n = prepared.first().map_or(0, |p| p.p.len());
        let floats2 = |v: Vec<f32>| Tensor::<2>::from_data(TensorData::new(v, [b, m]), device);
        let truth = Truth {
            flow: Tensor::from_data(TensorData::new(flow, [b, m, 3]), device),
            flow_cloud: config
                .flow_on_cloud
                .then(|| Tensor::from_data(TensorData::new(flow_cloud, [b, n, 3]), device)),
            visible: floats2(visible),
            matched: floats2(matched),
            targets: Tensor::from_data(TensorData::new(targets, [b, m]), device),
            parts: Tensor::from_data(TensorData::new(parts, [b, s]), device),
            parts_per_pair,
        };
        Ok(Self { input: PairTensors::new(&prepared, clouds, device), truth })
    }

    /// P's correspondence subsets, `[batch, m, 3]`.
    pub fn p(&self) -> Tensor<3> {
        self.input.p.clone()
    }
}
