//! Properties of the inference procedure on a small untrained network: its first pass is
//! the single pass (`net`), its records are complete and deterministic, the rotation search picks
//! one of its candidates and maps the result back to P's frame, and bad input is an error.

use burn::prelude::*;
use generator::config::GeneratorConfig;
use generator::stream::TrainingStream;
use model::inference::method::NetworkMethod;
use model::inference::rotation_search::{search_candidates, SEARCH_ROTATIONS};
use model::inference::InferenceParams;
use model::network::PartInductionNet;
use model::train::config::TrainConfig;
use model::train::stream_config;
use pairs::math::Point3;
use pairs::{Method, Pair};

fn net_and_pair() -> (PartInductionNet, Pair) {
    let config = TrainConfig::built_in("tiny");
    let pair = TrainingStream::new(GeneratorConfig {
        categories: vec!["laptop".into()],
        ..stream_config(&config)
    })
    .expect("valid generator config")
    .next()
    .expect("a pair")
    .expect("generated");
    (PartInductionNet::seeded(&config.network, &Device::flex(), 5), pair)
}

#[test]
fn the_first_pass_is_the_single_pass_and_records_are_complete() {
    let (net, pair) = net_and_pair();
    let input = pair.input();
    let params = InferenceParams { max_iterations: 3, ..InferenceParams::iterative() };
    let inference = net.infer(input, &params).expect("runs");
    assert!((1..=3).contains(&inference.iterations.len()));
    let single = net.infer(input, &InferenceParams::single_pass()).expect("runs");
    assert_eq!(inference.iterations[0], single.iterations[0]);
    assert!(inference.iterations[0].change.is_infinite());
    for it in &inference.iterations {
        let p = &it.prediction;
        let flow = p.flow.as_ref().expect("a flow");
        assert_eq!(flow.len(), input.p.len());
        assert!(flow.iter().all(|f| f.iter().all(|v| v.is_finite())));
        assert_eq!(p.segments_q.len(), input.q.len());
        let k = p.motions.len();
        assert!(p.segments_p.iter().chain(&p.segments_q).all(|&l| (l as usize) < k));
        let soft = p.segment_probs.as_ref().expect("soft segments");
        assert!(soft.iter().all(|row| row.len() == k));
    }
    assert_eq!(inference, net.infer(input, &params).expect("runs again"), "deterministic");
    let method = NetworkMethod::with_params("net-iter", net, params);
    assert_eq!(method.name(), "net-iter");
    assert_eq!(method.predict(input).expect("runs"), inference.prediction());
}

#[test]
fn the_rotation_search_picks_a_candidate_and_answers_in_ps_frame() {
    let (net, pair) = net_and_pair();
    let input = pair.input();
    let search = net.search_rotation(input).expect("runs");
    assert_eq!(search.magnitudes.len(), SEARCH_ROTATIONS);
    assert_eq!(search.rotation, search_candidates()[search.index]);
    let params = InferenceParams {
        max_iterations: 1,
        rotation_search: true,
        ..InferenceParams::iterative()
    };
    let inference = net.infer(input, &params).expect("runs");
    assert_eq!(inference.rotation, search.rotation);
    // The same pass run by hand on the turned P, mapped back: flow R x + f - x, motions M ∘ R.
    let mut turned = input.clone();
    turned.p.points =
        input.p.points.iter().map(|x| Point3::from(search.rotation * x.coords)).collect();
    let by_hand =
        net.infer(&turned, &InferenceParams { rotation_search: false, ..params }).expect("runs");
    let (found, expected) = (inference.prediction(), by_hand.prediction());
    assert_eq!(found.segments_p, expected.segments_p);
    let (flow, hand_flow) = (found.flow.expect("a flow"), expected.flow.expect("a flow"));
    for ((x, t), (f, g)) in
        input.p.points.iter().zip(&turned.p.points).zip(flow.iter().zip(&hand_flow))
    {
        assert!((f - (t + g - x)).norm() < 1e-4);
    }
    for (m, h) in found.motions.iter().zip(&expected.motions) {
        for (x, t) in input.p.points.iter().zip(&turned.p.points).take(20) {
            assert!((m.apply(x) - h.apply(t)).norm() < 1e-4);
        }
    }
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    let (net, pair) = net_and_pair();
    let mut bad = pair.input().clone();
    bad.p.points[3].y = f32::NAN;
    assert!(net.infer(&bad, &InferenceParams::iterative()).is_err());
    let mut empty = pair.input().clone();
    empty.q.points.clear();
    assert!(net.infer(&empty, &InferenceParams::iterative()).is_err());
}

