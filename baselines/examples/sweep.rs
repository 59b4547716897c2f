//! Chooses the baselines' thresholds on the validation split (never on test data) and
//! writes `reports/baselines_sweep.csv`. This should take a few minutes in release mode and
//! print the chosen values, which are the `Default`s of `SeqRansacParams`, `JLinkageParams`,
//! `SpectralParams`, `IcpParams` and `NrrParams`.
//!
//! ```text
//! cargo run --release -p baselines --example sweep -- [pairs] [points]
//! ```
//!
//! Pairs come from the generator's validation categories (seed 20181201, as the network's
//! validation set). Segmenters run on each pair's ground-truth flow, both exact ("clean")
//! and corrupted as in the tests ("noisy": 5% Gaussian noise, 10% outliers), since in the
//! benchmark they run on estimated flows; each value is scored by the matched IoU averaged
//! over every ground-truth part of every pair, and the best mean over the two flows wins.
//! ICP's trimming is scored by the flow's end-point error, NRR's feature weight and part
//! threshold by its own segments' IoU. Rows `defaults` give every flow method's EPE.

#[path = "../tests/support/mod.rs"]
mod support;

use std::fmt::Write as _;

use anyhow::Context;
use articulated::categories::Split;
use baselines::{
    IcpFlow, IcpParams, JLinkage, JLinkageParams, Nrr, NrrParams, SeqRansac, SeqRansacParams,
    Spectral, SpectralParams,
};
use generator::config::GeneratorConfig;
use generator::generate::{object_pairs, GenerateError};
use pairs::math::Vector3;
use pairs::metrics::{epe, matched_iou, rand_index};
use pairs::{Method, Pair, Segmenter};

/// Seed of the validation pairs.
const SEED: u64 = 20_181_201;

fn validation_pairs(points: u32, count: usize) -> anyhow::Result<Vec<Pair>> {
    let config = GeneratorConfig {
        split: Split::Validation,
        points,
        seed: SEED,
        ..GeneratorConfig::default()
    };
    let mut pairs = Vec::new();
    let mut object = 0;
    while pairs.len() < count {
        match object_pairs(&config, object) {
            Ok(made) => pairs.extend(made.into_iter().map(|g| g.pair)),
            Err(GenerateError::TooFewPairs { .. }) => {}
            Err(e) => return Err(e).context("generating validation pairs"),
        }
        object += 1;
    }
    pairs.truncate(count);
    Ok(pairs)
}

/// Mean IoU over all ground-truth parts and mean Rand index of a segmenter on `flows`.
fn score(
    segmenter: &dyn Segmenter,
    pairs: &[Pair],
    flows: &[Vec<Vector3>],
) -> anyhow::Result<(f64, f64)> {
    let (mut iou, mut parts, mut ri) = (0.0, 0usize, 0.0);
    for (pair, flow) in pairs.iter().zip(flows) {
        let prediction = segmenter.segment(pair.input(), flow)?;
        let matching = matched_iou(&prediction.segments_p, &pair.truth().part_p)?;
        iou += matching.iou.iter().sum::<f64>();
        parts += matching.iou.len();
        ri += rand_index(&prediction.segments_p, &pair.truth().part_p)?;
    }
    Ok((iou / parts.max(1) as f64, ri / pairs.len().max(1) as f64))
}

