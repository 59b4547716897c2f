//! The network as the evaluator's [`Method`] (single pass `net`, iterative `net-iter`) and
//! [`Segmenter`] (its segmentation module on a given flow).

use std::sync::{Mutex, MutexGuard, PoisonError};

use pairs::math::Vector3;
use pairs::{Method, MethodError, PairInput, Prediction, Segmenter};

use crate::inference::{Inference, InferenceParams};
use crate::network::PartInductionNet;

/// The network for the evaluator: as a [`Method`], the inference procedure with its
/// parameters (one pass for `net`, the iterative refinement for `net-iter`); as a
/// [`Segmenter`], its segmentation module alone on a given flow (`net-seg@gt-flow`: the
/// module on the true flow, the oracle row beside the classical segmenters'). It holds one
/// copy of the network per rayon worker thread (a burn module is not `Sync`), so pairs run
/// in parallel; the copies are identical, so results do not depend on which thread ran a pair.
#[derive(Debug)]
pub struct NetworkMethod {
    name: String,
    params: InferenceParams,
    nets: Vec<Mutex<PartInductionNet>>,
}

impl NetworkMethod {
    /// Wraps a network (on any device) under a leaderboard name, as a single pass.
    pub fn new(name: impl Into<String>, net: PartInductionNet) -> Self {
        Self::with_params(name, net, InferenceParams::single_pass())
    }

    /// Wraps a network with the given inference parameters.
    pub fn with_params(
        name: impl Into<String>,
        net: PartInductionNet,
        params: InferenceParams,
    ) -> Self {
        let copies = rayon::current_num_threads().max(1);
        let nets = (0..copies).map(|_| Mutex::new(net.clone())).collect();
        Self { name: name.into(), params, nets }
    }

    /// The copy of the network for the calling thread (rayon worker `i` gets copy `i`, any
    /// other thread copy 0).
    fn net(&self) -> MutexGuard<'_, PartInductionNet> {
        let i = rayon::current_thread_index().unwrap_or(0) % self.nets.len();
        self.nets[i].lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// The inference parameters.
    pub fn params(&self) -> &InferenceParams {
        &self.params
    }

    /// The whole record of the procedure on a pair: every pass's prediction, so that a
    /// caller can score each iteration (the paper's Table 4).
    pub fn infer(&self, input: &PairInput) -> Result<Inference, MethodError> {
        self.net()
            .infer(input, &self.params)
            .map_err(|e| MethodError::new(&self.name, &input.id, e))
    }
}

impl Method for NetworkMethod {
    fn name(&self) -> &str {
        &self.name
    }

    fn predict(&self, input: &PairInput) -> Result<Prediction, MethodError> {
        Ok(self.infer(input)?.prediction())
    }

    /// More than one pass allowed (`net-iter`).
    fn iterative(&self) -> bool {
        self.params.max_iterations > 1
    }

    fn predict_passes(&self, input: &PairInput) -> Result<Vec<Prediction>, MethodError> {
        let passes: Vec<Prediction> =
            self.infer(input)?.iterations.into_iter().map(|it| it.prediction).collect();
        if passes.is_empty() {
            return Err(MethodError::new(&self.name, &input.id, "the procedure made no pass"));
        }
        Ok(passes)
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
        self.net()
            .segment_flow_with(input, flow, &self.params.labels)
            .map_err(|e| MethodError::new(&self.name, &input.id, e))
    }
}
