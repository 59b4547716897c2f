//! Properties of the network: save/load and resume are bit-identical, per-point outputs
//! follow a permutation of P, degenerate clouds give errors or finite outputs, and the
//! segmentation module alone on the network's flow agrees with the whole network.

use burn::prelude::*;
use generator::config::GeneratorConfig;
use generator::stream::TrainingStream;
use model::network::sampling::SamplingError;
use model::network::PartInductionNet;
use model::train::checkpoint::CheckpointDir;
use model::train::config::TrainConfig;
use model::train::{stream_config, Budget, Draws, RunPaths, Trainer};
use model::weights::{self, read_record, write_record, WeightsError};
use pairs::math::Point3;
use pairs::{Cloud, Pair, PairInput};

fn tiny() -> TrainConfig {
    TrainConfig {
        stage1_pairs: 16,
        stage2_pairs: 16,
        stage3_pairs: 16,
        ..TrainConfig::built_in("tiny")
    }
}

fn some_pairs(config: &TrainConfig, n: usize) -> Vec<Pair> {
    TrainingStream::new(GeneratorConfig {
        categories: vec!["laptop".into()],
        ..stream_config(config)
    })
    .expect("valid generator config")
    .take(n)
    .collect::<Result<_, _>>()
    .expect("pairs")
}

fn fresh_net(config: &TrainConfig) -> PartInductionNet {
    PartInductionNet::seeded(&config.network, &Device::flex(), 3)
}

fn paths(root: &std::path::Path) -> RunPaths {
    RunPaths {
        checkpoints: CheckpointDir::new(root.join("checkpoints")),
        reports: root.join("reports"),
    }
}

#[test]
fn saved_and_loaded_weights_predict_bit_identically() {
    let config = tiny();
    let net = fresh_net(&config);
    let pair = &some_pairs(&config, 1)[0];
    let dir = tempfile::tempdir().expect("a temporary folder");
    let folder = dir.path().join("w");
    weights::save(&folder, &net, &config).expect("saved");
    let loaded = weights::load(&folder).expect("loaded");
    assert_eq!(loaded.config, config, "the config reads back equal");
    assert_eq!(
        net.predict(pair.input()).expect("runs"),
        loaded.net.predict(pair.input()).expect("runs")
    );
    let file = folder.join(weights::MODEL_FILE);
    let wrong = TrainConfig::built_in("cpu").network;
    assert!(read_record(&wrong, &file, &Device::flex()).is_err(), "other sizes are refused");
    // A file where the folder belongs is refused with the folder to give instead.
    let err = weights::load(&file).unwrap_err();
    assert!(matches!(err, WeightsError::NotAFolder { .. }), "{err}");
    assert!(err.to_string().contains(&folder.display().to_string()), "{err}");
    let err = weights::load(dir.path()).unwrap_err();
    assert!(matches!(err, WeightsError::NoModel { .. }), "{err}");
}

/// Trains on `pairs` in `root` in legs of `legs` steps (each a new trainer resuming from the
/// last one's checkpoint), then predicts the first pair with the saved weights.
fn train_in_legs(
    config: &TrainConfig,
    pairs: &[Pair],
    root: &std::path::Path,
    legs: &[u64],
) -> pairs::Prediction {
    for &steps in legs {
        let mut t = Trainer::on_pairs(
            config.clone(),
            paths(root),
            Device::flex().autodiff(),
            pairs.to_vec(),
        )
        .expect("a trainer");
        t.run(Budget::steps(steps), |_| {}).expect("training runs");
    }
    // A checkpoint folder is a weights folder.
    let loaded = weights::load(&root.join("checkpoints")).expect("weights");
    assert_eq!(&loaded.config, config);
    loaded.net.predict(pairs[0].input()).expect("runs")
}

#[test]
fn a_resumed_run_ends_with_the_same_weights_as_an_uninterrupted_one() {
    let config = tiny();
    let pairs = some_pairs(&config, 8);
    let run = |root: &std::path::Path, legs: &[u64]| train_in_legs(&config, &pairs, root, legs);
    let (a, b) = (tempfile::tempdir().expect("dir"), tempfile::tempdir().expect("dir"));
    // Six steps cross both stage boundaries; the break falls inside stage 2.
    let straight = run(a.path(), &[6]);
    let resumed = run(b.path(), &[3, 3]);
    assert_eq!(straight, resumed, "resuming changed the weights");
    let log = std::fs::read_to_string(b.path().join("reports/log.csv")).expect("log");
    assert_eq!(log.lines().count(), 7, "a header and one row per step:\n{log}");
}

