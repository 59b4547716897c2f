//! PointNet++ layers (Qi et al. 2017) over the shared MLPs of [`super::mlp`]: set
//! abstraction with ball grouping (one or several radii) or global pooling, and feature
//! propagation by 3-NN inverse-distance interpolation.
//!
//! Sampling and grouping indices come from [`crate::network::sampling`] on the points'
//! values, with no gradient; grouping itself is a gather (`select`) on the tensors, so
//! gradients reach every grouped point and feature.

use burn::prelude::*;
use burn::tensor::TensorData;

use crate::network::mlp::SharedMlp;
use crate::network::pool::max_pool;
use crate::network::sampling::{
    ball_query, farthest_point_sampling, three_nn_weighted, SamplingError,
};

/// One grouping scale of a set abstraction level: a ball and the shared MLP on its members.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupScale {
    /// Ball radius of the grouping, normalised units.
    pub radius: f32,
    /// Points grouped per centre.
    pub neighbours: usize,
    /// Widths of the shared MLP on (relative position, features).
    pub widths: Vec<usize>,
}

/// Settings of a [`SetAbstraction`]: its centres and one or more grouping scales (several
/// scales make the paper's multi-scale grouping; their pooled features are concatenated).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SetAbstractionConfig {
    /// Centres picked by farthest point sampling.
    pub centres: usize,
    /// Grouping scales around the same centres.
    pub scales: Vec<GroupScale>,
}

impl SetAbstractionConfig {
    /// A single-scale level.
    pub fn single(centres: usize, radius: f32, neighbours: usize, widths: Vec<usize>) -> Self {
        Self { centres, scales: vec![GroupScale { radius, neighbours, widths }] }
    }

    /// Channels of the level's output: the last widths of all scales, summed.
    pub fn output(&self) -> usize {
        self.scales.iter().map(|s| s.widths.last().copied().unwrap_or(3)).sum()
    }

    /// The layer for inputs with `features` channels (0 for positions only); with
    /// `centre_features` each group member's features are taken relative to its centre's.
    pub fn init(&self, features: usize, centre_features: bool, device: &Device) -> SetAbstraction {
        let scales = self
            .scales
            .iter()
            .map(|s| ScaleGroup {
                mlp: SharedMlp::new(3 + features, &s.widths, device),
                radius: s.radius,
                neighbours: s.neighbours,
            })
            .collect();
        SetAbstraction { scales, centres: self.centres, centre_features }
    }
}

/// One scale of a [`SetAbstraction`].
#[derive(Module, Debug)]
struct ScaleGroup {
    mlp: SharedMlp,
    #[module(skip)]
    radius: f32,
    #[module(skip)]
    neighbours: usize,
}

/// Set abstraction: FPS centres, ball groups around them (at one or more radii), a shared
/// MLP on each member's position relative to its centre and its features, max-pooled per
/// group; the scales' pooled features are concatenated.
#[derive(Module, Debug)]
pub struct SetAbstraction {
    scales: Vec<ScaleGroup>,
    #[module(skip)]
    centres: usize,
    #[module(skip)]
    centre_features: bool,
}

impl SetAbstraction {
    /// Abstracts a batch of clouds; errors if a cloud has fewer points than centres.
    ///
    /// # Shapes
    /// `xyz: [batch, points, 3]`, `features: [batch, points, channels]` ->
    /// `([batch, centres, 3], [batch, centres, output])`
    pub fn forward(
        &self,
        xyz: Tensor<3>,
        features: Option<Tensor<3>>,
    ) -> Result<(Tensor<3>, Tensor<3>), SamplingError> {
        let [batch, n, _] = xyz.dims();
        let clouds = point_lists(&xyz);
        let mut centre_idx = Vec::with_capacity(batch * self.centres);
        let mut centres = Vec::with_capacity(batch);
        for (b, cloud) in clouds.iter().enumerate() {
            let chosen = farthest_point_sampling(cloud, self.centres)?;
            centres.push(chosen.iter().map(|&i| cloud[i]).collect::<Vec<_>>());
            centre_idx.extend(chosen.into_iter().map(|i| i + b * n));
        }
        let device = xyz.device();
        let new_xyz =
            gather_rows(xyz.clone(), &centre_idx, &device).reshape([batch, self.centres, 3]); // [batch, centres, 3]
        let centre_f = match &features {
            Some(f) if self.centre_features => {
                let channels = f.dims()[2];
                Some(gather_rows(f.clone(), &centre_idx, &device).reshape([
                    batch,
                    self.centres,
                    1,
                    channels,
                ])) // [batch, centres, 1, channels]
            }
            _ => None,
        };
        let pooled =
            self.scales
                .iter()
                .map(|scale| {
                    let k = scale.neighbours;
                    let mut group_idx = Vec::with_capacity(batch * self.centres * k);
                    for (b, (cloud, c)) in clouds.iter().zip(&centres).enumerate() {
                        group_idx.extend(
                            ball_query(cloud, c, scale.radius, k).into_iter().map(|i| i + b * n),
                        );
                    }
                    let grouped_xyz = gather_rows(xyz.clone(), &group_idx, &device).reshape([
                        batch,
                        self.centres,
                        k,
                        3,
                    ]); // [batch, centres, k, 3]
                    let relative = grouped_xyz - new_xyz.clone().unsqueeze_dim::<4>(2);
                    let input =
                        match &features {
                            Some(f) => {
                                let channels = f.dims()[2];
                                let grouped = gather_rows(f.clone(), &group_idx, &device)
                                    .reshape([batch, self.centres, k, channels]); // [batch, centres, k, channels]
                                let grouped = match &centre_f {
                                    Some(c) => grouped - c.clone(),
                                    None => grouped,
                                };
                                Tensor::cat(vec![relative, grouped], 3)
                            }
                            None => relative,
                        };
                    max_pool(scale.mlp.forward(input)).squeeze_dim::<3>(2) // [batch, centres, out]
                })
                .collect();
        Ok((new_xyz, Tensor::cat(pooled, 2)))
    }
}

