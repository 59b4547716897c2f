//! The procedure itself: the first pass, the piecewise-rigid deformation of P by the
//! segments' motions, the residual flow on (P', Q), and the stop rule; the record of every
//! pass ([`Inference`]).

use pairs::math::{Matrix3, Point3, Real, Vector3};
use pairs::{PairInput, PairKind, Prediction};

use crate::inference::labels::{self, segment_pair, HardLabelParams, HardSegmentation};
use crate::inference::subproblems::{expand_eps, Geodesic};
use crate::inference::InferenceParams;
use crate::network::sampling::SamplingError;
use crate::network::PartInductionNet;

/// One pass of the procedure, in P's original frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Iteration {
    /// The flow, hard labels of P and Q, motions, mask and soft segments after this pass.
    pub prediction: Prediction,
    /// Mean norm of the flow's change from the previous pass (infinite for the first).
    pub change: Real,
    /// Mean norm of the residual flow the network predicted in this pass (after the
    /// calibration): how far P' still is from Q in the network's view (with sub-problems,
    /// of each point's chosen sub-pair residual).
    pub residual: Real,
}

/// The whole procedure's record.
#[derive(Debug, Clone, PartialEq)]
pub struct Inference {
    /// The rotation applied to P before the first pass (identity without search).
    pub rotation: Matrix3,
    /// Every pass, the first one first; the last is the result.
    pub iterations: Vec<Iteration>,
}

impl Inference {
    /// The last pass's prediction.
    pub fn prediction(&self) -> Prediction {
        self.iterations.last().map(|it| it.prediction.clone()).unwrap_or_default()
    }
}

/// `input` with P's points replaced by `points` (its normalisation kept).
fn with_p(input: &PairInput, points: Vec<Point3>) -> PairInput {
    let mut moved = input.clone();
    moved.p.points = points;
    moved
}

/// `points` moved by the rigid motion (Kabsch, no scale) that best maps them to
/// `points + flow`; `points` unchanged when no motion fits (fewer than one point, or a
/// non-finite flow).
pub fn align_globally(points: &[Point3], flow: &[Vector3]) -> Vec<Point3> {
    let moved: Vec<Point3> = points.iter().zip(flow).map(|(x, f)| x + f).collect();
    let weights = vec![1.0; points.len()];
    match pairs::transform::fit_similarity_weighted(points, &moved, &weights, false) {
        Some(fit) => points.iter().map(|x| fit.apply(x)).collect(),
        None => points.to_vec(),
    }
}

/// The index of the point of `cloud` nearest `x` (0 for an empty cloud).
pub(crate) fn nearest(cloud: &[Point3], x: &Point3) -> usize {
    (0..cloud.len())
        .min_by(|&a, &b| (cloud[a] - x).norm_squared().total_cmp(&(cloud[b] - x).norm_squared()))
        .unwrap_or(0)
}

/// A pass's prediction in P's original frame from its flow and segments of the rotated P
/// (`start = rotation · original`): the flow of x is R x + f - x, each motion M ∘ R.
fn in_original_frame(
    original: &[Point3],
    start: &[Point3],
    rotation: Matrix3,
    flow: &[Vector3],
    seg: &HardSegmentation,
    mask: Vec<f32>,
) -> Prediction {
    let flow = original.iter().zip(start).zip(flow).map(|((x, r), f)| r + f - x).collect();
    let motions = seg
        .motions
        .iter()
        .map(|m| pairs::transform::Similarity { rotation: m.rotation * rotation, ..*m })
        .collect();
    Prediction {
        flow: Some(flow),
        segments_p: seg.labels_p.clone(),
        segments_q: seg.labels_q.clone(),
        motions,
        corr_mask: Some(mask),
        segment_probs: Some(seg.probs.clone()),
        joints: None,
    }
}

impl PartInductionNet {
    /// Soft segments of the rotated P under `flow`, then hard labels and motions.
    fn segment_rotated(
        &self,
        rotated: &PairInput,
        flow: &[Vector3],
        params: &HardLabelParams,
    ) -> Result<HardSegmentation, SamplingError> {
        let probs = self.soft_segments(rotated, flow)?;
        Ok(segment_pair(&rotated.p.points, &rotated.q.points, &probs, flow, params))
    }

    /// The network's flow from Q to itself, on Q's points (ideally zero).
    pub fn null_flow(&self, input: &PairInput) -> Result<Vec<Vector3>, SamplingError> {
        let mut same = input.clone();
        same.p = input.q.clone();
        Ok(self.flow_pass(&same)?.0)
    }

    /// Runs the procedure of the module docs on `input`.
    pub fn infer(
        &self,
        input: &PairInput,
        params: &InferenceParams,
    ) -> Result<Inference, SamplingError> {
        self.infer_from(input, params, None)
    }

