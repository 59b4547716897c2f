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

use pairs::math::{Matrix3, Point3, Real, Vector3};
use pairs::{PairInput, Prediction};

use crate::inference::labels::{segment_pair, HardLabelParams};
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
    /// calibration): how far P' still is from Q in the network's view.
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
fn nearest(cloud: &[Point3], x: &Point3) -> usize {
    (0..cloud.len())
        .min_by(|&a, &b| (cloud[a] - x).norm_squared().total_cmp(&(cloud[b] - x).norm_squared()))
        .unwrap_or(0)
}

impl PartInductionNet {
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
        for _ in 0..params.max_iterations.max(1) {
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
            let probs = self.soft_segments(&rotated, &flow)?;
            let seg = segment_pair(start, &input.q.points, &probs, &flow, &params.labels);
            deformed = with_p(
                &rotated,
                start
                    .iter()
                    .zip(&seg.labels_p)
                    .map(|(x, &l)| seg.motions[l as usize].apply(x))
                    .collect(),
            );
            // Back to P's original frame: the flow of x is R x + f - x, each motion M ∘ R.
            let flow_original: Vec<Vector3> =
                original.iter().zip(start).zip(&flow).map(|((x, r), f)| r + f - x).collect();
            let change = iterations.last().and_then(|last| last.prediction.flow.as_ref()).map_or(
                Real::INFINITY,
                |previous| {
                    let total: Real =
                        previous.iter().zip(&flow_original).map(|(a, b)| (a - b).norm()).sum();
                    total / flow_original.len().max(1) as Real
                },
            );
            let motions = seg
                .motions
                .iter()
                .map(|m| pairs::transform::Similarity { rotation: m.rotation * rotation, ..*m })
                .collect();
            let residual_norm =
                residual.iter().map(|r| r.norm()).sum::<Real>() / residual.len().max(1) as Real;
            let levelled = iterations.last().is_some_and(|last| {
                residual_norm > last.residual * (1.0 - params.min_residual_decrease)
            });
            iterations.push(Iteration {
                prediction: Prediction {
                    flow: Some(flow_original),
                    segments_p: seg.labels_p,
                    segments_q: seg.labels_q,
                    motions,
                    corr_mask: Some(mask),
                    segment_probs: Some(seg.probs),
                    joints: None,
                },
                change,
                residual: residual_norm,
            });
            if change < params.tolerance || levelled {
                break;
            }
        }
        Ok(Inference { rotation, iterations })
    }
}