#[test]
fn a_checkpoint_from_before_weights_folders_resumes_into_one() {
    // Checkpoints used to hold no config.toml and keep the best weights as best.bpk.
    let config = tiny();
    let pairs = some_pairs(&config, 4);
    let dir = tempfile::tempdir().expect("dir");
    train_in_legs(&config, &pairs, dir.path(), &[1]);
    let checkpoints = dir.path().join("checkpoints");
    std::fs::remove_file(checkpoints.join(weights::CONFIG_FILE)).expect("removed");
    let _ = std::fs::remove_dir_all(checkpoints.join("best"));
    // Still a weights folder: the config comes from state.json.
    assert_eq!(weights::load(&checkpoints).expect("loads").config, config);
    let best = PartInductionNet::seeded(&config.network, &Device::flex(), 17);
    write_record(&best, &checkpoints.join("best.bpk")).expect("saved");
    let optimizer = burn::optim::AdamConfig::new().init();
    CheckpointDir::new(&checkpoints)
        .load(&config, optimizer, &Device::flex().autodiff())
        .expect("the old checkpoint resumes");
    assert!(checkpoints.join(weights::CONFIG_FILE).is_file());
    assert!(!checkpoints.join("best.bpk").exists());
    let moved = weights::load(&checkpoints.join("best")).expect("best/ is a weights folder");
    assert_eq!(moved.config, config);
    assert_eq!(parameter_values(&moved.net), parameter_values(&best));
}

#[test]
fn permuting_p_permutes_the_per_point_outputs() {
    let config = tiny();
    let net = fresh_net(&config);
    let pair = &some_pairs(&config, 1)[0];
    let input = pair.input();
    let n = input.p.len();
    let order: Vec<usize> = (0..n).map(|i| (i * 7 + 3) % n).collect();
    let permuted = PairInput {
        p: Cloud { points: order.iter().map(|&i| input.p.points[i]).collect(), ..input.p.clone() },
        ..input.clone()
    };
    let (a, b) = (net.predict(input).expect("runs"), net.predict(&permuted).expect("runs"));
    let (fa, fb) = (a.flow.expect("flow"), b.flow.expect("flow"));
    for (j, &i) in order.iter().enumerate() {
        assert!((fa[i] - fb[j]).norm() < 1e-4, "point {i}: {:?} vs {:?}", fa[i], fb[j]);
        for (k, &l) in order.iter().enumerate() {
            let same_a = a.segments_p[i] == a.segments_p[l];
            assert_eq!(same_a, b.segments_p[j] == b.segments_p[k], "points {i} and {l}");
        }
    }
}

#[test]
fn degenerate_clouds_give_errors_or_finite_outputs() {
    let config = tiny();
    let net = fresh_net(&config);
    let pair = &some_pairs(&config, 1)[0];
    let input = pair.input();
    let same = Cloud { points: vec![Point3::new(0.1, 0.2, 0.3); input.p.len()], ..input.p.clone() };
    let flat = PairInput { p: same.clone(), q: same, ..input.clone() };
    let out = net.predict(&flat).expect("equal points are a valid, if useless, cloud");
    assert!(out.flow.expect("flow").iter().all(|f| f.iter().all(|v| v.is_finite())));
    let short = Cloud { points: input.p.points[..10].to_vec(), ..input.p.clone() };
    let err = net.predict(&PairInput { p: short, ..input.clone() }).expect_err("10 < 32 points");
    assert_eq!(err, SamplingError::TooFewPoints { wanted: 32, points: 10 });
    let mut bad = input.clone();
    bad.q.points[5].x = f32::NAN;
    assert_eq!(net.predict(&bad).expect_err("NaN"), SamplingError::NotFinite(5));
}

