//! Hypothesis generation: a rigid motion `(R_i, t_i)` per point of P from a PointNet++ on
//! (centred positions, flow), in the paper's residual parameterisation:
//! `R_i = proj(R̂_i + I)`, `t_i = -(R_i - I) x_i + f_i + t̂_i`. Without the projection
//! (`hypothesis_projection = false`, the authors' release) `R_i = R̂_i + I` is any linear
//! map, which fits the similarity a part undergoes between two separately normalised
//! clouds exactly.

use burn::prelude::*;

use crate::network::backbone::Backbone;
use crate::network::config::NetworkConfig;
use crate::network::rotation::{project_to_rotation, ITERATIONS};
use crate::network::sampling::SamplingError;

/// Rigid-motion hypotheses, one per point.
#[derive(Debug, Clone)]
pub struct Hypotheses {
    /// Rotations `[batch, s, 3, 3]`.
    pub rotations: Tensor<4>,
    /// Translations `[batch, s, 3]`.
    pub translations: Tensor<3>,
}

/// The hypothesis generator.
#[derive(Module, Debug)]
pub struct HypothesisModule {
    points: Backbone,
    #[module(skip)]
    project: bool,
}

impl HypothesisModule {
    /// The module with `config`'s sizes.
    pub fn new(config: &NetworkConfig, device: &Device) -> Self {
        Self {
            points: config.hypothesis.init(3, 12, true, device),
            project: config.hypothesis_projection,
        }
    }

    /// Hypotheses for the first `s` points of P (the backbone sees all m points).
    ///
    /// # Shapes
    /// `p, flow: [batch, m, 3]` -> rotations `[batch, s, 3, 3]`, translations `[batch, s, 3]`
    pub fn forward(
        &self,
        p: Tensor<3>,
        flow: Tensor<3>,
        s: usize,
    ) -> Result<Hypotheses, SamplingError> {
        let [batch, _, _] = p.dims();
        let centred = p.clone() - p.clone().mean_dim(1);
        let out = self.points.forward(centred, Some(flow.clone()))?.slice([0..batch, 0..s]); // [batch, s, 12]
        let residual = out.clone().slice([0..batch, 0..s, 0..9]).reshape([batch * s, 3, 3]);
        let eye = Tensor::<2>::eye(3, &p.device()).unsqueeze_dim::<3>(0);
        let rotations = if self.project {
            project_to_rotation(residual + eye.clone(), ITERATIONS) // [batch s, 3, 3]
        } else {
            residual + eye.clone()
        };
        let x = p.slice([0..batch, 0..s]).reshape([batch * s, 3, 1]);
        let turned = (rotations.clone() - eye).matmul(x).reshape([batch, s, 3]);
        let f = flow.slice([0..batch, 0..s]);
        let translations = f - turned + out.slice([0..batch, 0..s, 9..12]);
        Ok(Hypotheses { rotations: rotations.reshape([batch, s, 3, 3]), translations })
    }
}