/// One swept value: its label and the segmenter it makes.
type Candidate = (String, Box<dyn Segmenter>);

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let count: usize = args.get(1).map_or(Ok(20), |a| a.parse())?;
    let points: u32 = args.get(2).map_or(Ok(512), |a| a.parse())?;
    let pairs = validation_pairs(points, count)?;
    let clean: Vec<Vec<Vector3>> =
        pairs.iter().map(|p| p.truth().flow.clone().expect("a flow")).collect();
    let noisy: Vec<Vec<Vector3>> = clean
        .iter()
        .enumerate()
        .map(|(i, f)| support::corrupt_flow(f, 0.05, 0.10, i as u64))
        .collect();
    let thresholds = [0.01, 0.02, 0.03, 0.05, 0.08];
    let mut groups: Vec<(&str, &str, Vec<Candidate>)> = vec![
        (
            "seqransac",
            "inlier_threshold",
            thresholds
                .iter()
                .map(|&t| {
                    let params =
                        SeqRansacParams { inlier_threshold: t, ..SeqRansacParams::default() };
                    (t.to_string(), Box::new(SeqRansac::with_params(params)) as Box<dyn Segmenter>)
                })
                .collect(),
        ),
        (
            "jlc",
            "inlier_threshold",
            thresholds
                .iter()
                .map(|&t| {
                    let params =
                        JLinkageParams { inlier_threshold: t, ..JLinkageParams::default() };
                    (t.to_string(), Box::new(JLinkage::with_params(params)) as Box<dyn Segmenter>)
                })
                .collect(),
        ),
    ];
    let mut spectral = Vec::new();
    for space in [0.3, f32::INFINITY] {
        for sd in [0.01, 0.02, 0.05] {
            for sa in [0.1, 0.2, 0.3] {
                let params = SpectralParams {
                    sigma_distance: sd,
                    sigma_angle: sa,
                    sigma_space: space,
                    ..SpectralParams::default()
                };
                let label = format!("{sd}/{sa}/{space}");
                spectral
                    .push((label, Box::new(Spectral::with_params(params)) as Box<dyn Segmenter>));
            }
        }
    }
    groups.push(("sc", "sigma_distance/sigma_angle/sigma_space", spectral));

    let mut csv =
        String::from("method,parameter,value,flow,pairs,points,mean_iou,rand_index,epe,chosen\n");
    for (method, parameter, candidates) in &groups {
        let mut rows = Vec::new();
        for (value, segmenter) in candidates {
            let (iou_clean, ri_clean) = score(segmenter.as_ref(), &pairs, &clean)?;
            let (iou_noisy, ri_noisy) = score(segmenter.as_ref(), &pairs, &noisy)?;
            rows.push((value, [(iou_clean, ri_clean), (iou_noisy, ri_noisy)]));
        }
        let best = rows
            .iter()
            .enumerate()
            .max_by(|a, b| {
                (a.1 .1[0].0 + a.1 .1[1].0)
                    .total_cmp(&(b.1 .1[0].0 + b.1 .1[1].0))
                    .then(b.0.cmp(&a.0))
            })
            .map_or(0, |(i, _)| i);
        for (i, (value, scores)) in rows.iter().enumerate() {
            for (flow, (iou, ri)) in ["clean", "noisy"].iter().zip(scores) {
                writeln!(
                    csv,
                    "{method},{parameter},{value},{flow},{},{points},{iou:.4},{ri:.4},,{}",
                    pairs.len(),
                    i == best
                )?;
            }
        }
        println!(
            "{method}: {parameter} = {} (mean IoU clean {:.3}, noisy {:.3})",
            rows[best].0, rows[best].1[0].0, rows[best].1[1].0
        );
    }

    let mut icp_rows = Vec::new();
    for keep in [0.6, 0.7, 0.8, 0.9, 1.0] {
        let method =
            IcpFlow::with_params(IcpParams { keep_fraction: keep, ..IcpParams::default() });
        let mut total = 0.0;
        for pair in &pairs {
            let prediction = method.predict(pair.input())?;
            total += epe(
                prediction.flow.as_deref().unwrap_or_default(),
                pair.truth().flow.as_deref().expect("a flow"),
            )?;
        }
        icp_rows.push((keep, total / pairs.len() as f64));
    }
    let best =
        icp_rows.iter().enumerate().min_by(|a, b| a.1 .1.total_cmp(&b.1 .1)).map_or(0, |(i, _)| i);
    for (i, (keep, e)) in icp_rows.iter().enumerate() {
        writeln!(
            csv,
            "icp,keep_fraction,{keep},pair,{},{points},,,{e:.4},{}",
            pairs.len(),
            i == best
        )?;
    }
    println!("icp: keep_fraction = {} (EPE {:.4})", icp_rows[best].0, icp_rows[best].1);

    let mut nrr_rows = Vec::new();
    for features in [0.0, 0.3, 1.0] {
        for threshold in [0.01, 0.02, 0.03, 0.05] {
            let params = NrrParams {
                weight_features: features,
                segment_threshold: threshold,
                ..NrrParams::default()
            };
            let (mut iou, mut parts, mut flow_error) = (0.0, 0usize, 0.0);
            for pair in &pairs {
                let prediction = Nrr::with_params(params).predict(pair.input())?;
                let matching = matched_iou(&prediction.segments_p, &pair.truth().part_p)?;
                iou += matching.iou.iter().sum::<f64>();
                parts += matching.iou.len();
                flow_error += epe(
                    prediction.flow.as_deref().unwrap_or_default(),
                    pair.truth().flow.as_deref().expect("a flow"),
                )?;
            }
            nrr_rows.push((
                format!("{features}/{threshold}"),
                iou / parts.max(1) as f64,
                flow_error / pairs.len() as f64,
            ));
        }
    }
    let best =
        nrr_rows.iter().enumerate().max_by(|a, b| a.1 .1.total_cmp(&b.1 .1)).map_or(0, |(i, _)| i);
    for (i, (value, iou, e)) in nrr_rows.iter().enumerate() {
        writeln!(
            csv,
            "nrr,weight_features/segment_threshold,{value},own,{},{points},{iou:.4},,{e:.4},{}",
            pairs.len(),
            i == best
        )?;
    }
    println!(
        "nrr: weight_features/segment_threshold = {} (mean IoU {:.3}, EPE {:.4})",
        nrr_rows[best].0, nrr_rows[best].1, nrr_rows[best].2
    );

    // Every flow method at its defaults, for reference (nothing chosen here).
    for method in baselines::methods() {
        let mut total = 0.0;
        for pair in &pairs {
            let prediction = method.predict(pair.input())?;
            total += epe(
                prediction.flow.as_deref().unwrap_or_default(),
                pair.truth().flow.as_deref().expect("a flow"),
            )?;
        }
        let e = total / pairs.len() as f64;
        writeln!(csv, "{},defaults,,own,{},{points},,,{e:.4},", method.name(), pairs.len())?;
        println!("{} at its defaults: EPE {e:.4}", method.name());
    }

    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../reports");
    std::fs::create_dir_all(&root)?;
    let path = root.join("baselines_sweep.csv");
    std::fs::write(&path, csv).with_context(|| format!("writing {}", path.display()))?;
    println!("wrote {}", path.display());
    Ok(())
}