#[test]
fn the_segmentation_module_on_the_networks_own_flow_predicts_like_the_network() {
    let config = tiny();
    let net = fresh_net(&config);
    for pair in some_pairs(&config, 2) {
        let whole = net.predict(pair.input()).expect("predicts");
        let flow = whole.flow.clone().expect("the network reports its flow");
        let alone = net.segment_flow(pair.input(), &flow).expect("segments");
        assert_eq!(alone.segments_p, whole.segments_p);
        assert_eq!(alone.segments_q, whole.segments_q);
        assert!(alone.flow.is_none());
    }
}

/// Every parameter's gradient, in module order (empty for a parameter without one).
fn draws<'a>(rotations: &'a [pairs::math::Matrix3], true_flow: &'a [bool]) -> Draws<'a> {
    Draws { rotations, true_flow, residuals: &[] }
}

fn gradient_values(net: &PartInductionNet, grads: &burn::optim::GradientsParams) -> Vec<Vec<f32>> {
    struct Collect<'a> {
        grads: &'a burn::optim::GradientsParams,
        out: Vec<Vec<f32>>,
    }
    impl burn::module::ModuleVisitor for Collect<'_> {
        fn visit_float<const D: usize>(&mut self, param: &burn::module::Param<Tensor<D>>) {
            let values = self.grads.get::<D>(param.id).map_or_else(Vec::new, |g| {
                g.into_data().convert::<f32>().try_to_vec().expect("f32")
            });
            self.out.push(values);
        }
    }
    let mut visitor = Collect { grads, out: Vec::new() };
    net.visit(&mut visitor);
    visitor.out
}

#[test]
fn two_replicas_sum_the_gradients_of_their_halves_of_the_batch() {
    use model::train::batch_gradients;
    use pairs::math::Matrix3;
    let one = TrainConfig { batch: 4, replicas: 1, ..tiny() };
    let two = TrainConfig { replicas: 2, ..one.clone() };
    let pairs = some_pairs(&one, 4);
    let rotations = vec![Matrix3::identity(); 4];
    let device = Device::flex().autodiff();
    let net = PartInductionNet::seeded(&one.network, &device, 5);
    // Stage 3 with the true flow fed for the first and last pair: each shard gets its marks.
    let marks = [true, false, false, true];
    for stage in [1u8, 3] {
        let (value, _, grads, phases) =
            batch_gradients(&net, &two, &device, &pairs, draws(&rotations, &marks), stage)
                .expect("a step");
        assert!(phases.batch > 0.0 && phases.forward > 0.0 && phases.backward > 0.0);
        assert_eq!(phases.optimizer, 0.0, "the optimiser is the caller's");
        let together = gradient_values(&net, &grads);
        let halves: Vec<_> = [0..2, 2..4]
            .into_iter()
            .map(|range| {
                let (v, _, g, _) = batch_gradients(
                    &net,
                    &one,
                    &device,
                    &pairs[range.clone()],
                    draws(&rotations[range.clone()], &marks[range]),
                    stage,
                )
                .expect("a step");
                (v, gradient_values(&net, &g))
            })
            .collect();
        assert!((value - 0.5 * (halves[0].0 + halves[1].0)).abs() <= 1e-5 * value.abs());
        let mut compared = 0;
        for (i, sum) in together.iter().enumerate() {
            let (a, b) = (&halves[0].1[i], &halves[1].1[i]);
            if a.is_empty() && b.is_empty() {
                assert!(sum.is_empty(), "parameter {i} has a gradient from no shard");
                continue;
            }
            for (k, s) in sum.iter().enumerate() {
                let expected = 0.5 * (a.get(k).unwrap_or(&0.0) + b.get(k).unwrap_or(&0.0));
                assert!(
                    (s - expected).abs() <= 1e-5 * (1.0 + expected.abs()),
                    "stage {stage}, parameter {i}[{k}]: {s} vs {expected}"
                );
                compared += 1;
            }
        }
        assert!(compared > 1000, "stage {stage}: only {compared} gradient entries");
    }
}

#[test]
fn a_two_replica_run_is_deterministic_and_resumes_bit_identically() {
    let config = TrainConfig { replicas: 2, ..tiny() };
    let pairs = some_pairs(&config, 8);
    let run = |root: &std::path::Path, legs: &[u64]| train_in_legs(&config, &pairs, root, legs);
    let dirs: Vec<_> = (0..3).map(|_| tempfile::tempdir().expect("dir")).collect();
    let straight = run(dirs[0].path(), &[5]);
    assert_eq!(straight, run(dirs[1].path(), &[5]), "two identical runs differ");
    assert_eq!(straight, run(dirs[2].path(), &[2, 3]), "resuming changed the weights");
}