#[test]
fn a_global_alignment_recovers_a_rigid_flow_and_runs_before_the_passes() {
    use model::inference::align_globally;
    use pairs::math::{Rotation3, Vector3};
    let (net, pair) = net_and_pair();
    let p = &pair.input().p.points;
    // A flow that is one rigid motion: aligning moves P exactly onto P + flow.
    let turn = Rotation3::from_axis_angle(&Vector3::z_axis(), 0.4);
    let shift = Vector3::new(0.05, -0.02, 0.1);
    let flow: Vec<Vector3> = p.iter().map(|x| turn * x.coords + shift - x.coords).collect();
    for (aligned, (x, f)) in align_globally(p, &flow).iter().zip(p.iter().zip(&flow)) {
        assert!((aligned - (x + f)).norm() < 1e-4, "{aligned} vs {}", x + f);
    }
    // A flow that no motion fits leaves P where it is.
    assert_eq!(&align_globally(p, &vec![Vector3::new(f32::NAN, 0.0, 0.0); p.len()]), p);
    // In the procedure: deterministic; the untrained network predicts no flow, so its
    // alignments are the identity and the passes are those of the plain procedure.
    let params =
        InferenceParams { global_alignments: 2, max_iterations: 2, ..InferenceParams::iterative() };
    let aligned = net.infer(pair.input(), &params).expect("runs");
    assert_eq!(aligned, net.infer(pair.input(), &params).expect("runs"));
    let plain = net
        .infer(pair.input(), &InferenceParams { max_iterations: 2, ..InferenceParams::iterative() })
        .expect("runs");
    assert_eq!(aligned, plain);
    let flow = aligned.prediction().flow.expect("a flow");
    assert!(flow.iter().all(|f| f.iter().all(|v| v.is_finite())));
}

#[test]
fn sub_problems_move_each_segment_by_its_motion_and_keep_the_first_pass() {
    use model::inference::subproblems::{attention_masks, Geodesic};
    use pairs::math::Vector3;
    let (net, pair) = net_and_pair();
    let (input, truth) = (pair.input(), pair.truth());
    // The untrained network predicts no flow, so with the true segments and motions every
    // sub-pair's prediction is its segment's motion: a point that only its own segment's
    // mask holds gets the true flow, and every point some segment's motion.
    let graphs = (Geodesic::new(&input.p.points), Geodesic::new(&input.q.points));
    let labels_p: Vec<u32> = truth.part_p.iter().map(|&l| u32::from(l)).collect();
    let labels_q: Vec<u32> = truth.part_q.iter().map(|&l| u32::from(l)).collect();
    let eps = 0.05;
    let zero = vec![Vector3::zeros(); input.p.len()];
    let sub = net
        .sub_problem_flow(
            input,
            &input.p.points,
            (&graphs.0, &graphs.1),
            (&labels_p, &labels_q),
            &truth.motions,
            &zero,
            None,
            eps,
        )
        .expect("runs");
    let masks =
        attention_masks(&graphs.0, &graphs.1, &labels_p, &labels_q, truth.motions.len(), eps);
    let mut alone = 0;
    for (i, (x, f)) in input.p.points.iter().zip(&sub.flow).enumerate() {
        let holders: Vec<usize> = masks
            .iter()
            .enumerate()
            .filter(|(_, m)| m.as_ref().is_some_and(|m| m.p.contains(&i)))
            .map(|(s, _)| s)
            .collect();
        assert!(holders.contains(&(labels_p[i] as usize)), "point {i} is in its segment's mask");
        if holders.len() == 1 {
            alone += 1;
            assert!(
                (f - truth.flow.as_ref().expect("a flow")[i]).norm() < 1e-4,
                "point {i}: {f} vs {}",
                truth.flow.as_ref().expect("a flow")[i]
            );
        }
        assert!(
            truth.motions.iter().any(|m| (x + f - m.apply(x)).norm() < 1e-4),
            "point {i} moves by a segment's motion"
        );
    }
    assert!(alone > input.p.len() / 2, "most points are in one mask only: {alone}");

    // In the procedure: the first pass is the plain one; deterministic; complete records.
    let params =
        InferenceParams { sub_problems: true, max_iterations: 3, ..InferenceParams::iterative() };
    let inference = net.infer(input, &params).expect("runs");
    let plain = net.infer(input, &InferenceParams::single_pass()).expect("runs");
    assert_eq!(inference.iterations[0], plain.iterations[0]);
    assert_eq!(inference, net.infer(input, &params).expect("runs again"));
    // Every pass runs with sub-problems; the plain procedure stops once the flow is still
    // (the untrained network's is zero from the first pass).
    assert_eq!(inference.iterations.len(), 3);
    let plain = InferenceParams { max_iterations: 3, ..InferenceParams::iterative() };
    assert_eq!(net.infer(input, &plain).expect("runs").iterations.len(), 2);
    for it in &inference.iterations {
        let flow = it.prediction.flow.as_ref().expect("a flow");
        assert_eq!(flow.len(), input.p.len());
        assert!(flow.iter().all(|f| f.iter().all(|v| v.is_finite())));
        assert_eq!(it.prediction.segments_q.len(), input.q.len());
    }
}