    /// [`Self::infer`], with the passes started from `labels` of P (segments `0..K`) when
    /// given: P is first moved piecewise rigidly by one motion per segment, fitted to the
    /// network's flow of the (calibrated) first prediction, as a pass with those labels
    /// would have moved it (diagnosis: the iterations' ceiling from the true labels).
    pub fn infer_from(
        &self,
        input: &PairInput,
        params: &InferenceParams,
        labels: Option<&[u32]>,
    ) -> Result<Inference, SamplingError> {
        let rotation = if params.rotation_search {
            self.search_rotation(input)?.rotation
        } else {
            Matrix3::identity()
        };
        let original = &input.p.points;
        let rotated =
            with_p(input, original.iter().map(|x| Point3::from(rotation * x.coords)).collect());
        let start = &rotated.p.points;
        let mut iterations: Vec<Iteration> = Vec::new();
        let mut deformed = rotated.clone();
        let null = if params.calibrate { Some(self.null_flow(input)?) } else { None };
        let calibrated = |deformed: &PairInput| -> Result<(Vec<Vector3>, Vec<f32>), SamplingError> {
            let (mut residual, mask) = self.flow_pass(deformed)?;
            if let Some(null) = &null {
                for (r, x) in residual.iter_mut().zip(&deformed.p.points) {
                    *r -= null[nearest(&input.q.points, x)];
                }
            }
            Ok((residual, mask))
        };
        for _ in 0..params.global_alignments {
            let (flow, _) = calibrated(&deformed)?;
            deformed = with_p(&rotated, align_globally(&deformed.p.points, &flow));
        }
        if let Some(labels) = labels {
            let (residual, _) = calibrated(&deformed)?;
            let flow: Vec<Vector3> = deformed
                .p
                .points
                .iter()
                .zip(start)
                .zip(&residual)
                .map(|((moved, x), f)| moved - x + f)
                .collect();
            let k = labels.iter().max().map_or(0, |&m| m as usize + 1);
            let weights = vec![1.0; labels.len()];
            let motions = labels::fit_motions_shared_scale(start, &flow, labels, &weights, k);
            deformed = with_p(
                &rotated,
                start.iter().zip(labels).map(|(x, &l)| motions[l as usize].apply(x)).collect(),
            );
        }
        let graphs =
            params.sub_problems.then(|| (Geodesic::new(start), Geodesic::new(&input.q.points)));
        // The previous pass's segments and flow (of the rotated P), for the sub-problems.
        let mut previous: Option<(HardSegmentation, Vec<Vector3>)> = None;
        for pass in 0..params.max_iterations.max(1) {
            let (flow, mask, residual_norm) = match (&graphs, &previous) {
                (Some((p_graph, q_graph)), Some((seg, flow))) => {
                    let sub = self.sub_problem_flow(
                        &rotated,
                        start,
                        (p_graph, q_graph),
                        (&seg.labels_p, &seg.labels_q),
                        &seg.motions,
                        flow,
                        null.as_deref(),
                        expand_eps(pass),
                    )?;
                    (sub.flow, sub.mask, sub.residual)
                }
                _ => {
                    let (residual, mask) = calibrated(&deformed)?;
                    // The refined flow of the rotated P: (P' - P) + f'.
                    let flow: Vec<Vector3> = deformed
                        .p
                        .points
                        .iter()
                        .zip(start)
                        .zip(&residual)
                        .map(|((moved, x), f)| moved - x + f)
                        .collect();
                    let norm = residual.iter().map(|r| r.norm()).sum::<Real>()
                        / residual.len().max(1) as Real;
                    (flow, mask, norm)
                }
            };
            let seg = self.segment_rotated(&rotated, &flow, &params.labels)?;
            deformed = with_p(
                &rotated,
                start
                    .iter()
                    .zip(&seg.labels_p)
                    .map(|(x, &l)| seg.motions[l as usize].apply(x))
                    .collect(),
            );
            let prediction = in_original_frame(original, start, rotation, &flow, &seg, mask);
            let change = iterations.last().and_then(|last| last.prediction.flow.as_ref()).map_or(
                Real::INFINITY,
                |previous| {
                    let now = prediction.flow.as_deref().unwrap_or_default();
                    let total: Real = previous.iter().zip(now).map(|(a, b)| (a - b).norm()).sum();
                    total / now.len().max(1) as Real
                },
            );
            let levelled = iterations.last().is_some_and(|last| {
                residual_norm > last.residual * (1.0 - params.min_residual_decrease)
            });
            iterations.push(Iteration { prediction, change, residual: residual_norm });
            previous = Some((seg, flow));
            // With sub-problems every pass runs, as in the release (its radii shrink pass by
            // pass, and a residual of the smallest sub-pair is not the whole pair's).
            if !params.sub_problems && (change < params.tolerance || levelled) {
                break;
            }
        }
        if params.full_matching && input.kind == PairKind::Sf2f {
            if let (Some((_, flow)), Some(last)) = (previous, iterations.last_mut()) {
                let q = &input.q.points;
                let snapped: Vec<Vector3> =
                    start.iter().zip(&flow).map(|(x, f)| q[nearest(q, &(x + f))] - x).collect();
                let seg = self.segment_rotated(&rotated, &snapped, &params.labels)?;
                let mask = last.prediction.corr_mask.take().unwrap_or_default();
                last.prediction =
                    in_original_frame(original, start, rotation, &snapped, &seg, mask);
            }
        }
        Ok(Inference { rotation, iterations })
    }

    /// The segmentation module on a given flow with the graph-cut labels of
    /// [`segment_pair`]: the network as one more segmenter over any flow source (the
    /// evaluator's `net-seg` rows).
    pub fn segment_flow_with(
        &self,
        input: &PairInput,
        flow: &[Vector3],
        params: &HardLabelParams,
    ) -> Result<Prediction, SamplingError> {
        let probs = self.soft_segments(input, flow)?;
        let seg = segment_pair(&input.p.points, &input.q.points, &probs, flow, params);
        Ok(Prediction {
            flow: None,
            segments_p: seg.labels_p,
            segments_q: seg.labels_q,
            motions: seg.motions,
            corr_mask: None,
            segment_probs: Some(seg.probs),
            joints: None,
        })
    }
}
