//! The wrapping every baseline shares between its algorithm and the `pairs` traits: input
//! checks, per-pair seeds, completion of P's labels into a full [`Prediction`] and the
//! final NaN check, with errors wrapped in [`MethodError`].

use pairs::math::Vector3;
use pairs::segments::complete_prediction;
use pairs::{MethodError, PairInput, Prediction};

use crate::geometry::{check_flow, check_pair, check_prediction, seed_for_pair, InputError};

/// Runs a segmentation algorithm `segment(input, flow, seed) -> labels of P` as a
/// segmenter: checks the flow, seeds per pair, completes the prediction (motions fitted
/// on `flow`, Q labelled by transfer; the flow is not reported as the segmenter's own).
pub fn run_segmenter<E>(
    name: &str,
    input: &PairInput,
    flow: &[Vector3],
    seed: u64,
    segment: impl FnOnce(&PairInput, &[Vector3], u64) -> Result<Vec<u32>, E>,
) -> Result<Prediction, MethodError>
where
    E: std::error::Error + Send + Sync + 'static + From<InputError>,
{
    let wrap = |e: E| MethodError::new(name, &input.id, e);
    check_flow(input, flow).map_err(|e| wrap(e.into()))?;
    let labels = segment(input, flow, seed_for_pair(seed, &input.id)).map_err(wrap)?;
    check_prediction(complete_prediction(input, flow, &labels, false)).map_err(|e| wrap(e.into()))
}

/// Runs a method `predict(input, seed) -> (flow on P, labels of P)` that estimates its own
/// flow: checks the pair, seeds per pair, completes the prediction with the flow reported.
pub fn run_method<E>(
    name: &str,
    input: &PairInput,
    seed: u64,
    predict: impl FnOnce(&PairInput, u64) -> Result<(Vec<Vector3>, Vec<u32>), E>,
) -> Result<Prediction, MethodError>
where
    E: std::error::Error + Send + Sync + 'static + From<InputError>,
{
    let wrap = |e: E| MethodError::new(name, &input.id, e);
    check_pair(input).map_err(|e| wrap(e.into()))?;
    let (flow, labels) = predict(input, seed_for_pair(seed, &input.id)).map_err(wrap)?;
    check_flow(input, &flow).map_err(|e| wrap(e.into()))?;
    check_prediction(complete_prediction(input, &flow, &labels, true)).map_err(|e| wrap(e.into()))
}