/// Every parameter's values, in module order.
fn parameter_values(net: &PartInductionNet) -> Vec<Vec<f32>> {
    struct Collect(Vec<Vec<f32>>);
    impl burn::module::ModuleVisitor for Collect {
        fn visit_float<const D: usize>(&mut self, param: &burn::module::Param<Tensor<D>>) {
            self.0.push(param.val().into_data().convert::<f32>().try_to_vec().expect("f32"));
        }
    }
    let mut visitor = Collect(Vec::new());
    net.visit(&mut visitor);
    visitor.0
}

#[test]
fn seeding_is_not_disturbed_by_networks_loaded_on_other_threads() {
    // burn draws weights from one process-wide generator, and building a network to load
    // weights into draws from it too: without the crate's lock, a load on another thread
    // changed a seeded network (and with it a whole training run).
    let config = tiny().network;
    let dir = tempfile::tempdir().expect("a temporary folder");
    let file = dir.path().join("w.bpk");
    write_record(&PartInductionNet::seeded(&config, &Device::flex(), 1), &file).expect("saved");
    let expected = parameter_values(&PartInductionNet::seeded(&config, &Device::flex(), 3));
    use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
    let (done, loads) = (AtomicBool::new(false), AtomicUsize::new(0));
    std::thread::scope(|scope| {
        scope.spawn(|| {
            while !done.load(Ordering::Relaxed) {
                read_record(&config, &file, &Device::flex()).expect("loads");
                loads.fetch_add(1, Ordering::Relaxed);
            }
        });
        while loads.load(Ordering::Relaxed) == 0 {
            std::thread::yield_now();
        }
        let differing = (0..30)
            .filter(|_| {
                parameter_values(&PartInductionNet::seeded(&config, &Device::flex(), 3)) != expected
            })
            .count();
        done.store(true, Ordering::Relaxed);
        assert_eq!(differing, 0, "of 30 seeded networks beside the loads");
    });
}

#[test]
fn a_run_with_init_weights_starts_from_them() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let file = dir.path().join("start.bpk");
    let start = PartInductionNet::seeded(&tiny().network, &Device::flex(), 11);
    write_record(&start, &file).expect("saved");
    let config = TrainConfig { init_weights: Some(file.clone()), ..tiny() };
    let pairs = some_pairs(&config, 2);
    let trainer = Trainer::on_pairs(
        config.clone(),
        paths(&dir.path().join("run")),
        Device::flex().autodiff(),
        pairs.clone(),
    )
    .expect("a trainer");
    let expected = parameter_values(&start);
    assert_eq!(parameter_values(&trainer.network().valid()), expected);
    let seeded = Trainer::on_pairs(
        tiny(),
        paths(&dir.path().join("seeded")),
        Device::flex().autodiff(),
        pairs.clone(),
    )
    .expect("a trainer");
    let fresh = parameter_values(&seeded.network().valid());
    assert_ne!(fresh, expected, "another seed");
    // Only the correspondence and flow modules from the file: those tensors come first in
    // module order, and the rest are the seeded network's.
    use model::train::config::NetModule;
    let flow_only = TrainConfig {
        init_modules: vec![NetModule::Correspondence, NetModule::Flow],
        ..config.clone()
    };
    let mixed = Trainer::on_pairs(
        flow_only,
        paths(&dir.path().join("mixed")),
        Device::flex().autodiff(),
        pairs.clone(),
    )
    .expect("a trainer");
    let mixed = parameter_values(&mixed.network().valid());
    let split = mixed.iter().zip(&expected).position(|(a, b)| a != b).expect("some seeded");
    let device = Device::flex();
    let flow_tensors =
        parameter_count(&model::network::correspondence::CorrespondenceModule::new(
            &tiny().network,
            &device,
        )) + parameter_count(&model::network::flow::FlowModule::new(&tiny().network, &device));
    assert_eq!(split, flow_tensors, "the correspondence and flow modules come from the file");
    assert_eq!(mixed[split..], fresh[split..], "the segmentation module is the seeded one");
    let orphan = TrainConfig { init_weights: None, ..flow_only_config(&config) };
    assert!(orphan.validate().is_err(), "init_modules without init_weights");
    let missing = TrainConfig { init_weights: Some(dir.path().join("none.bpk")), ..tiny() };
    let err =
        Trainer::on_pairs(missing, paths(&dir.path().join("m")), Device::flex().autodiff(), pairs)
            .expect_err("a missing weights file");
    assert!(err.to_string().contains("none.bpk"), "{err}");
}

