//! The paper's inference procedure ("Iterative Segmentation and Motion Estimation"): a first
//! pass gives a flow, soft segments, hard labels and one rigid motion per segment; then P is
//! deformed piecewise rigidly by those motions into P', the correspondence and flow modules
//! run on (P', Q) for a residual flow f', the refined flow `P' - P + f'` is segmented again,
//! and so on until the flow changes by less than a tolerance or after 10 iterations. An
//! optional rotation search ([`rotation_search`]) picks P's initial orientation. [`labels`]
//! turns soft segments into hard labels (graph cut, fragment merging, per-segment motions,
//! Q's labels), and [`method`] is the network as the evaluator's method and segmenter.

pub mod labels;
pub mod method;
pub mod rotation_search;
pub mod subproblems;

use pairs::math::{Matrix3, Point3, Real, Vector3};
use pairs::{PairInput, PairKind, Prediction};

use crate::inference::labels::{segment_pair, HardLabelParams, HardSegmentation};
use crate::inference::subproblems::{expand_eps, Geodesic};
use crate::network::sampling::SamplingError;
use crate::network::PartInductionNet;

/// Parameters of the inference procedure.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InferenceParams {
    /// The hard-label step's parameters.
    pub labels: HardLabelParams,
    /// Most passes, the first included (paper: 10; 1 is the single pass).
    pub max_iterations: usize,
    /// Stop when the mean change of the flow between two passes is below this (normalised
    /// units: the clouds' bounding-box diagonals are 1).
    pub tolerance: Real,
    /// Also stop when the mean residual flow shrank by less than this fraction since the
    /// previous pass: the alignment has stopped improving (the paper iterates "until the
    /// total magnitude of the deformation flow field is minimized"). With the shipped
    /// weights the residual levels off after about 5 passes (0.068, 0.020, 0.016, 0.015,
    /// 0.014 on SF2F), where EPE does too.
    pub min_residual_decrease: Real,
    /// Search 48 rotations of P for the initial orientation (paper: when the pair's
    /// orientations are inconsistent; off by default).
    pub rotation_search: bool,
    /// Subtract the network's flow on (Q, Q) (at each point's nearest point of Q) from
    /// every predicted flow. A departure from the paper: a network should predict no flow
    /// between identical clouds, but the shipped weights predict a mean flow of about 0.02
    /// there, which the iteration would add again on every pass; with the correction, the
    /// procedure's fixed point is P' = Q.
    pub calibrate: bool,
    /// Global alignments before the first pass (the authors' release: 2; 0 by default, the
    /// paper's procedure): each predicts the flow of P' (P to begin with), fits one rigid
    /// motion to it (Kabsch) and moves P' by it, so that the passes start from a P' already
    /// aligned with Q as a whole. Not yet measured against the default on the validation
    /// sets.
    pub global_alignments: usize,
    /// Refine by per-segment sub-problems (the authors' release; off by default, the
    /// paper's procedure): every pass after the first runs the correspondence and flow
    /// modules on one sub-pair per segment of the previous pass, cut within a geodesic
    /// radius of the segment (0.2, then 0.15, then 0.1), instead of on the whole deformed
    /// pair ([`subproblems`]), each sub-pair's residual calibrated like the whole pair's.
    /// Every pass runs (`max_iterations`: 1 + 9 in the release), without the stop rules.
    pub sub_problems: bool,
    /// End on Q (the release's `ISFULL_MATCHING`, for full Q only): the last pass's flow
    /// is moved to the nearest point of Q and segmented again. Applies to SF2F pairs;
    /// a scanned Q is left alone (its points do not cover P's moved surface).
    pub full_matching: bool,
}

impl Default for InferenceParams {
    fn default() -> Self {
        Self::iterative()
    }
}

impl InferenceParams {
    /// The paper's iterative procedure: up to 10 passes, tolerance 1e-3, a residual that
    /// shrinks by at least 5% per pass, no rotation search, calibrated flows.
    pub fn iterative() -> Self {
        Self {
            labels: HardLabelParams::default(),
            max_iterations: 10,
            tolerance: 1e-3,
            min_residual_decrease: 0.05,
            rotation_search: false,
            calibrate: true,
            global_alignments: 0,
            sub_problems: false,
            full_matching: false,
        }
    }

    /// One pass only (the `net` row).
    pub fn single_pass() -> Self {
        Self { max_iterations: 1, ..Self::iterative() }
    }
}

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
}