/// Global set abstraction: one group of every point, pooled into one feature per cloud.
#[derive(Module, Debug)]
pub struct GlobalAbstraction {
    mlp: SharedMlp,
}

impl GlobalAbstraction {
    /// The layer for inputs with `features` channels, MLP `widths`.
    pub fn new(features: usize, widths: &[usize], device: &Device) -> Self {
        Self { mlp: SharedMlp::new(3 + features, widths, device) }
    }

    /// # Shapes
    /// `xyz: [batch, points, 3]`, `features: [batch, points, channels]` -> `[batch, 1, out]`
    pub fn forward(&self, xyz: Tensor<3>, features: Tensor<3>) -> Tensor<3> {
        max_pool(self.mlp.forward(Tensor::cat(vec![xyz, features], 2))) // [batch, 1, out]
    }
}

/// Feature propagation: features of a coarse set interpolated onto a dense set by 3-NN
/// inverse-distance weights, joined with the dense set's own (skip) features, then a shared
/// MLP.
#[derive(Module, Debug)]
pub struct FeaturePropagation {
    mlp: SharedMlp,
}

impl FeaturePropagation {
    /// The layer for `input` channels (skip plus interpolated) and MLP `widths`.
    pub fn new(input: usize, widths: &[usize], device: &Device) -> Self {
        Self { mlp: SharedMlp::new(input, widths, device) }
    }

    /// Errors if the coarse set has fewer than 3 points.
    ///
    /// # Shapes
    /// `dense: [batch, n, 3]`, `coarse: [batch, m, 3]`, `skip: [batch, n, c1]`,
    /// `features: [batch, m, c2]` -> `[batch, n, widths.last()]`
    pub fn forward(
        &self,
        dense: Tensor<3>,
        coarse: Tensor<3>,
        skip: Option<Tensor<3>>,
        features: Tensor<3>,
    ) -> Result<Tensor<3>, SamplingError> {
        let interpolated = interpolate_features(&dense, &coarse, features, 1)?;
        let input = match skip {
            Some(s) => Tensor::cat(vec![s, interpolated], 2),
            None => interpolated,
        };
        Ok(self.mlp.forward(input))
    }
}

/// `features` of the `coarse` points carried to the `dense` ones by their 3 nearest coarse
/// points, weighted by `1/d` (`power` 1, every propagation layer of the backbones) or `1/d²`
/// (`power` 2, the release's `three_interpolate` on its squared distances).
///
/// # Shapes
/// `dense: [batch, n, 3]`, `coarse: [batch, m, 3]`, `features: [batch, m, c]` ->
/// `[batch, n, c]`
pub(crate) fn interpolate_features(
    dense: &Tensor<3>,
    coarse: &Tensor<3>,
    features: Tensor<3>,
    power: i32,
) -> Result<Tensor<3>, SamplingError> {
    let [batch, n, _] = dense.dims();
    let [_, m, channels] = features.dims();
    let (targets, sources) = (point_lists(dense), point_lists(coarse));
    let mut idx = Vec::with_capacity(batch * n * 3);
    let mut weights = Vec::with_capacity(batch * n * 3);
    for (b, (t, s)) in targets.iter().zip(&sources).enumerate() {
        let (i, w) = three_nn_weighted(t, s, power)?;
        idx.extend(i.into_iter().map(|i| i + b * m));
        weights.extend(w);
    }
    let device = dense.device();
    let neighbours = gather_rows(features, &idx, &device).reshape([batch, n, 3, channels]); // [batch, n, 3, c]
    let weights = Tensor::<4>::from_data(TensorData::new(weights, [batch, n, 3, 1]), &device);
    Ok((neighbours * weights).sum_dim(2).squeeze_dim::<3>(2))
}

/// The clouds of a batch as point lists, for the index computations.
pub fn point_lists(xyz: &Tensor<3>) -> Vec<Vec<[f32; 3]>> {
    let [batch, n, _] = xyz.dims();
    let flat: Vec<f32> =
        xyz.to_data().convert::<f32>().try_to_vec().expect("float data converts to f32");
    (0..batch)
        .map(|b| {
            (0..n)
                .map(|i| {
                    let k = (b * n + i) * 3;
                    [flat[k], flat[k + 1], flat[k + 2]]
                })
                .collect()
        })
        .collect()
}

/// Rows `indices` of `x` flattened over its first two dimensions, as `[indices.len(), c]`.
fn gather_rows(x: Tensor<3>, indices: &[usize], device: &Device) -> Tensor<2> {
    let [batch, n, c] = x.dims();
    let idx: Vec<i64> = indices.iter().map(|&i| i as i64).collect();
    let idx = Tensor::<1, Int>::from_data(TensorData::new(idx, [indices.len()]), device);
    x.reshape([batch * n, c]).select(0, idx) // [indices, c]
}

#[cfg(test)]
mod tests;
