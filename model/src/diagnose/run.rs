//! The diagnosis itself: every oracle row computed pair by pair and summed.

use pairs::math::{Point3, Vector3};
use pairs::metrics::{epe, matched_iou};
use pairs::transform::fit_similarity_weighted;
use pairs::{Pair, PartId};

use crate::diagnose::report::{DiagnoseError, DiagnoseParams, Diagnosis, Row, ScaleSummary};
use crate::inference::labels::{argmax, segment_pair};
use crate::inference::InferenceParams;
use crate::network::predict::{interpolate, LinearMotion};
use crate::network::sampling::farthest_point_sampling;
use crate::network::PartInductionNet;
use crate::train::validation::{support_iou, true_flow, ScoreError};

/// Sums of one row's scores over pairs.
#[derive(Debug, Clone, Default)]
struct Sums {
    support: f64,
    support_n: usize,
    iou: f64,
    parts: usize,
    epe: f64,
    epe_n: usize,
}

impl Sums {
    fn row(&self, name: String) -> Row {
        let mean = |v: f64, n: usize| (n > 0).then(|| v / n as f64);
        Row {
            name,
            support_iou: mean(self.support, self.support_n),
            iou: mean(self.iou, self.parts),
            epe: mean(self.epe, self.epe_n),
        }
    }
}

/// The residual rule's 0/1 support matrix on the subset points `x` with flow `f`.
fn rule_support(x: &[Point3], f: &[Vector3], motions: &[LinearMotion], tau: f32) -> Vec<f32> {
    motions
        .iter()
        .flat_map(|(r, t)| {
            x.iter().zip(f).map(move |(xj, fj)| {
                let residual = r * xj.coords + t - (xj.coords + fj);
                if residual.norm() < tau {
                    1.0
                } else {
                    0.0
                }
            })
        })
        .collect()
}

/// The motion of every true part fitted to the true flow (rigid, or a similarity), as the
/// hypothesis of each subset point of that part.
fn fitted_hypotheses(
    pair: &Pair,
    subset: &[usize],
    with_scale: bool,
) -> Result<Vec<LinearMotion>, DiagnoseError> {
    let truth = pair.truth();
    let p = &pair.input().p.points;
    let moved: Vec<Point3> = p.iter().zip(true_flow(pair)?).map(|(x, f)| x + f).collect();
    let k = truth.part_p.iter().copied().max().map_or(0, |m| m as usize + 1);
    let mut fits = Vec::with_capacity(k);
    for part in 0..k {
        let weights: Vec<f32> =
            truth.part_p.iter().map(|&l| if l as usize == part { 1.0 } else { 0.0 }).collect();
        let fit = fit_similarity_weighted(p, &moved, &weights, with_scale);
        fits.push(fit.map(|s| (s.rotation * s.scale, s.translation)));
    }
    subset
        .iter()
        .map(|&i| {
            let part = truth.part_p[i];
            fits[part as usize]
                .ok_or_else(|| DiagnoseError::Fit { pair: pair.id().to_string(), part })
        })
        .collect()
}

