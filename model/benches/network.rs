//! Speed of the network on this machine: one single-pass prediction at N = 512 (the paper's
//! target is 0.4 s on a TITAN Xp) and one training step of every stage, for the `cpu` and
//! `paper` configs (the `cpu` step on its `replicas` threads). Peak memory: run `model train` under `/usr/bin/time -v`.

use burn::optim::AdamConfig;
use burn::prelude::*;
use criterion::{criterion_group, criterion_main, Criterion};
use generator::config::GeneratorConfig;
use generator::stream::TrainingStream;
use model::network::PartInductionNet;
use model::train::config::TrainConfig;
use model::train::{batch_gradients, stream_config, Draws};
use pairs::math::Matrix3;

// The binaries' allocator (jemalloc, from the `cli` crate), so timings are theirs.
use cli as _;

/// The fused layer (`model::network::norm`: product, bias, layer norm, ReLU) on one pair
/// tensor's worth of rows (4 pairs x 128 x 128 points, 64 channels in and out).
fn norm(c: &mut Criterion) {
    let (rows, channels) = (4 * 128 * 128, 64);
    let x: Vec<f32> =
        (0..rows * channels).map(|i| ((i * 7919) % 1009) as f32 / 500.0 - 1.0).collect();
    let weight: Vec<f32> =
        (0..channels * channels).map(|i| ((i * 31) % 61) as f32 / 240.0 - 0.125).collect();
    let gamma: Vec<f32> = (0..channels).map(|i| 0.5 + i as f32 / channels as f32).collect();
    let beta: Vec<f32> = (0..channels).map(|i| i as f32 / channels as f32 - 0.5).collect();
    let bias: Vec<f32> = beta.iter().map(|b| b * 0.1).collect();
    let params = model::network::fused::Channels { bias: &bias, gamma: &gamma, beta: &beta };
    let (out, z) = model::network::fused::forward(&x, &weight, &params, true);
    let grad: Vec<f32> = out.iter().map(|v| v * 0.5 - 0.1).collect();
    let mut group = c.benchmark_group("norm");
    group.sample_size(20);
    group.bench_function("forward_65536x64", |b| {
        b.iter(|| model::network::fused::forward(&x, &weight, &params, true))
    });
    group.bench_function("backward_65536x64", |b| {
        let mut dz = grad.clone();
        b.iter(|| {
            dz.copy_from_slice(&grad);
            model::network::fused::backward(&x, &weight, &z, &params, &mut dz, true)
        })
    });
    group.finish();
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("network");
    group.sample_size(10);
    for name in ["cpu", "paper"] {
        let config = TrainConfig::built_in(name);
        let pairs: Vec<_> =
            TrainingStream::new(GeneratorConfig { points: 512, ..stream_config(&config) })
                .expect("valid generator config")
                .take(8)
                .collect::<Result<_, _>>()
                .expect("pairs");
        let net = PartInductionNet::seeded(&config.network, &Device::flex(), 1);
        group.bench_function(format!("{name}/predict_n512"), |b| {
            b.iter(|| net.predict(pairs[0].input()).expect("runs"))
        });
        let device = Device::flex().autodiff();
        let batch_size = if name == "paper" { 2 } else { config.batch };
        let rotations = vec![Matrix3::identity(); batch_size];
        let batch = &pairs[..batch_size];
        for stage in 1..=3u8 {
            let mut net = PartInductionNet::seeded(&config.network, &device, 1);
            let mut optimizer = AdamConfig::new().init();
            // One optimiser step as the trainer takes it: the batch's tensors, the loss (on
            // `replicas` threads), backward and Adam.
            group.bench_function(
                format!("{name}/train_step_stage{stage}_batch{batch_size}"),
                |b| {
                    b.iter(|| {
                        let (_, _, grads, _) = batch_gradients(
                            &net,
                            &config,
                            &device,
                            batch,
                            Draws { rotations: &rotations, true_flow: &[], residuals: &[] },
                            stage,
                        )
                        .expect("a loss");
                        net = optimizer.step(1e-4, net.clone(), grads);
                    })
                },
            );
        }
    }
    group.finish();
}

criterion_group!(benches, norm, bench);
criterion_main!(benches);