#[test]
fn full_matching_ends_on_q_for_full_pairs_only() {
    let (net, pair) = net_and_pair();
    let input = pair.input();
    assert_eq!(input.kind, pairs::PairKind::Sf2f);
    let params =
        InferenceParams { full_matching: true, max_iterations: 2, ..InferenceParams::iterative() };
    let matched = net.infer(input, &params).expect("runs").prediction();
    let flow = matched.flow.as_ref().expect("a flow");
    for (x, f) in input.p.points.iter().zip(flow) {
        let d = input.q.points.iter().map(|y| (x + f - y).norm()).fold(f32::INFINITY, f32::min);
        assert!(d < 1e-5, "P + flow lies on a point of Q: {d}");
    }
    let k = matched.motions.len();
    assert!(matched.segments_p.iter().chain(&matched.segments_q).all(|&l| (l as usize) < k));
    // A scanned Q is left alone.
    let mut scanned = input.clone();
    scanned.kind = pairs::PairKind::Sf2p;
    let plain = InferenceParams { max_iterations: 2, ..InferenceParams::iterative() };
    assert_eq!(
        net.infer(&scanned, &params).expect("runs"),
        net.infer(&scanned, &plain).expect("runs")
    );
}

#[test]
fn procedures_are_scored_side_by_side_against_the_first() {
    use model::procedures::{release_variants, score_procedure, table, to_csv};
    let (net, pair) = net_and_pair();
    let mut scanned = pair.clone();
    let variants = release_variants();
    assert_eq!(
        variants.iter().map(|v| v.name).collect::<Vec<_>>(),
        ["paper", "+align", "+sub", "+full", "release"]
    );
    assert_eq!(variants[0].params, InferenceParams::iterative());
    let paper = variants[0].clone();
    let full = variants[3].clone();
    // A second pair that differs only in its kind: full matching leaves it alone.
    scanned = {
        let mut input = scanned.input().clone();
        input.kind = pairs::PairKind::Sf2p;
        Pair::new(input, pair.truth().clone(), pair.provenance().clone()).expect("a valid pair")
    };
    let pairs = vec![pair, scanned];
    let a = score_procedure(&net, &pairs, &paper).expect("scores");
    let b = score_procedure(&net, &pairs, &full).expect("scores");
    let key = |s: &model::train::validation::PairScores| (s.epe, s.rand_index, s.iou_sum, s.parts);
    assert_eq!(key(&a.pairs[1]), key(&b.pairs[1]), "a scanned Q is not matched");
    assert!(a.pairs[0].support_iou.is_nan(), "the support IoU is not scored");
    assert_eq!(a.passes.len(), 2);
    let lines = table(&pairs, &[a.clone(), b], 50, 1).expect("compares");
    // all, SF2F, SF2P: two variants each.
    assert_eq!(lines.len(), 6);
    assert!(lines[0].against_first.is_none());
    let sf2p = lines.iter().find(|l| l.group == "SF2P" && l.variant == "+full").unwrap();
    let d = sf2p.against_first.expect("a comparison").iou;
    assert_eq!((d.value, d.low, d.high), (0.0, 0.0, 0.0));
    let all = lines.iter().find(|l| l.group == "all" && l.variant == "paper").unwrap();
    assert_eq!(all.scores.epe, (a.pairs[0].epe + a.pairs[1].epe) / 2.0);
    let csv = to_csv(&lines);
    assert_eq!(csv.lines().count(), 7);
    assert!(csv.lines().all(|l| l.split(',').count() == 16), "every row has the header's fields");
    assert!(csv.lines().nth(1).unwrap().starts_with("paper,all,2,"));
}
