//! One forward pass on a pair, turned into a [`Prediction`]: flow and correspondence mask
//! interpolated from the correspondence subset to every point of P, RPEN segments until the
//! continuation score drops below one half, hard labels by argmax, one rigid motion per
//! segment fitted to the flow (`pairs::segments`), and Q labelled by its nearest moved point of P.
//! The iterative refinement of the paper is not part of this pass. The segmentation half
//! also runs alone on any given flow ([`PartNet::segment_flow`], the [`Segmenter`] side of
//! [`NetworkMethod`]).

use burn::prelude::*;
use burn::tensor::activation;
use pairs::math::{Matrix3, Vector3};
use pairs::segments::{compact_labels, fit_segment_motions, transfer_labels};
use pairs::{Method, MethodError, PairInput, Prediction, Segmenter};

use crate::batch::{points_tensor, Prepared};
use crate::network::PartNet;
use crate::sampling::{three_nn, SamplingError};

fn floats<const D: usize>(t: Tensor<D>) -> Vec<f32> {
    t.into_data().convert::<f32>().try_to_vec().expect("float data converts to f32")
}

/// Values of `sources` (rows of `width`) interpolated onto `targets` by 3-NN weights.
fn interpolate(
    targets: &[[f32; 3]],
    sources: &[[f32; 3]],
    values: &[f32],
    width: usize,
) -> Result<Vec<f32>, SamplingError> {
    let (idx, w) = three_nn(targets, sources)?;
    let mut out = vec![0.0; targets.len() * width];
    for (t, row) in out.chunks_mut(width).enumerate() {
        for k in 0..3 {
            let (i, weight) = (idx[t * 3 + k], w[t * 3 + k]);
            for (o, v) in row.iter_mut().zip(&values[i * width..(i + 1) * width]) {
                *o += weight * v;
            }
        }
    }
    Ok(out)
}

impl PartNet {
    /// The network's prediction for one pair (see the module docs).
    pub fn predict(&self, input: &PairInput) -> Result<Prediction, SamplingError> {
        let device = self.devices().into_iter().next().unwrap_or_else(Device::flex);
        let prep = Prepared::new(input, self.corr_points(), &Matrix3::identity())?;
        let (p_m, q_m) = (prep.p_points(), prep.q_points());
        let p = points_tensor(std::slice::from_ref(&p_m), &device);
        let q = points_tensor(&[q_m], &device);
        let out = self.flow(p, q)?;
        let mask = floats(activation::sigmoid(out.correspondence.mask_logits));
        let subset_flow = floats(out.flow);
        let flow = interpolate(&prep.p, &p_m, &subset_flow, 3)?;
        let flow: Vec<Vector3> = flow.chunks(3).map(|f| Vector3::new(f[0], f[1], f[2])).collect();
        let mut prediction = self.segment_prepared(input, &prep, &subset_flow, &flow)?;
        prediction.flow = Some(flow);
        prediction.corr_mask = Some(interpolate(&prep.p, &p_m, &mask, 1)?);
        Ok(prediction)
    }

    /// The segmentation module alone on a given flow of P (one vector per point, Q's
    /// normalised units): the network as one more segmenter over any flow source. The
    /// prediction reports no flow of its own.
    pub fn segment_flow(
        &self,
        input: &PairInput,
        flow: &[Vector3],
    ) -> Result<Prediction, SamplingError> {
        let prep = Prepared::new(input, self.corr_points(), &Matrix3::identity())?;
        let subset_flow: Vec<f32> = prep
            .p_subset
            .iter()
            .flat_map(|&i| flow.get(i).map_or([0.0; 3], |f| [f.x, f.y, f.z]))
            .collect();
        self.segment_prepared(input, &prep, &subset_flow, flow)
    }

    /// RPEN segments of the subset (flow `subset_flow`, row-major `[m, 3]`) until the
    /// continuation score drops below one half, spread to every point, with motions fitted
    /// to `flow` and Q labelled through them.
    fn segment_prepared(
        &self,
        input: &PairInput,
        prep: &Prepared,
        subset_flow: &[f32],
        flow: &[Vector3],
    ) -> Result<Prediction, SamplingError> {
        let device = self.devices().into_iter().next().unwrap_or_else(Device::flex);
        let p_m = prep.p_points();
        let p = points_tensor(std::slice::from_ref(&p_m), &device);
        let m = p_m.len();
        let f = Tensor::<1>::from_floats(subset_flow, &device).reshape([1, m, 3]); // [1, m, 3]
        let seg = self.segment(p, f, self.max_segments())?;
        let segments = seg.segments.expect("max_segments is at least 1");
        let steps = self.max_segments();
        let go_on = floats(segments.continuation);
        let kept = go_on.iter().position(|&r| r < 0.0).map_or(steps, |t| t + 1);
        let s = self.seg_points();
        let y = floats(segments.segments.swap_dims(1, 2)); // [s, steps] row-major
        let probs = interpolate(&prep.p, &p_m[..s], &y, steps)?;
        let raw: Vec<usize> = probs
            .chunks(steps)
            .map(|row| {
                (0..kept).max_by(|&a, &b| row[a].total_cmp(&row[b]).then(b.cmp(&a))).unwrap_or(0)
            })
            .collect();
        let segments_p = compact_labels(&raw);
        let mut order: Vec<usize> = Vec::new();
        for &r in &raw {
            if !order.contains(&r) {
                order.push(r);
            }
        }
        let motions = fit_segment_motions(&input.p.points, flow, &segments_p);
        let segments_q = transfer_labels(&input.p.points, &segments_p, &motions, &input.q.points);
        let segment_probs =
            probs.chunks(steps).map(|row| order.iter().map(|&o| row[o]).collect()).collect();
        Ok(Prediction {
            flow: None,
            segments_p,
            segments_q,
            motions,
            corr_mask: None,
            segment_probs: Some(segment_probs),
        })
    }
}

/// The network for the evaluator: as a [`Method`], one forward pass per pair; as a
/// [`Segmenter`], its segmentation module alone on a given flow (`net-seg@gt-flow`: the
/// module on the true flow, the oracle row beside the classical segmenters').
#[derive(Debug)]
pub struct NetworkMethod {
    name: String,
    net: std::sync::Mutex<PartNet>,
}

impl NetworkMethod {
    /// Wraps a network (on any device) under a leaderboard name.
    pub fn new(name: impl Into<String>, net: PartNet) -> Self {
        Self { name: name.into(), net: std::sync::Mutex::new(net) }
    }
}

impl Method for NetworkMethod {
    fn name(&self) -> &str {
        &self.name
    }

    fn predict(&self, input: &PairInput) -> Result<Prediction, MethodError> {
        let net = self.net.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        net.predict(input).map_err(|e| MethodError::new(&self.name, &input.id, e))
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
        let net = self.net.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        net.segment_flow(input, flow).map_err(|e| MethodError::new(&self.name, &input.id, e))
    }
}