fn flow_only_config(config: &TrainConfig) -> TrainConfig {
    use model::train::config::NetModule;
    TrainConfig { init_modules: vec![NetModule::Flow], ..config.clone() }
}

#[test]
fn stage_three_on_the_true_flow_sees_what_stage_two_sees() {
    use model::train::batch::TrainingBatch;
    use model::train::objective::{stage_loss, Objective};
    use pairs::math::Matrix3;
    let config = tiny();
    let pairs = some_pairs(&config, 2);
    let rotations = vec![Matrix3::identity(); 2];
    let device = Device::flex();
    let batch = TrainingBatch::new(&pairs, &rotations, &config.network, &device).expect("batch");
    let net = fresh_net(&config);
    let objective = Objective::default();
    let terms = |stage, marks: &[bool]| {
        stage_loss(&net, &batch, stage, &objective, marks).expect("a loss").1
    };
    let truth = terms(2, &[]);
    let fed_truth = terms(3, &[true, true]);
    assert_eq!((fed_truth.motion, fed_truth.support), (truth.motion, truth.support));
    assert!(fed_truth.segment.is_some() && truth.segment.is_none(), "stage 3 runs the RPEN");
    let predicted = terms(3, &[]);
    assert_ne!(predicted.motion, truth.motion, "an untrained flow is not the true one");
    let half = terms(3, &[true, false]);
    assert!(half.motion != truth.motion && half.motion != predicted.motion);
}

/// Parameter tensors of a module, in visiting order.
fn parameter_count<M: burn::module::Module>(module: &M) -> usize {
    struct Count(usize);
    impl burn::module::ModuleVisitor for Count {
        fn visit_float<const D: usize>(&mut self, _: &burn::module::Param<Tensor<D>>) {
            self.0 += 1;
        }
    }
    let mut count = Count(0);
    module.visit(&mut count);
    count.0
}

#[test]
fn the_release_switches_stop_gradients_where_the_release_does() {
    use model::network::segmentation::hypotheses::HypothesisModule;
    use model::network::segmentation::{rpen::RpenModule, support::SupportModule};
    use model::train::batch::TrainingBatch;
    use model::train::objective::{stage_loss, Objective};
    use pairs::math::Matrix3;
    let config = tiny();
    let pairs = some_pairs(&config, 2);
    let rotations = vec![Matrix3::identity(); 2];
    let device = Device::flex().autodiff();
    let batch = TrainingBatch::new(&pairs, &rotations, &config.network, &device).expect("batch");
    let seeded = PartInductionNet::seeded(&config.network, &device, 7);
    // Output heads start at zero, which passes no gradient back to their inputs: one step
    // of the default objective in each stage makes every path live.
    let mut optimizer = burn::optim::AdamConfig::new().init();
    let mut net = seeded;
    for stage in [2u8, 3] {
        let (loss, _) =
            stage_loss(&net, &batch, stage, &Objective::default(), &[]).expect("a loss");
        let grads = burn::optim::GradientsParams::from_grads(loss.backward(), &net);
        net = optimizer.step(1e-2, net, grads);
    }
    let grads = |stage, objective: Objective| {
        let (loss, _) = stage_loss(&net, &batch, stage, &objective, &[]).expect("a loss");
        gradient_values(&net, &burn::optim::GradientsParams::from_grads(loss.backward(), &net))
    };
    // Module order: correspondence, flow, hypotheses, support, RPEN.
    let total = parameter_count(&net);
    let rpen = parameter_count(&RpenModule::new(&config.network, &device));
    let hypotheses = parameter_count(&HypothesisModule::new(&config.network, &device));
    let support = parameter_count(&SupportModule::new(&config.network, &device));
    let hyp_range = total - rpen - support - hypotheses..total - rpen - support;
    let nonzero = |g: &[f32]| g.iter().any(|v| *v != 0.0);
    // Stage 2 with the hypotheses detached: the support loss's weight does not reach the
    // hypothesis generator; without the switch it does.
    for detach in [true, false] {
        let at = |weight| {
            let objective = Objective {
                detach_hypotheses: detach,
                support_weight: weight,
                ..Objective::default()
            };
            grads(2, objective)[hyp_range.clone()].to_vec()
        };
        let (light, heavy) = (at(0.5), at(50.0));
        assert!(light.iter().any(|g| nonzero(g)), "the motion loss trains the hypotheses");
        assert_eq!(light == heavy, detach, "detach {detach}");
    }
    // Stage 3 training the RPEN alone: every gradient before the RPEN is absent or zero.
    let rpen_only = grads(3, Objective { rpen_only: true, ..Objective::default() });
    assert!(rpen_only[..total - rpen].iter().all(|g| !nonzero(g)));
    assert!(rpen_only[total - rpen..].iter().any(|g| nonzero(g)));
    let whole = grads(3, Objective::default());
    assert!(whole[hyp_range].iter().any(|g| nonzero(g)), "the default trains the hypotheses");
}

