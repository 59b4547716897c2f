//! `model diagnose` on a tiny set with an untrained network: the oracle rows must score as
//! oracles do, whatever the network, and the network's rows must not.

use burn::prelude::*;
use generator::config::GeneratorConfig;
use generator::stream::TrainingStream;
use model::diagnose::{diagnose, DiagnoseError, DiagnoseParams};
use model::network::PartInductionNet;
use model::train::config::TrainConfig;
use model::train::stream_config;
use pairs::Pair;

fn pairs(n: usize) -> (TrainConfig, Vec<Pair>) {
    let config = TrainConfig::built_in("tiny");
    let pairs = TrainingStream::new(GeneratorConfig {
        categories: vec!["laptop".into(), "scissors".into()],
        ..stream_config(&config)
    })
    .expect("valid generator config")
    .take(n)
    .collect::<Result<_, _>>()
    .expect("pairs");
    (config, pairs)
}

#[test]
fn oracle_rows_score_as_oracles() {
    let (config, pairs) = pairs(3);
    let points = pairs[0].input().p.points.len();
    let net = PartInductionNet::seeded(&config.network, &Device::flex(), 11);
    let params = DiagnoseParams {
        thresholds: vec![0.001, 0.5],
        flow_samples: vec![points],
        ..DiagnoseParams::default()
    };
    let mut seen = Vec::new();
    let d = diagnose(&net, &pairs, &params, |done| seen.push(done)).expect("a diagnosis");
    assert_eq!(seen, [1, 2, 3], "progress after every pair");
    assert_eq!(d.pairs, 3);
    let row = |name: &str| {
        d.rows.iter().find(|r| r.name == name).unwrap_or_else(|| panic!("no row {name}"))
    };
    // The true flow at every point, interpolated back, is the true flow.
    let all = row(&format!("flow: the true flow at {points} points, interpolated"));
    assert!(all.epe.expect("an EPE") < 1e-6, "{all:?}");
    // A similarity fit per true part is exact on the true flow: at τ = 0.001 each
    // hypothesis supports exactly its part.
    let exact = row("true flow: rule τ = 0.001 on a similarity fit per true part");
    assert!(exact.support_iou.expect("a support IoU") > 0.999, "{exact:?}");
    let truth = row("true flow: the true same-part matrix");
    assert_eq!(truth.support_iou, Some(1.0));
    // An untrained network's hypotheses are translations by each point's own flow: at a
    // tight threshold they do not pick out the moving parts.
    let own = row("true flow: rule τ = 0.001 on the network's hypotheses");
    assert!(own.support_iou.expect("a support IoU") < 0.9, "{own:?}");
    // A threshold as large as the cloud supports everything: no better than chance.
    let loose = row("true flow: rule τ = 0.5 on a similarity fit per true part");
    assert!(loose.support_iou < exact.support_iou, "{loose:?}");
    // The matching floor falls as Q's subset grows (farthest point subsets are nested), and
    // with every point of Q in the subset it is the distance to Q's nearest point.
    let floor = |n: usize| {
        row(&format!(
            "flow: each point to Q's subset point nearest its true end, {n} points (matching floor)"
        ))
        .epe
        .expect("an EPE")
    };
    assert!(floor(128) >= floor(256) && floor(256) >= floor(512), "{:?}", d.rows);
    assert!(floor(128) > 0.0);
    // The mean flow on a nearly aligned pair and on (Q, Q) is a length.
    for name in [
        "residual: the flow module on P moved by the true motions (mean flow; ideal 0)",
        "residual: the flow module on (Q, Q) (mean flow; ideal 0)",
    ] {
        assert!(row(name).epe.is_some_and(|v| v.is_finite() && v >= 0.0), "{name}");
    }
    // The untrained flow head is zero-initialised: its flow is 0, so P moved by it is P and
    // a second pass adds another 0.
    let once = row("flow: the flow module").epe.expect("an EPE");
    let twice = row("flow: two passes (the flow module again on P moved by its flow; the sum)")
        .epe
        .expect("an EPE");
    assert!((once - twice).abs() <= 1e-6 * once.max(1e-6), "{once} against {twice}");
    // Started from the true labels, the iterations' piecewise-rigid flow fits the true
    // motions to the untrained network's flow: an EPE, not the truth's 0.
    let from_truth =
        row("net-iter from the true labels: the piecewise-rigid flow of its final segments alone");
    assert!(from_truth.epe.is_some_and(|v| v.is_finite()), "{from_truth:?}");
    // Every IoU is a fraction; the flow rows have no IoU and the segmentation rows no EPE,
    // except the iterations' final rows, which score both.
    for r in &d.rows {
        assert!(r.iou.is_none_or(|v| (0.0..=1.0).contains(&v)), "{r:?}");
        assert!(r.epe.is_none() || r.iou.is_none() || r.name.contains("the final flow"), "{r:?}");
    }
    // Laptops and scissors rotate a part: the motions' scale is not 1 for every pair.
    assert!(d.scale.max > 0.0 && d.scale.median <= d.scale.p90 && d.scale.p90 <= d.scale.max);
    let csv = d.to_csv();
    assert_eq!(csv.lines().count(), d.rows.len() + 2, "{csv}");
    assert!(csv.starts_with("row,support_iou,iou,epe\n"));
}

#[test]
fn no_pairs_is_an_error() {
    let config = TrainConfig::built_in("tiny");
    let net = PartInductionNet::seeded(&config.network, &Device::flex(), 1);
    let err = diagnose(&net, &[], &DiagnoseParams::default(), |_| {}).expect_err("empty");
    assert!(matches!(err, DiagnoseError::Empty));
}
