//! The multi-task objective of each training stage, with the paper's weights:
//! stage 1 `L_a + L_b + L_flow`; stage 2 `L_motion + λ_e L_e` on ground-truth flow;
//! stage 3 every term, the segmentation module on the predicted flow (detached unless the
//! run is end to end), or on the true flow for the pairs a run's `stage3_true_flow` picks.
//! [`Objective`] holds the switches that follow the authors' release instead: stage 2 with
//! the hypotheses detached from the support loss, stage 3 training the RPEN alone
//! (`L_f + L_g`), the motion loss normalised per row.

use burn::prelude::*;

use crate::network::sampling::SamplingError;
use crate::network::{Detached, PartInductionNet};
use crate::train::batch::TrainingBatch;
use crate::train::config::TrainConfig;
use crate::train::losses::{
    continuation_loss, correspondence_loss, flow_loss, motion_loss, segment_loss, support_loss,
};

/// How a run's stages combine their losses (from [`TrainConfig`]'s switches).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Objective {
    /// Stage 3's segmentation losses reach the flow and correspondence modules.
    pub end_to_end: bool,
    /// Stages 2 and 3: the support loss does not train the hypothesis generator.
    pub detach_hypotheses: bool,
    /// Stage 3 trains the RPEN alone, with `L_f + L_g`.
    pub rpen_only: bool,
    /// The motion loss weighs every row (hypothesis) equally.
    pub motion_per_row: bool,
    /// Weight of `L_e` (λ_e); every other weight is 1.
    pub support_weight: f32,
}

impl Objective {
    /// The objective a config asks for.
    pub fn of(config: &TrainConfig) -> Self {
        Self {
            end_to_end: config.end_to_end,
            detach_hypotheses: config.stage2_detach_hypotheses,
            rpen_only: config.stage3_rpen_only,
            motion_per_row: config.motion_loss_per_row,
            support_weight: config.support_weight,
        }
    }
}

impl Default for Objective {
    /// The paper's objective as this crate trained it before the release's switches: end to
    /// end off, nothing detached, pair-averaged motion loss, λ_e = 0.5.
    fn default() -> Self {
        Self {
            end_to_end: false,
            detach_hypotheses: false,
            rpen_only: false,
            motion_per_row: false,
            support_weight: 0.5,
        }
    }
}

/// The value of every loss term of a step (absent when the stage does not use it).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct LossTerms {
    /// `L_a + L_b`: matching cross-entropy and mask BCE.
    pub correspondence: Option<f32>,
    /// Flow L2 on visible points.
    pub flow: Option<f32>,
    /// Rigid-motion loss of the hypotheses.
    pub motion: Option<f32>,
    /// Support BCE `L_e` (unweighted).
    pub support: Option<f32>,
    /// Segment loss `L_f`, as `Σ (1 - IoU)` per pair.
    pub segment: Option<f32>,
    /// Continuation BCE `L_g`.
    pub continuation: Option<f32>,
}

/// Column names of [`LossTerms::values`], in order.
pub const TERM_NAMES: [&str; 6] =
    ["correspondence", "flow", "motion", "support", "segment", "continuation"];

impl LossTerms {
    /// Every term multiplied by `factor`.
    pub fn scaled(&self, factor: f32) -> Self {
        let f = |v: Option<f32>| v.map(|v| v * factor);
        Self {
            correspondence: f(self.correspondence),
            flow: f(self.flow),
            motion: f(self.motion),
            support: f(self.support),
            segment: f(self.segment),
            continuation: f(self.continuation),
        }
    }

    /// Term-by-term sums (a term absent from both stays absent).
    pub fn plus(&self, other: &Self) -> Self {
        let f = |a: Option<f32>, b: Option<f32>| match (a, b) {
            (None, None) => None,
            (a, b) => Some(a.unwrap_or(0.0) + b.unwrap_or(0.0)),
        };
        Self {
            correspondence: f(self.correspondence, other.correspondence),
            flow: f(self.flow, other.flow),
            motion: f(self.motion, other.motion),
            support: f(self.support, other.support),
            segment: f(self.segment, other.segment),
            continuation: f(self.continuation, other.continuation),
        }
    }

    /// The terms in [`TERM_NAMES`] order.
    pub fn values(&self) -> [Option<f32>; 6] {
        [self.correspondence, self.flow, self.motion, self.support, self.segment, self.continuation]
    }
}

/// Accumulates weighted terms into a total and records their values.
struct Sum {
    total: Option<Tensor<1>>,
    terms: LossTerms,
}

impl Sum {
    fn add(&mut self, loss: Tensor<1>, weight: f32, slot: fn(&mut LossTerms) -> &mut Option<f32>) {
        *slot(&mut self.terms) = Some(loss.clone().into_scalar::<f32>());
        let weighted = loss * weight;
        self.total = Some(match self.total.take() {
            Some(t) => t + weighted,
            None => weighted,
        });
    }
}

