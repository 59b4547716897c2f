//! Weight averaging ("model soups", Wortsman et al. 2022): the element-wise mean of several
//! checkpoints of one network, for checkpoints fine-tuned from the same weights. A run at a
//! high learning rate moves its weights around a basin from step to step (two trajectories
//! that differed in the last bit of one loss 112 steps earlier validated at IoU 0.454 and
//! 0.494, `model/TRAINING.md`); the mean of points on such a walk sits nearer its middle.
//!
//! The mean is taken parameter by parameter in the order the files are given,
//! `((w_1 + w_2) + … + w_n) / n` in `f32`, so the same files in the same order give the same
//! bytes.

use std::path::PathBuf;

use burn::module::{Module, ModuleMapper, ModuleVisitor, Param};
use burn::prelude::*;

use crate::network::config::NetworkConfig;
use crate::network::PartInductionNet;
use crate::train::checkpoint::{load_weights, CheckpointError};

/// Why weights could not be averaged.
#[derive(Debug, thiserror::Error)]
pub enum AverageError {
    /// Fewer than one file.
    #[error("averaging needs at least one weights file")]
    Empty,
    /// A file could not be loaded with the config's sizes.
    #[error(transparent)]
    Load(#[from] CheckpointError),
}

/// Every float parameter's values, in the module's visiting order.
pub fn parameters(net: &PartInductionNet) -> Vec<Vec<f32>> {
    struct Collect(Vec<Vec<f32>>);
    impl ModuleVisitor for Collect {
        fn visit_float<const D: usize>(&mut self, param: &Param<Tensor<D>>) {
            let values = param.val().to_data().convert::<f32>();
            self.0.push(values.try_to_vec::<f32>().expect("converted to f32"));
        }
    }
    let mut collect = Collect(Vec::new());
    net.visit(&mut collect);
    collect.0
}

/// The network whose every parameter is the mean of the same parameter in `paths`' weights
/// (each loaded with `config`'s sizes), on `device`.
pub fn average_weights(
    config: &NetworkConfig,
    paths: &[PathBuf],
    device: &Device,
) -> Result<PartInductionNet, AverageError> {
    let (first, rest) = paths.split_first().ok_or(AverageError::Empty)?;
    let net = load_weights(config, first, device)?;
    let mut sums = parameters(&net);
    for path in rest {
        let other = parameters(&load_weights(config, path, device)?);
        for (sum, values) in sums.iter_mut().zip(other) {
            for (s, v) in sum.iter_mut().zip(values) {
                *s += v;
            }
        }
    }
    let n = paths.len() as f32;
    Ok(net.map(&mut Replace { values: sums.into_iter(), divisor: n }))
}

/// Replaces each float parameter, in visiting order, by the next values divided by `divisor`.
struct Replace<I> {
    values: I,
    divisor: f32,
}

impl<I: Iterator<Item = Vec<f32>>> ModuleMapper for Replace<I> {
    fn map_float<const D: usize>(&mut self, param: Param<Tensor<D>>) -> Param<Tensor<D>> {
        let Some(sum) = self.values.next() else { return param };
        param.map(|t| {
            let (shape, device) = (t.shape(), t.device());
            let mean: Vec<f32> = sum.iter().map(|s| s / self.divisor).collect();
            Tensor::from_data(TensorData::new(mean, shape), &device)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::train::checkpoint::save_weights;
    use crate::train::config::TrainConfig;

    #[test]
    fn the_average_is_the_mean_of_every_parameter_and_of_one_file_the_file() {
        let config = TrainConfig::built_in("tiny").network;
        let device = Device::flex();
        let dir = tempfile::tempdir().expect("a temporary folder");
        let paths: Vec<PathBuf> = (1..=3u64)
            .map(|seed| {
                let path = dir.path().join(format!("{seed}.bpk"));
                save_weights(&PartInductionNet::seeded(&config, &device, seed), &path)
                    .expect("saved");
                path
            })
            .collect();
        let each: Vec<_> = paths
            .iter()
            .map(|p| parameters(&load_weights(&config, p, &device).expect("loads")))
            .collect();
        let mean = parameters(&average_weights(&config, &paths, &device).expect("averages"));
        assert_eq!(mean.len(), each[0].len());
        assert!(mean.len() > 10, "{} parameters", mean.len());
        for (i, m) in mean.iter().enumerate() {
            for (j, &v) in m.iter().enumerate() {
                let expected = (each[0][i][j] + each[1][i][j] + each[2][i][j]) / 3.0;
                assert_eq!(v, expected, "parameter {i}, entry {j}");
            }
        }
        // The three networks differ, so the mean is none of them.
        assert_ne!(mean, each[0]);
        let one = parameters(&average_weights(&config, &paths[..1], &device).expect("averages"));
        assert_eq!(one, each[0]);
        assert!(matches!(average_weights(&config, &[], &device), Err(AverageError::Empty)));
    }
}
