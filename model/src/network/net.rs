//! [`PartInductionNet`] itself: its modules, one forward per training stage (flow, matching,
//! segmentation), and what each stage's forward returns.

use burn::prelude::*;
use burn::tensor::activation;

use crate::network::config::NetworkConfig;
use crate::network::correspondence::{Correspondence, CorrespondenceModule};
use crate::network::flow::FlowModule;
use crate::network::input::PairTensors;
use crate::network::sampling::SamplingError;
use crate::network::segmentation::hypotheses::{Hypotheses, HypothesisModule};
use crate::network::segmentation::rpen::{RpenModule, Segments};
use crate::network::segmentation::support::SupportModule;
use crate::network::{input, rng};

/// The network of Yi et al. 2018, "Deep Part Induction from Articulated Object Pairs".
#[derive(Module, Debug)]
pub struct PartInductionNet {
    correspondence: CorrespondenceModule,
    flow: FlowModule,
    hypotheses: HypothesisModule,
    support: SupportModule,
    rpen: RpenModule,
    #[module(skip)]
    corr_points: usize,
    #[module(skip)]
    seg_points: usize,
    #[module(skip)]
    max_segments: usize,
}

/// The flow stage's outputs.
#[derive(Debug, Clone)]
pub struct FlowOutput {
    /// Matching logits and correspondence mask.
    pub correspondence: Correspondence,
    /// Flow on the correspondence subset of P, `[batch, m, 3]` (on every point of P,
    /// `[batch, n, 3]`, with `flow_on_cloud`).
    pub flow: Tensor<3>,
}

/// One of the network's modules, by the paper's names (a config's `init_modules`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum NetModule {
    /// Correspondence proposal (features, matching, mask).
    Correspondence,
    /// Flow module.
    Flow,
    /// Hypothesis generator.
    Hypotheses,
    /// Support (verification) network.
    Support,
    /// Recurrent part extraction network.
    Rpen,
}

/// Where [`PartInductionNet::segment_with`] stops gradients.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Detached {
    /// The support module sees the hypotheses as constants: its loss does not train the
    /// hypothesis generator (the release's stage 2).
    pub hypotheses: bool,
    /// The RPEN sees the support matrix as a constant: its losses train the RPEN alone (the
    /// release's stage 3).
    pub support: bool,
}

/// The segmentation module's outputs, on the segmentation subset (the first s points).
#[derive(Debug, Clone)]
pub struct SegmentationOutput {
    /// One rigid-motion hypothesis per point.
    pub hypotheses: Hypotheses,
    /// Support logits `[batch, s, s]`, rows hypotheses.
    pub support_logits: Tensor<3>,
    /// RPEN segments and continuation logits (absent when no steps were asked for).
    pub segments: Option<Segments>,
}

impl PartInductionNet {
    /// A freshly initialised network with `config`'s sizes (weights from burn's default
    /// initialisers, seeded by the device's RNG).
    pub(crate) fn new(config: &NetworkConfig, device: &Device) -> Self {
        Self {
            correspondence: CorrespondenceModule::new(config, device),
            flow: FlowModule::new(config, device),
            hypotheses: HypothesisModule::new(config, device),
            support: SupportModule::new(config, device),
            rpen: RpenModule::new(config, device),
            corr_points: config.corr_points,
            seg_points: config.seg_points,
            max_segments: config.max_segments,
        }
    }

    /// A network initialised from `seed`: the same seed gives the same weights, whatever
    /// other threads do ([`rng`] explains why that takes care).
    pub fn seeded(config: &NetworkConfig, device: &Device, seed: u64) -> Self {
        rng::seeded(device, seed, || rng::materialised(Self::new(config, device)))
    }

    /// This network with the modules in `which` taken from `other` (of the same sizes).
    pub fn with_modules_from(self, other: Self, which: &[NetModule]) -> Self {
        let pick = |m| which.contains(&m);
        Self {
            correspondence: if pick(NetModule::Correspondence) {
                other.correspondence
            } else {
                self.correspondence
            },
            flow: if pick(NetModule::Flow) { other.flow } else { self.flow },
            hypotheses: if pick(NetModule::Hypotheses) {
                other.hypotheses
            } else {
                self.hypotheses
            },
            support: if pick(NetModule::Support) { other.support } else { self.support },
            rpen: if pick(NetModule::Rpen) { other.rpen } else { self.rpen },
            ..self
        }
    }

    /// Correspondences on the correspondence subsets of P and Q, and the flow (on P's subset,
    /// or on every point of P with `flow_on_cloud`).
    ///
    /// # Shapes
    /// `input.p, input.q: [batch, m, 3]`
    pub fn flow(&self, input: &PairTensors) -> Result<FlowOutput, SamplingError> {
        let correspondence = self.correspondence.forward(input)?;
        let matching = correspondence.refined_with(self.flow.mask_detached());
        let flow = self.flow.forward(input, matching)?;
        Ok(FlowOutput { correspondence, flow })
    }