#[test]
fn a_residual_pair_asks_for_the_flow_its_perturbation_left() {
    use model::train::batch::{BatchOptions, TrainingBatch};
    use pairs::math::{Isometry3, Matrix3, Vector3};
    let config = tiny();
    let pairs = some_pairs(&config, 2);
    let rotations = vec![Matrix3::identity(); 2];
    let shift = Vector3::new(0.01, -0.02, 0.005);
    let residuals =
        [Some(Isometry3::identity()), Some(Isometry3::translation(shift.x, shift.y, shift.z))];
    let device = Device::flex();
    let batch = TrainingBatch::with(
        &pairs,
        &rotations,
        &residuals,
        BatchOptions::default(),
        &config.network,
        &device,
    )
    .expect("batch");
    let flow = batch.truth.flow.to_data().convert::<f32>().try_to_vec::<f32>().expect("floats");
    let m = config.network.corr_points;
    // P moved by the true flow exactly: nothing remains. Then shifted: the shift back.
    assert!(flow[..m * 3].iter().all(|v| *v == 0.0), "{:?}", &flow[..6]);
    for f in flow[m * 3..].chunks(3) {
        for (v, s) in f.iter().zip(shift.iter()) {
            assert!((v + s).abs() < 1e-6, "{f:?} against {shift:?}");
        }
    }
    // Without a residual the truth is the pair's own flow, which moves P.
    let plain = TrainingBatch::new(&pairs, &rotations, &config.network, &device).expect("batch");
    let plain = plain.truth.flow.to_data().convert::<f32>().try_to_vec::<f32>().expect("floats");
    assert!(plain[..m * 3].iter().any(|v| v.abs() > 1e-3));
}

#[test]
fn residual_pairs_are_drawn_in_stage_one_only() {
    let pairs = some_pairs(&tiny(), 8);
    let trained = |stage1_pairs: u64, residual_pairs: f64, root: &std::path::Path| {
        let config = TrainConfig { stage1_pairs, residual_pairs, ..tiny() };
        train_in_legs(&config, &pairs, root, &[1])
    };
    let dirs: Vec<_> = (0..4).map(|_| tempfile::tempdir().expect("dir")).collect();
    // One step of stage 1: every pair a residual pair changes what is learnt.
    assert_ne!(trained(16, 1.0, dirs[0].path()), trained(16, 0.0, dirs[1].path()));
    // One step of stage 2 (no stage 1): the switch changes nothing.
    assert_eq!(trained(0, 1.0, dirs[2].path()), trained(0, 0.0, dirs[3].path()));
}

