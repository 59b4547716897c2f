//! Weight averaging ("model soups", Wortsman et al. 2022): the element-wise mean of several
//! checkpoints of one network, for checkpoints fine-tuned from the same weights. A run at a
//! high learning rate moves its weights around a basin from step to step (two trajectories
//! that differed in the last bit of one loss 112 steps earlier validated at IoU 0.454 and
//! 0.494, `model/TRAINING.md`); the mean of points on such a walk sits nearer its middle.
//!
//! The mean is taken parameter by parameter in the order the files are given,
//! `((w_1 + w_2) + … + w_n) / n` in `f32`, so the same files in the same order give the same
//! bytes.

use std::path::{Path, PathBuf};

use burn::module::{Module, ModuleMapper, ModuleVisitor, Param};
use burn::prelude::*;

use crate::network::PartInductionNet;
use crate::train::config::TrainConfig;
use crate::weights::{self, WeightsError};

/// Why weights could not be averaged.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum AverageError {
    /// Fewer than one folder.
    #[error("averaging needs at least one weights folder")]
    Empty,
    /// A folder's network has other sizes than the first's.
    #[error("{dir}: its network's sizes differ from those of {first}")]
    Sizes {
        /// The folder.
        dir: PathBuf,
        /// The first folder.
        first: PathBuf,
    },
    /// A folder could not be loaded.
    #[error(transparent)]
    Load(#[from] WeightsError),
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

/// The network whose every parameter is the mean of the same parameter in the weights
/// folders `dirs` (all of the first's sizes), on `device`, with the first folder's config.
pub fn average_weights(
    dirs: &[PathBuf],
    device: &Device,
) -> Result<(PartInductionNet, TrainConfig), AverageError> {
    let (first, rest) = dirs.split_first().ok_or(AverageError::Empty)?;
    let weights::Weights { net, config, .. } = weights::load_on(first, device)?;
    let mut sums = parameters(&net);
    for dir in rest {
        let (other, _) = weights::read_config(dir)?;
        if other.network != config.network {
            return Err(AverageError::Sizes { dir: dir.clone(), first: first.clone() });
        }
        let model = Path::new(dir).join(weights::MODEL_FILE);
        let other = parameters(&weights::read_record(&config.network, &model, device)?);
        for (sum, values) in sums.iter_mut().zip(other) {
            for (s, v) in sum.iter_mut().zip(values) {
                *s += v;
            }
        }
    }
    let n = dirs.len() as f32;
    Ok((net.map(&mut Replace { values: sums.into_iter(), divisor: n }), config))
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

    #[test]
    fn the_average_is_the_mean_of_every_parameter_and_of_one_folder_the_folder() {
        let config = TrainConfig::built_in("tiny");
        let device = Device::flex();
        let dir = tempfile::tempdir().expect("a temporary folder");
        let paths: Vec<PathBuf> = (1..=3u64)
            .map(|seed| {
                let path = dir.path().join(format!("{seed}"));
                let net = PartInductionNet::seeded(&config.network, &device, seed);
                weights::save(&path, &net, &config).expect("saved");
                path
            })
            .collect();
        let each: Vec<_> =
            paths.iter().map(|p| parameters(&weights::load(p).expect("loads").net)).collect();
        let (mean, mean_config) = average_weights(&paths, &device).expect("averages");
        assert_eq!(mean_config, config);
        let mean = parameters(&mean);
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
        let one = parameters(&average_weights(&paths[..1], &device).expect("averages").0);
        assert_eq!(one, each[0]);
        assert!(matches!(average_weights(&[], &device), Err(AverageError::Empty)));
        // A folder of other sizes is named.
        let mut wider = config.clone();
        wider.network.feature_dim *= 2;
        let other = dir.path().join("wider");
        weights::save(&other, &PartInductionNet::seeded(&wider.network, &device, 4), &wider)
            .expect("saved");
        let err = average_weights(&[paths[0].clone(), other.clone()], &device).unwrap_err();
        assert!(matches!(&err, AverageError::Sizes { dir, .. } if *dir == other), "{err}");
    }
}