    /// The flow module fed `matching` (`[batch, m, m]`, as [`Correspondence::refined`]
    /// gives it) instead of the correspondence module's: an oracle substitute for diagnosis.
    pub fn flow_given_matching(
        &self,
        input: &PairTensors,
        matching: Tensor<3>,
    ) -> Result<Tensor<3>, SamplingError> {
        self.flow.forward(input, matching)
    }

    /// The correspondence module alone: matching logits and mask on the subsets.
    ///
    /// # Shapes
    /// `input.p, input.q: [batch, m, 3]`
    pub fn correspondences(&self, input: &PairTensors) -> Result<Correspondence, SamplingError> {
        self.correspondence.forward(input)
    }

    /// Whether the network reads whole clouds (`features_on_cloud` or `flow_on_cloud`):
    /// its inputs must then carry them ([`PairTensors::new`]).
    pub fn reads_clouds(&self) -> bool {
        self.correspondence.on_cloud() || self.flow.on_cloud()
    }

    /// The flow module's output on P's correspondence subset: itself, or (with
    /// `flow_on_cloud`) gathered there from every point of P.
    ///
    /// # Shapes
    /// `flow: [batch, m, 3]` or `[batch, n, 3]` -> `[batch, m, 3]`
    pub fn flow_at_subset(
        &self,
        input: &PairTensors,
        flow: Tensor<3>,
    ) -> Result<Tensor<3>, SamplingError> {
        if !self.flow.on_cloud() {
            return Ok(flow);
        }
        let clouds = input.clouds.as_ref().ok_or(SamplingError::NoClouds)?;
        Ok(input::gather_points(flow, clouds.p_subset.clone()))
    }

    /// Whether the flow comes out on every point of P (`flow_on_cloud`).
    pub fn flow_on_cloud(&self) -> bool {
        self.flow.on_cloud()
    }

    /// Hypotheses and support on the first s points of P given a flow, and `steps` RPEN
    /// steps (none for stage 2).
    ///
    /// # Shapes
    /// `p, flow: [batch, m, 3]`
    pub fn segment(
        &self,
        p: Tensor<3>,
        flow: Tensor<3>,
        steps: usize,
    ) -> Result<SegmentationOutput, SamplingError> {
        self.segment_with(p, flow, steps, Detached::default())
    }

    /// [`PartInductionNet::segment`] with the gradient stopped where `detached` says (the
    /// release's `tf.stop_gradient` in stages 2 and 3).
    ///
    /// # Shapes
    /// `p, flow: [batch, m, 3]`
    pub fn segment_with(
        &self,
        p: Tensor<3>,
        flow: Tensor<3>,
        steps: usize,
        detached: Detached,
    ) -> Result<SegmentationOutput, SamplingError> {
        let [batch, _, _] = p.dims();
        let s = self.seg_points;
        let hypotheses = self.hypotheses.forward(p.clone(), flow.clone(), s)?;
        let (p_s, f_s) = (p.slice([0..batch, 0..s]), flow.slice([0..batch, 0..s]));
        let support_logits = if detached.hypotheses {
            let stopped = Hypotheses {
                rotations: hypotheses.rotations.clone().detach(),
                translations: hypotheses.translations.clone().detach(),
            };
            self.support.forward(p_s.clone(), f_s, &stopped)
        } else {
            self.support.forward(p_s.clone(), f_s, &hypotheses)
        };
        let segments = (steps > 0).then(|| {
            let support = activation::sigmoid(support_logits.clone());
            let support = if detached.support { support.detach() } else { support };
            self.extract_parts(p_s, support, steps)
        });
        Ok(SegmentationOutput { hypotheses, support_logits, segments })
    }

    /// `steps` RPEN steps on the segmentation subset's points (centred) and support
    /// probabilities.
    ///
    /// # Shapes
    /// `p_s: [batch, s, 3]`, `support: [batch, s, s]`
    pub(crate) fn extract_parts(
        &self,
        p_s: Tensor<3>,
        support: Tensor<3>,
        steps: usize,
    ) -> Segments {
        let centred = p_s.clone() - p_s.mean_dim(1);
        self.rpen.forward(centred, support, steps)
    }

    /// Points of the correspondence subsets.
    pub fn corr_points(&self) -> usize {
        self.corr_points
    }

    /// Points of the segmentation subset.
    pub fn seg_points(&self) -> usize {
        self.seg_points
    }

    /// Most RPEN steps at inference.
    pub fn max_segments(&self) -> usize {
        self.max_segments
    }
}