#[test]
fn the_nearest_target_is_never_farther_than_the_same_part_one() {
    use model::train::batch::{BatchOptions, MatchingTarget, TrainingBatch};
    use pairs::math::Matrix3;
    let config = tiny();
    let pairs = some_pairs(&config, 4);
    let rotations = vec![Matrix3::identity(); 4];
    let device = Device::flex();
    let with = |target| {
        TrainingBatch::with(
            &pairs,
            &rotations,
            &[],
            BatchOptions { target },
            &config.network,
            &device,
        )
        .expect("batch")
    };
    let (same, nearest) = (with(MatchingTarget::SamePart), with(MatchingTarget::Nearest));
    let floats = |t: Tensor<3>| t.to_data().convert::<f32>().try_to_vec::<f32>().expect("floats");
    let ints = |t: Tensor<2, Int>| t.to_data().convert::<i64>().try_to_vec::<i64>().expect("ints");
    let (p, q, f) =
        (floats(same.p()), floats(same.input.q.clone()), floats(same.truth.flow.clone()));
    let matched = |b: &TrainingBatch| {
        b.truth.matched.to_data().convert::<f32>().try_to_vec::<f32>().expect("floats")
    };
    let (ts, tn) = (ints(same.truth.targets.clone()), ints(nearest.truth.targets.clone()));
    let (ms, mn) = (matched(&same), matched(&nearest));
    let m = config.network.corr_points;
    let mut differ = 0;
    for i in 0..ts.len() {
        let b = i / m;
        let end: Vec<f32> = (0..3).map(|k| p[i * 3 + k] + f[i * 3 + k]).collect();
        let d = |j: i64| -> f32 {
            let j = (b * m + j as usize) * 3;
            (0..3).map(|k| (q[j + k] - end[k]).powi(2)).sum()
        };
        assert!(mn[i] >= ms[i], "a same-part target implies a nearest one");
        if ms[i] > 0.0 {
            assert!(d(tn[i]) <= d(ts[i]), "point {i}");
            differ += usize::from(tn[i] != ts[i]);
        }
    }
    assert!(ms.iter().sum::<f32>() > 0.0);
    // The two rules differ: some points' true ends lie nearer a point of the other part
    // (11 of 128 here).
    assert!(differ > 0, "no target differs");
}

#[test]
fn the_stage_one_release_switches_change_the_network_and_train() {
    use model::network::config::PairNorm;
    use model::train::batch::TrainingBatch;
    use model::train::objective::{stage_loss, Objective};
    use pairs::math::Matrix3;
    // Subsets smaller than the clouds (the tiny config's are the whole clouds), so that the
    // backbone on the whole clouds sees more than the subsets.
    let mut base = tiny();
    base.network.corr_points = 16;
    base.network.seg_points = 16;
    let pairs = some_pairs(&base, 2);
    let rotations = vec![Matrix3::identity(); 2];
    let device = Device::flex().autodiff();
    let loss_of = |config: &TrainConfig| {
        let batch =
            TrainingBatch::new(&pairs, &rotations, &config.network, &device).expect("batch");
        let mut net = PartInductionNet::seeded(&config.network, &device, 7);
        let flow = net.flow(&batch.input).expect("a flow");
        // Output heads start at zero (uniform matching, zero flow): one step makes the
        // loss depend on the features.
        let mut optimizer = burn::optim::AdamConfig::new().init();
        let (loss, _) = stage_loss(&net, &batch, 1, &Objective::default(), &[]).expect("a loss");
        let grads = burn::optim::GradientsParams::from_grads(loss.backward(), &net);
        let live = gradient_values(&net, &grads).iter().flatten().any(|g| *g != 0.0);
        net = optimizer.step(1e-2, net, grads);
        let (loss, _) = stage_loss(&net, &batch, 1, &Objective::default(), &[]).expect("a loss");
        (flow.flow.dims(), loss.into_scalar::<f32>(), live)
    };
    let (dims, base_loss, live) = loss_of(&base);
    assert_eq!(dims, [2, base.network.corr_points, 3]);
    assert!(base_loss.is_finite() && live);
    let n = pairs[0].input().p.len();
    type Switch = fn(&mut TrainConfig);
    let switches: [(&str, Switch); 3] = [
        ("features_on_cloud", |c| c.network.features_on_cloud = true),
        ("flow_on_cloud", |c| c.network.flow_on_cloud = true),
        ("pair_norm", |c| c.network.pair_norm = PairNorm::Pair),
    ];
    for (name, switch) in switches {
        let mut config = base.clone();
        switch(&mut config);
        let (dims, loss, live) = loss_of(&config);
        assert!(loss.is_finite() && live, "{name}");
        assert_ne!(loss, base_loss, "{name} changes nothing");
        // The flow comes out at every point of P where the flow module carries it there.
        let points = if name == "flow_on_cloud" { n } else { base.network.corr_points };
        assert_eq!(dims, [2, points, 3], "{name}");
    }
}