/// `predicted` with the pairs `true_flow` marks replaced by `truth` (both `[B, N, 3]`);
/// `predicted` itself when none is marked.
fn mix_true_flow(predicted: Tensor<3>, truth: Tensor<3>, true_flow: &[bool]) -> Tensor<3> {
    let [b, _, _] = predicted.dims();
    let marks: Vec<f32> = (0..b)
        .map(|i| if true_flow.get(i).copied().unwrap_or(false) { 1.0 } else { 0.0 })
        .collect();
    if marks.iter().all(|&m| m == 0.0) {
        return predicted;
    }
    let device = predicted.device();
    let mask = Tensor::<3>::from_data(TensorData::new(marks, [b, 1, 1]), &device);
    let keep = mask.clone().neg() + 1.0;
    predicted * keep + truth * mask
}

/// The stage's total loss (for `backward`) and its terms under `objective`; in stage 3 the
/// pairs `true_flow` marks (by batch index; missing entries are `false`) feed the
/// segmentation module the ground-truth flow instead of the predicted one.
pub fn stage_loss(
    net: &PartInductionNet,
    batch: &TrainingBatch,
    stage: u8,
    objective: &Objective,
    true_flow: &[bool],
) -> Result<(Tensor<1>, LossTerms), SamplingError> {
    let end_to_end = objective.end_to_end;
    let truth = &batch.truth;
    let mut sum = Sum { total: None, terms: LossTerms::default() };
    let rpen_only = stage == 3 && objective.rpen_only;
    let flow = if stage == 2 {
        truth.flow.clone()
    } else if rpen_only {
        // The release's stage 3: every module before the RPEN runs as a constant.
        let predicted = net.flow(&batch.input)?.flow.detach();
        let predicted = net.flow_at_subset(&batch.input, predicted)?;
        mix_true_flow(predicted, truth.flow.clone(), true_flow)
    } else {
        let out = net.flow(&batch.input)?;
        let c = out.correspondence;
        let corr = correspondence_loss(
            c.logits,
            truth.targets.clone(),
            truth.matched.clone(),
            c.mask_logits,
            truth.visible.clone(),
        );
        sum.add(corr, 1.0, |t| &mut t.correspondence);
        let flow_term = match &truth.flow_cloud {
            // The release's loss: every point of P (its true flow is defined whether or not
            // Q sees it).
            Some(cloud) if net.flow_on_cloud() => {
                let [b, n, _] = cloud.dims();
                let every = Tensor::<2>::ones([b, n], &cloud.device());
                flow_loss(out.flow.clone(), cloud.clone(), every)
            }
            _ => flow_loss(out.flow.clone(), truth.flow.clone(), truth.visible.clone()),
        };
        sum.add(flow_term, 1.0, |t| &mut t.flow);
        if stage == 1 {
            return Ok((sum.total.expect("two terms"), sum.terms));
        }
        let predicted = if end_to_end { out.flow } else { out.flow.detach() };
        let predicted = net.flow_at_subset(&batch.input, predicted)?;
        mix_true_flow(predicted, truth.flow.clone(), true_flow)
    };
    let steps =
        if stage == 3 { truth.parts_per_pair.iter().copied().max().unwrap_or(1) + 2 } else { 0 };
    let detached =
        Detached { hypotheses: objective.detach_hypotheses || rpen_only, support: rpen_only };
    let seg = net.segment_with(batch.p(), flow, steps, detached)?;
    if rpen_only {
        let segments = seg.segments.expect("stage 3 asks for RPEN steps");
        sum.add(segment_loss(segments.segments, truth.parts.clone()), 1.0, |t| &mut t.segment);
        sum.add(continuation_loss(segments.continuation, &truth.parts_per_pair), 1.0, |t| {
            &mut t.continuation
        });
        return Ok((sum.total.expect("two terms"), sum.terms));
    }
    let [b, _, _] = batch.input.p.dims();
    let s = net.seg_points();
    let p_s = batch.p().slice([0..b, 0..s]);
    let q_s = p_s.clone() + truth.flow.clone().slice([0..b, 0..s]);
    let visible_s = truth.visible.clone().slice([0..b, 0..s]);
    let motion = motion_loss(
        seg.hypotheses.rotations,
        seg.hypotheses.translations,
        p_s,
        q_s,
        truth.parts.clone(),
        visible_s,
        objective.motion_per_row,
    );
    sum.add(motion, 1.0, |t| &mut t.motion);
    sum.add(support_loss(seg.support_logits, truth.parts.clone()), objective.support_weight, |t| {
        &mut t.support
    });
    if let Some(segments) = seg.segments {
        sum.add(segment_loss(segments.segments, truth.parts.clone()), 1.0, |t| &mut t.segment);
        sum.add(continuation_loss(segments.continuation, &truth.parts_per_pair), 1.0, |t| {
            &mut t.continuation
        });
    }
    Ok((sum.total.expect("at least two terms"), sum.terms))
}