/// Diagnoses `net` on `pairs` (see the module docs for the rows).
pub fn diagnose(
    net: &PartInductionNet,
    pairs: &[Pair],
    params: &DiagnoseParams,
    mut progress: impl FnMut(usize),
) -> Result<Diagnosis, DiagnoseError> {
    if pairs.is_empty() {
        return Err(DiagnoseError::Empty);
    }
    let taus = &params.thresholds;
    let names: Vec<String> = [
        "flow: the flow module".to_string(),
        "flow: the matching's soft-argmax".to_string(),
        "flow: the matching's argmax".to_string(),
    ]
    .into_iter()
    .chain(
        params
            .flow_samples
            .iter()
            .map(|n| format!("flow: the true flow at {n} points, interpolated")),
    )
    .chain(params.matching_samples.iter().map(|n| {
        format!("flow: each point to Q's subset point nearest its true end, {n} points (matching floor)")
    }))
    .chain([
        "flow: the flow module fed the true matching (one-hot, times the true mask)".to_string(),
        "residual: the flow module on P moved by the true motions (mean flow; ideal 0)".to_string(),
        "residual: the flow module on (Q, Q) (mean flow; ideal 0)".to_string(),
        "flow: two passes (the flow module again on P moved by its flow; the sum)".to_string(),
    ])
    .chain(["true flow: the support module (net-seg@gt-flow, one pass)".to_string()])
    .chain(
        ["the network's hypotheses", "a rigid fit per true part", "a similarity fit per true part"]
            .iter()
            .flat_map(|source| {
                taus.iter().map(move |t| format!("true flow: rule τ = {t} on {source}"))
            }),
    )
    .chain(["true flow: the true same-part matrix".to_string()])
    .chain(ceiling_sizes(net).iter().flat_map(|n| {
        [
            format!("ceiling: true labels at {n} points, interpolated (argmax)"),
            format!("ceiling: true labels at {n} points, interpolated (graph cut)"),
        ]
    }))
    .chain(params.iterations.then(iteration_rows).into_iter().flatten())
    .collect();
    let mut sums = vec![Sums::default(); names.len()];
    let mut scales = Vec::with_capacity(pairs.len());
    for (done, pair) in pairs.iter().enumerate() {
        let id = || pair.id().to_string();
        let network = |source| ScoreError::Predict { pair: id(), source };
        let metric = |source| ScoreError::Metric { pair: id(), source };
        let (input, truth) = (pair.input(), pair.truth());
        let truth_flow = true_flow(pair)?;
        let points = &input.p.points;
        let mut row = 0;
        let add_epe_to = |sums: &mut [Sums], row: &mut usize, flow: &[Vector3], to: &[Vector3]| {
            let e = epe(flow, to).map_err(metric)?;
            sums[*row].epe += e;
            sums[*row].epe_n += 1;
            *row += 1;
            Ok::<_, DiagnoseError>(())
        };
        let add_epe = |sums: &mut [Sums], row: &mut usize, flow: &[Vector3]| {
            add_epe_to(sums, row, flow, truth_flow)
        };
        let (flow, _) = net.flow_pass(input).map_err(network)?;
        add_epe(&mut sums, &mut row, &flow)?;
        let (soft, hard) = net.matching_flows(input).map_err(network)?;
        add_epe(&mut sums, &mut row, &soft)?;
        add_epe(&mut sums, &mut row, &hard)?;
        let plain: Vec<[f32; 3]> = points.iter().map(|x| [x.x, x.y, x.z]).collect();
        for &n in &params.flow_samples {
            let subset = farthest_point_sampling(&plain, n.min(plain.len())).map_err(network)?;
            let sub: Vec<[f32; 3]> = subset.iter().map(|&i| plain[i]).collect();
            let values: Vec<f32> = subset
                .iter()
                .flat_map(|&i| [truth_flow[i].x, truth_flow[i].y, truth_flow[i].z])
                .collect();
            let back = interpolate(&plain, &sub, &values, 3).map_err(network)?;
            let back: Vec<Vector3> =
                back.chunks(3).map(|f| Vector3::new(f[0], f[1], f[2])).collect();
            add_epe(&mut sums, &mut row, &back)?;
        }
        // The matching floor: each subset point of P to the point of Q's subset nearest its
        // true end, interpolated to every point of P.
        let q_plain: Vec<[f32; 3]> = input.q.points.iter().map(|x| [x.x, x.y, x.z]).collect();
        for &n in &params.matching_samples {
            let sub_p = farthest_point_sampling(&plain, n.min(plain.len())).map_err(network)?;
            let sub_q = farthest_point_sampling(&q_plain, n.min(q_plain.len())).map_err(network)?;
            let p_m: Vec<[f32; 3]> = sub_p.iter().map(|&i| plain[i]).collect();
            let values: Vec<f32> = sub_p
                .iter()
                .flat_map(|&i| {
                    let end = points[i] + truth_flow[i];
                    let j = sub_q
                        .iter()
                        .copied()
                        .min_by(|&a, &b| {
                            (input.q.points[a] - end)
                                .norm_squared()
                                .total_cmp(&(input.q.points[b] - end).norm_squared())
                        })
                        .unwrap_or(0);
                    let f = input.q.points[j] - points[i];
                    [f.x, f.y, f.z]
                })
                .collect();
            let back = interpolate(&plain, &p_m, &values, 3).map_err(network)?;
            let back: Vec<Vector3> =
                back.chunks(3).map(|f| Vector3::new(f[0], f[1], f[2])).collect();
            add_epe(&mut sums, &mut row, &back)?;
        }
        let fed =
            net.flow_given_true_matching(input, truth_flow, &truth.corr_mask).map_err(network)?;
        add_epe(&mut sums, &mut row, &fed)?;
        let mut aligned = input.clone();
        aligned.p.points = points.iter().zip(truth_flow).map(|(x, f)| x + f).collect();
        let (residual, _) = net.flow_pass(&aligned).map_err(network)?;
        add_epe_to(&mut sums, &mut row, &residual, &vec![Vector3::zeros(); residual.len()])?;
        let null = net.null_flow(input).map_err(network)?;
        add_epe_to(&mut sums, &mut row, &null, &vec![Vector3::zeros(); null.len()])?;
        // A second pass from where the first left P: does the module refine its own flow?
        let mut moved = input.clone();
        moved.p.points = points.iter().zip(&flow).map(|(x, f)| x + f).collect();
        let (second, _) = net.flow_pass(&moved).map_err(network)?;
        let twice: Vec<Vector3> = flow.iter().zip(&second).map(|(a, b)| a + b).collect();
        add_epe(&mut sums, &mut row, &twice)?;
        // Segmentation on the true flow.
        let add_pass = |sums: &mut [Sums], row: &mut usize, support: Option<(&[f32], f64)>| {
            let probs = net
                .soft_segments_given(input, truth_flow, support.map(|(s, _)| s))
                .map_err(network)?;
            let matching = matched_iou(&argmax(&probs), &truth.part_p).map_err(metric)?;
            let r = &mut sums[*row];
            r.iou += matching.iou.iter().sum::<f64>();
            r.parts += matching.iou.len();
            if let Some((_, s)) = support {
                r.support += s;
                r.support_n += 1;
            }
            *row += 1;
            Ok::<_, DiagnoseError>(())
        };
        let (subset, probs) = net.supports(input, truth_flow).map_err(network)?;
        let parts_s: Vec<PartId> = subset.iter().map(|&i| truth.part_p[i]).collect();
        let own = support_iou(&probs, &parts_s);
        sums[row].support += own;
        sums[row].support_n += 1;
        add_pass(&mut sums, &mut row, None)?;
        let x: Vec<Point3> = subset.iter().map(|&i| points[i]).collect();
        let f: Vec<Vector3> = subset.iter().map(|&i| truth_flow[i]).collect();
        let (_, own_motions) = net.hypotheses(input, truth_flow).map_err(network)?;
        for motions in [
            own_motions,
            fitted_hypotheses(pair, &subset, false)?,
            fitted_hypotheses(pair, &subset, true)?,
        ] {
            for &tau in taus {
                let support = rule_support(&x, &f, &motions, tau);
                let score = support_iou(&support, &parts_s);
                add_pass(&mut sums, &mut row, Some((&support, score)))?;
            }
        }
        let same: Vec<f32> = parts_s
            .iter()
            .flat_map(|a| parts_s.iter().map(move |b| if a == b { 1.0 } else { 0.0 }))
            .collect();
        let score = support_iou(&same, &parts_s);
        add_pass(&mut sums, &mut row, Some((&same, score)))?;
        // The subset ceiling.
        let k = truth.part_p.iter().copied().max().map_or(1, |m| m as usize + 1);
        for n in ceiling_sizes(net) {
            let subset = farthest_point_sampling(&plain, n.min(plain.len())).map_err(network)?;
            let sub: Vec<[f32; 3]> = subset.iter().map(|&i| plain[i]).collect();
            let one_hot: Vec<f32> = subset
                .iter()
                .flat_map(|&i| {
                    (0..k).map(move |c| if truth.part_p[i] as usize == c { 1.0 } else { 0.0 })
                })
                .collect();
            let probs: Vec<Vec<f32>> = interpolate(&plain, &sub, &one_hot, k)
                .map_err(network)?
                .chunks(k)
                .map(<[f32]>::to_vec)
                .collect();
            for labels in [
                argmax(&probs),
                segment_pair(points, &input.q.points, &probs, truth_flow, &params.hard).labels_p,
            ] {
                let matching = matched_iou(&labels, &truth.part_p).map_err(metric)?;
                sums[row].iou += matching.iou.iter().sum::<f64>();
                sums[row].parts += matching.iou.len();
                row += 1;
            }
        }
        if params.iterations {
            let labels = pairs::parts::part_segments(&truth.part_p);
            for start in [None, Some(labels.as_slice())] {
                let prediction = net
                    .infer_from(input, &InferenceParams::iterative(), start)
                    .map_err(network)?
                    .prediction();
                let flow = prediction.flow.clone().unwrap_or_default();
                let matching =
                    matched_iou(&prediction.segments_p, &truth.part_p).map_err(metric)?;
                sums[row].iou += matching.iou.iter().sum::<f64>();
                sums[row].parts += matching.iou.len();
                add_epe(&mut sums, &mut row, &flow)?;
                let rigid: Vec<Vector3> = points
                    .iter()
                    .zip(&prediction.segments_p)
                    .map(|(x, &l)| {
                        prediction
                            .motions
                            .get(l as usize)
                            .map_or(Vector3::zeros(), |m| m.apply(x) - x)
                    })
                    .collect();
                add_epe(&mut sums, &mut row, &rigid)?;
            }
        }
        debug_assert_eq!(row, names.len());
        scales.push(f64::from((truth.motions.first().map_or(1.0, |m| m.scale) - 1.0).abs()));
        progress(done + 1);
    }
    scales.sort_by(f64::total_cmp);
    let at =
        |q: f64| scales[((q * (scales.len() - 1) as f64).round() as usize).min(scales.len() - 1)];
    Ok(Diagnosis {
        pairs: pairs.len(),
        rows: names.into_iter().zip(&sums).map(|(name, s)| s.row(name)).collect(),
        scale: ScaleSummary { median: at(0.5), p90: at(0.9), max: at(1.0) },
    })
}

/// The names of the iterative procedure's rows: from the network's first pass and from the
/// true labels, each its final flow (with its labels' IoU) and the piecewise-rigid flow of
/// its final segments alone.
fn iteration_rows() -> Vec<String> {
    ["net-iter", "net-iter from the true labels"]
        .iter()
        .flat_map(|from| {
            [
                format!("{from}: the final flow (P' - P + last residual), its labels"),
                format!("{from}: the piecewise-rigid flow of its final segments alone"),
            ]
        })
        .collect()
}

/// The subset sizes of the ceiling rows: the segmentation subset, then the correspondence
/// subset when it differs (one row each, not two equal ones).
fn ceiling_sizes(net: &PartInductionNet) -> Vec<usize> {
    let mut sizes = vec![net.seg_points(), net.corr_points()];
    sizes.dedup();
    sizes
}
