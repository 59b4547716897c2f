//! The PointNet++ segmentation backbone ("PointNet++S" in the paper's supplement): set
//! abstraction levels, a global level, feature propagation back to every input point, and a
//! linear output head. The feature extractor, the flow module and the hypothesis generator
//! are each one of these with their own sizes.

use burn::prelude::*;
use serde::{Deserialize, Serialize};

use crate::network::mlp::{Head, SharedMlp};
use crate::network::pointnet::{
    FeaturePropagation, GlobalAbstraction, SetAbstraction, SetAbstractionConfig,
};
use crate::network::sampling::SamplingError;

/// Sizes of a [`Backbone`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BackboneConfig {
    /// Set abstraction levels, finest first.
    pub levels: Vec<SetAbstractionConfig>,
    /// Widths of the global level's MLP (one group of all remaining points).
    pub global: Vec<usize>,
    /// Feature propagation MLP widths, coarsest first: one for the global level and one per
    /// set abstraction level.
    pub propagation: Vec<Vec<usize>>,
    /// Whether the first set abstraction level subtracts each centre's input features from
    /// its group members' (the release's `centralize_points`, used by the hypothesis
    /// generator on the flow): the level then sees the flow's local variation, which a
    /// rigid motion makes linear in the relative position, instead of the flow itself.
    #[serde(default)]
    pub centre_features: bool,
}

impl BackboneConfig {
    /// The backbone for inputs with `features` channels per point (0 for positions only) and
    /// `output` channels out per point; a `zero_head` starts by predicting 0 (see
    /// [`Head::new`]), otherwise the head is initialised like any layer (for features).
    ///
    /// Panics if there are no levels or `propagation` does not hold one entry per level plus
    /// one; configs are
    /// checked by [`crate::network::config::NetworkConfig::validate`] before they get here.
    pub fn init(
        &self,
        features: usize,
        output: usize,
        zero_head: bool,
        device: &Device,
    ) -> Backbone {
        assert!(!self.levels.is_empty(), "checked by validate");
        assert_eq!(self.propagation.len(), self.levels.len() + 1, "checked by validate");
        let mut channels = vec![features];
        // Level 0's skip connection carries each point's own position next to its input
        // features (as PointNet++'s part segmentation does), so outputs can tell
        // neighbouring points apart.
        let levels = self
            .levels
            .iter()
            .enumerate()
            .map(|(i, level)| {
                let centred = self.centre_features && i == 0 && features > 0;
                let layer = level.init(*channels.last().expect("non-empty"), centred, device);
                channels.push(level.output());
                layer
            })
            .collect();
        let coarsest = *channels.last().expect("non-empty");
        let global = GlobalAbstraction::new(coarsest, &self.global, device);
        let global_out = self.global.last().copied().unwrap_or(coarsest + 3);
        let top = SharedMlp::new(coarsest + global_out, &self.propagation[0], device);
        let mut width = top.output(coarsest + global_out);
        let propagation = (0..self.levels.len())
            .rev()
            .zip(&self.propagation[1..])
            .map(|(level, widths)| {
                let skip = channels[level] + if level == 0 { 3 } else { 0 };
                let layer = FeaturePropagation::new(skip + width, widths, device);
                width = widths.last().copied().unwrap_or(skip + width);
                layer
            })
            .collect();
        let head = if zero_head {
            Head::new(width, &[], output, device)
        } else {
            Head::dense(width, &[], output, device)
        };
        Backbone { levels, global, top, propagation, head }
    }

    /// Fewest input points the backbone accepts (its first level's centres).
    pub fn min_points(&self) -> usize {
        self.levels.first().map_or(1, |l| l.centres)
    }
}

/// PointNet++ with feature propagation: a per-point output for every input point.
#[derive(Module, Debug)]
pub struct Backbone {
    levels: Vec<SetAbstraction>,
    global: GlobalAbstraction,
    top: SharedMlp,
    propagation: Vec<FeaturePropagation>,
    head: Head,
}

impl Backbone {
    /// Errors if a cloud has fewer points than a level's centres, or a level fewer than 3.
    ///
    /// # Shapes
    /// `xyz: [batch, n, 3]`, `features: [batch, n, c]` -> `[batch, n, output]`
    pub fn forward(
        &self,
        xyz: Tensor<3>,
        features: Option<Tensor<3>>,
    ) -> Result<Tensor<3>, SamplingError> {
        let own = match &features {
            Some(f) => Tensor::cat(vec![xyz.clone(), f.clone()], 2),
            None => xyz.clone(),
        };
        let mut stack = vec![(xyz, features)];
        for level in &self.levels {
            let (x, f) = stack.last().expect("non-empty").clone();
            let (x, f) = level.forward(x, f)?;
            stack.push((x, Some(f)));
        }
        let (x, f) = stack.pop().expect("non-empty");
        let [batch, m, _] = x.dims();
        let f = f.expect("a backbone has at least one level (checked by validate)");
        let g = self.global.forward(x.clone(), f.clone()); // [batch, 1, global]
        let g = g.clone().expand([batch, m, g.dims()[2]]);
        let mut up = self.top.forward(Tensor::cat(vec![f, g], 2)); // [batch, m, c]
        let mut coarse = x;
        for layer in &self.propagation {
            let (dense, skip) = stack.pop().expect("one entry per level");
            let skip = if stack.is_empty() { Some(own.clone()) } else { skip };
            up = layer.forward(dense.clone(), coarse, skip, up)?;
            coarse = dense;
        }
        Ok(self.head.forward(up))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::network::pointnet::GroupScale;
    use crate::network::rng;
    use burn::tensor::{Distribution, TensorData};

    fn config() -> BackboneConfig {
        BackboneConfig {
            levels: vec![
                SetAbstractionConfig {
                    centres: 16,
                    scales: vec![
                        GroupScale { radius: 0.2, neighbours: 8, widths: vec![8, 8] },
                        GroupScale { radius: 0.4, neighbours: 8, widths: vec![8, 16] },
                    ],
                },
                SetAbstractionConfig::single(8, 0.6, 8, vec![16, 32]),
            ],
            global: vec![32, 64],
            propagation: vec![vec![32], vec![32, 16], vec![16, 16]],
            centre_features: false,
        }
    }

    #[test]
    fn every_input_point_gets_an_output_and_gradients_reach_the_features() {
        let device = Device::flex().autodiff();
        let net =
            rng::seeded(&device, 1, || rng::materialised(config().init(2, 5, false, &device)));
        let xyz = rng::random(&device, 2, [2, 40, 3], Distribution::Default);
        let f = rng::random(&device, 3, [2, 40, 2], Distribution::Default).require_grad();
        let out = net.forward(xyz, Some(f.clone())).expect("40 points");
        assert_eq!(out.dims(), [2, 40, 5]);
        let grads = out.powf_scalar(2.0).sum().backward();
        let g: Vec<f32> = f
            .grad(&grads)
            .expect("gradient")
            .into_data()
            .convert::<f32>()
            .try_to_vec()
            .expect("f32");
        assert!(g.iter().any(|v| *v != 0.0));
    }

    #[test]
    fn too_few_points_is_an_error() {
        let device = Device::flex();
        let net = rng::seeded(&device, 4, || rng::materialised(config().init(0, 3, true, &device)));
        let xyz = Tensor::<3>::from_data(TensorData::new(vec![0.1f32; 30], [1, 10, 3]), &device);
        assert!(matches!(net.forward(xyz, None), Err(SamplingError::TooFewPoints { .. })));
    }
}
