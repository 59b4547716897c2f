//! A pair as the network's input: both clouds as plain points (optionally rotated, for
//! the training augmentation and the rotation search) with the farthest-point subsets the
//! correspondence, flow and segmentation modules work on, and point lists as tensors.

use burn::prelude::*;
use burn::tensor::TensorData;
use pairs::math::{Matrix3, Point3};
use pairs::PairInput;

use crate::network::sampling::{farthest_point_sampling, SamplingError};

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

/// A batch of pairs as the correspondence and flow modules read it: the subsets' points and,
/// for the modules that run on every point (`features_on_cloud`, `flow_on_cloud`), the whole
/// clouds with the subsets' places in them.
#[derive(Debug, Clone)]
pub struct PairTensors {
    /// P's correspondence subsets, `[batch, m, 3]`.
    pub p: Tensor<3>,
    /// Q's correspondence subsets, `[batch, m, 3]`.
    pub q: Tensor<3>,
    /// The whole clouds, when a module needs them.
    pub clouds: Option<Clouds>,
}

/// Whole clouds of a batch and where its subsets sit in them.
#[derive(Debug, Clone)]
pub struct Clouds {
    /// Every point of P, `[batch, n, 3]`.
    pub p: Tensor<3>,
    /// Every point of Q, `[batch, n, 3]`.
    pub q: Tensor<3>,
    /// Index into P of each subset point, `[batch, m]`.
    pub p_subset: Tensor<2, Int>,
    /// Index into Q of each subset point, `[batch, m]`.
    pub q_subset: Tensor<2, Int>,
}

impl PairTensors {
    /// The tensors of `prepared` pairs (the whole clouds too when `with_clouds`; every pair
    /// must then have as many points as the first).
    pub fn new(prepared: &[Prepared], with_clouds: bool, device: &Device) -> Self {
        let p: Vec<_> = prepared.iter().map(Prepared::p_points).collect();
        let q: Vec<_> = prepared.iter().map(Prepared::q_points).collect();
        let clouds = with_clouds.then(|| {
            let indices = |pick: fn(&Prepared) -> &Vec<usize>| {
                let m = prepared.first().map_or(0, |x| pick(x).len());
                let flat: Vec<i64> =
                    prepared.iter().flat_map(|x| pick(x).iter().map(|&i| i as i64)).collect();
                Tensor::<2, Int>::from_data(TensorData::new(flat, [prepared.len(), m]), device)
            };
            let whole_p: Vec<_> = prepared.iter().map(|x| x.p.clone()).collect();
            let whole_q: Vec<_> = prepared.iter().map(|x| x.q.clone()).collect();
            Clouds {
                p: points_tensor(&whole_p, device),
                q: points_tensor(&whole_q, device),
                p_subset: indices(|x| &x.p_subset),
                q_subset: indices(|x| &x.q_subset),
            }
        });
        Self { p: points_tensor(&p, device), q: points_tensor(&q, device), clouds }
    }
}

/// Rows `indices` of `x` per batch entry: `x: [batch, n, c]`, `indices: [batch, m]` ->
/// `[batch, m, c]` (gradients reach the gathered rows).
pub fn gather_points(x: Tensor<3>, indices: Tensor<2, Int>) -> Tensor<3> {
    let [batch, m] = indices.dims();
    let c = x.dims()[2];
    x.gather(1, indices.unsqueeze_dim::<3>(2).expand([batch, m, c]))
}

/// `[batch, m, 3]` from point lists of equal length.
pub fn points_tensor(clouds: &[Vec<[f32; 3]>], device: &Device) -> Tensor<3> {
    let m = clouds.first().map_or(0, Vec::len);
    let flat: Vec<f32> = clouds.iter().flatten().flatten().copied().collect();
    Tensor::from_data(TensorData::new(flat, [clouds.len(), m, 3]), device)
}
