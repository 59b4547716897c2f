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

/// `[batch, m, 3]` from point lists of equal length.
pub fn points_tensor(clouds: &[Vec<[f32; 3]>], device: &Device) -> Tensor<3> {
    let m = clouds.first().map_or(0, Vec::len);
    let flat: Vec<f32> = clouds.iter().flatten().flatten().copied().collect();
    Tensor::from_data(TensorData::new(flat, [clouds.len(), m, 3]), device)
}
