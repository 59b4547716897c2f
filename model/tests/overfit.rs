//! The `tiny` config overfits 8 training pairs: the full objective (every loss term of
//! stage 3) falls by at least 90%, and the single-pass prediction reaches an IoU above 0.9
//! on those pairs.

use burn::prelude::*;
use generator::config::GeneratorConfig;
use generator::stream::TrainingStream;
use model::network::PartInductionNet;
use model::train::batch::TrainingBatch;
use model::train::checkpoint::CheckpointDir;
use model::train::config::TrainConfig;
use model::train::objective::{stage_loss, Objective};
use model::train::validation::score;
use model::train::{stream_config, Budget, RunPaths, Trainer};
use pairs::math::Matrix3;
use pairs::Pair;

fn full_objective(
    net: &PartInductionNet,
    pairs: &[Pair],
    config: &TrainConfig,
    device: &Device,
) -> f32 {
    let rotations = vec![Matrix3::identity(); pairs.len()];
    let batch = TrainingBatch::new(pairs, &rotations, &config.network, device).expect("a batch");
    stage_loss(net, &batch, 3, &Objective::default(), &[]).expect("a loss").0.into_scalar::<f32>()
}

#[test]
fn tiny_config_overfits_eight_pairs() {
    let config = TrainConfig::built_in("tiny");
    let generator = GeneratorConfig { categories: vec!["laptop".into()], ..stream_config(&config) };
    let pairs: Vec<_> = TrainingStream::new(generator)
        .expect("valid generator config")
        .take(8)
        .collect::<Result<_, _>>()
        .expect("pairs");
    let dir = tempfile::tempdir().expect("a temporary folder");
    let paths = RunPaths {
        checkpoints: CheckpointDir::new(dir.path().join("checkpoints")),
        reports: dir.path().join("reports"),
    };
    let device = Device::flex().autodiff();
    let mut trainer =
        Trainer::on_pairs(config.clone(), paths, device.clone(), pairs.clone()).expect("a trainer");
    let before = full_objective(trainer.network(), &pairs, &config, &device);
    trainer.run(Budget::default(), |_| {}).expect("training runs");
    let after = full_objective(trainer.network(), &pairs, &config, &device);
    let scores = score(&trainer.network().valid(), &pairs).expect("scores");
    eprintln!("full objective {before} -> {after}; {scores:?}");
    assert!(after <= 0.1 * before, "the objective fell from {before} to {after} only");
    assert!(scores.iou > 0.9, "IoU {} on the training pairs", scores.iou);
    assert!(dir.path().join("reports/loss.png").exists());
}
