//! The network as the evaluator's [`Method`] (single pass `net`, iterative `net-iter`) and
//! [`Segmenter`] (its segmentation module on a given flow).

use std::sync::{Mutex, PoisonError};

use pairs::math::Vector3;
use pairs::{Method, MethodError, PairInput, Prediction, Segmenter};

use crate::inference::{Inference, InferenceParams};
use crate::network::PartNet;

/// The network for the evaluator: as a [`Method`], the inference procedure with its
/// parameters (one pass for `net`, the iterative refinement for `net-iter`); as a
/// [`Segmenter`], its segmentation module alone on a given flow (`net-seg@gt-flow`: the
/// module on the true flow, the oracle row beside the classical segmenters').
#[derive(Debug)]
pub struct NetworkMethod {
    name: String,
    params: InferenceParams,
    net: Mutex<PartNet>,
}

impl NetworkMethod {
    /// Wraps a network (on any device) under a leaderboard name, as a single pass.
    pub fn new(name: impl Into<String>, net: PartNet) -> Self {
        Self::with_params(name, net, InferenceParams::single_pass())
    }

    /// Wraps a network with the given inference parameters.
    pub fn with_params(name: impl Into<String>, net: PartNet, params: InferenceParams) -> Self {
        Self { name: name.into(), params, net: Mutex::new(net) }
    }

    /// The inference parameters.
    pub fn params(&self) -> &InferenceParams {
        &self.params
    }

    /// The whole record of the procedure on a pair: every pass's prediction, so that a
    /// caller can score each iteration (the paper's Table 3).
    pub fn infer(&self, input: &PairInput) -> Result<Inference, MethodError> {
        let net = self.net.lock().unwrap_or_else(PoisonError::into_inner);
        net.infer(input, &self.params).map_err(|e| MethodError::new(&self.name, &input.id, e))
    }
}

impl Method for NetworkMethod {
    fn name(&self) -> &str {
        &self.name
    }

    fn predict(&self, input: &PairInput) -> Result<Prediction, MethodError> {
        Ok(self.infer(input)?.prediction())
    }
}

impl Segmenter for NetworkMethod {
    fn name(&self) -> &str {
        &self.name
    }

    fn segment(&self, input: &PairInput, flow: &[Vector3]) -> Result<Prediction, MethodError> {
        if flow.len() != input.p.len() {
            let msg = format!("flow has {} vectors for {} points", flow.len(), input.p.len());
            return Err(MethodError::new(&self.name, &input.id, msg));
        }
        let net = self.net.lock().unwrap_or_else(PoisonError::into_inner);
        net.segment_flow_with(input, flow, &self.params.labels)
            .map_err(|e| MethodError::new(&self.name, &input.id, e))
    }
}
