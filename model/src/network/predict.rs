//! One forward pass on a pair: the flow and correspondence mask interpolated from the
//! correspondence subset to every point of P ([`PartInductionNet::flow_pass`]), and the segmentation
//! module's soft segment probabilities on every point ([`PartInductionNet::soft_segments`]: RPEN
//! steps until the continuation score drops below one half). [`PartInductionNet::predict`] turns them
//! into the raw network's [`Prediction`] (argmax labels), as the trainer validates it; the
//! whole inference procedure (graph cut, iterations, rotation search) is
//! [`PartInductionNet::infer`] in [`crate::inference`].

use burn::prelude::*;
use burn::tensor::activation;
use pairs::math::{Matrix3, Vector3};
use pairs::segments::complete_prediction;
use pairs::{PairInput, Prediction};

use crate::network::input::{points_tensor, PairTensors, Prepared};
use crate::network::sampling::{distance2, three_nn, SamplingError};
use crate::network::PartInductionNet;

/// A tensor's values as f32.
pub(crate) fn floats<const D: usize>(t: Tensor<D>) -> Vec<f32> {
    t.into_data().convert::<f32>().try_to_vec().expect("float data converts to f32")
}

/// Values of `sources` (rows of `width`) interpolated onto `targets` by 3-NN weights.
pub(crate) fn interpolate(
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

/// A hypothesis as a map `x -> A x + t` (`A` is a rotation only when the network projects
/// its hypotheses; see `hypothesis_projection`).
pub type LinearMotion = (Matrix3, Vector3);

/// What the segmentation module reads of a pair: P's subsets, their points and the
/// `[1, m, 3]` tensors of the points and of the flow on them.
struct SegmentationInput {
    prep: Prepared,
    p_m: Vec<[f32; 3]>,
    p: Tensor<3>,
    flow: Tensor<3>,
}

impl PartInductionNet {
    /// The device the network's parameters live on.
    pub(crate) fn device(&self) -> Device {
        self.devices().into_iter().next().unwrap_or_else(Device::flex)
    }

    /// The flow on every point of P (Q's normalised units) and the correspondence mask,
    /// from one pass of the correspondence and flow modules.
    pub fn flow_pass(&self, input: &PairInput) -> Result<(Vec<Vector3>, Vec<f32>), SamplingError> {
        let device = self.device();
        let prep = Prepared::new(input, self.corr_points(), &Matrix3::identity())?;
        let p_m = prep.p_points();
        let tensors = PairTensors::new(std::slice::from_ref(&prep), self.reads_clouds(), &device);
        let out = self.flow(&tensors)?;
        let mask = floats(activation::sigmoid(out.correspondence.mask_logits));
        let flow = if self.flow_on_cloud() {
            floats(out.flow)
        } else {
            interpolate(&prep.p, &p_m, &floats(out.flow), 3)?
        };
        let flow = flow.chunks(3).map(|f| Vector3::new(f[0], f[1], f[2])).collect();
        Ok((flow, interpolate(&prep.p, &p_m, &mask, 1)?))
    }

    /// The flow module's flow on every point of P fed the matching that sends each subset
    /// point of P to its nearest point of Q's subset after the true flow `truth` (one-hot
    /// rows, times the true correspondence mask `visible`) instead of the correspondence
    /// module's: whether the flow module can read offsets at all (diagnosis).
    pub fn flow_given_true_matching(
        &self,
        input: &PairInput,
        truth: &[Vector3],
        visible: &[bool],
    ) -> Result<Vec<Vector3>, SamplingError> {
        let device = self.device();
        let prep = Prepared::new(input, self.corr_points(), &Matrix3::identity())?;
        let (p_m, q_m) = (prep.p_points(), prep.q_points());
        let m = p_m.len();
        let mut matching = vec![0.0f32; m * m];
        for (row, &i) in prep.p_subset.iter().enumerate() {
            if !visible.get(i).copied().unwrap_or(false) {
                continue;
            }
            let f = truth.get(i).copied().unwrap_or_else(Vector3::zeros);
            let moved = [prep.p[i][0] + f.x, prep.p[i][1] + f.y, prep.p[i][2] + f.z];
            let j = (0..m)
                .min_by(|&a, &b| distance2(&q_m[a], &moved).total_cmp(&distance2(&q_m[b], &moved)))
                .unwrap_or(0);
            matching[row * m + j] = 1.0;
        }
        let tensors = PairTensors::new(std::slice::from_ref(&prep), self.reads_clouds(), &device);
        let matching = Tensor::<1>::from_floats(matching.as_slice(), &device).reshape([1, m, m]);
        let flow = floats(self.flow_given_matching(&tensors, matching)?);
        let flow = if self.flow_on_cloud() { flow } else { interpolate(&prep.p, &p_m, &flow, 3)? };
        Ok(flow.chunks(3).map(|f| Vector3::new(f[0], f[1], f[2])).collect())
    }

    /// The flows the correspondence module's matching alone implies, on every point of P:
    /// the soft-argmax (each subset point of P moved to its probability-weighted mean point
    /// of Q's subset) and the argmax (to its most likely point), interpolated from the
    /// subset like the flow module's. Floors for diagnosis: what the flow module adds.
    pub fn matching_flows(
        &self,
        input: &PairInput,
    ) -> Result<(Vec<Vector3>, Vec<Vector3>), SamplingError> {
        let device = self.device();
        let prep = Prepared::new(input, self.corr_points(), &Matrix3::identity())?;
        let (p_m, q_m) = (prep.p_points(), prep.q_points());
        let m = p_m.len();
        let tensors = PairTensors::new(std::slice::from_ref(&prep), self.reads_clouds(), &device);
        let c = self.correspondences(&tensors)?;
        let (p, q) = (tensors.p, tensors.q);
        let probs = activation::softmax(c.logits, 2); // [1, m, m]
        let soft = floats(probs.clone().matmul(q) - p);
        let probs = floats(probs);
        let hard: Vec<f32> = probs
            .chunks_exact(m)
            .zip(&p_m)
            .flat_map(|(row, x)| {
                let j = (0..m).max_by(|&a, &b| row[a].total_cmp(&row[b])).unwrap_or(0);
                [q_m[j][0] - x[0], q_m[j][1] - x[1], q_m[j][2] - x[2]]
            })
            .collect();
        let vectors = |v: Vec<f32>| v.chunks(3).map(|f| Vector3::new(f[0], f[1], f[2])).collect();
        Ok((
            vectors(interpolate(&prep.p, &p_m, &soft, 3)?),
            vectors(interpolate(&prep.p, &p_m, &hard, 3)?),
        ))
    }

    /// P's correspondence subset and the given flow of P on it, as the segmentation module
    /// reads them.
    fn segmentation_input(
        &self,
        input: &PairInput,
        flow: &[Vector3],
    ) -> Result<SegmentationInput, SamplingError> {
        let device = self.device();
        let prep = Prepared::new(input, self.corr_points(), &Matrix3::identity())?;
        let p_m = prep.p_points();
        let subset_flow: Vec<f32> = prep
            .p_subset
            .iter()
            .flat_map(|&i| flow.get(i).map_or([0.0; 3], |f| [f.x, f.y, f.z]))
            .collect();
        let p = points_tensor(std::slice::from_ref(&p_m), &device);
        let m = p_m.len();
        let f = Tensor::<1>::from_floats(subset_flow.as_slice(), &device).reshape([1, m, 3]); // [1, m, 3]
        Ok(SegmentationInput { prep, p_m, p, flow: f })
    }

    /// The support module's probabilities given a flow on P, on the segmentation subset of
    /// `s` points: the subset's indices into P and an `s × s` row-major matrix whose row `i`
    /// is the hypothesis seeded at subset point `i` and column `j` subset point `j` (what
    /// stage 2 trains towards "`j` is in the part of `i`"). No RPEN step runs.
    pub fn supports(
        &self,
        input: &PairInput,
        flow: &[Vector3],
    ) -> Result<(Vec<usize>, Vec<f32>), SamplingError> {
        let SegmentationInput { prep, p, flow: f, .. } = self.segmentation_input(input, flow)?;
        let seg = self.segment(p, f, 0)?;
        let mut subset = prep.p_subset;
        subset.truncate(self.seg_points());
        Ok((subset, floats(activation::sigmoid(seg.support_logits))))
    }

    /// The hypothesis generator's rigid motions given a flow on P, one per point of the
    /// segmentation subset: the subset's indices into P, and each hypothesis as the matrix
    /// `R_i` and translation `t_i` that map a point `x` of P to `R_i x + t_i` (where the
    /// flow should take it).
    pub fn hypotheses(
        &self,
        input: &PairInput,
        flow: &[Vector3],
    ) -> Result<(Vec<usize>, Vec<LinearMotion>), SamplingError> {
        let SegmentationInput { prep, p, flow: f, .. } = self.segmentation_input(input, flow)?;
        let seg = self.segment(p, f, 0)?;
        let r = floats(seg.hypotheses.rotations); // [1, s, 3, 3]
        let t = floats(seg.hypotheses.translations); // [1, s, 3]
        let motions = r
            .chunks_exact(9)
            .zip(t.chunks_exact(3))
            .map(|(r, t)| (Matrix3::from_row_slice(r), Vector3::new(t[0], t[1], t[2])))
            .collect();
        let mut subset = prep.p_subset;
        subset.truncate(self.seg_points());
        Ok((subset, motions))
    }

    /// The segmentation module's soft probabilities on every point of P given a flow on P
    /// (one row per point, one column per RPEN step kept by the continuation score).
    pub fn soft_segments(
        &self,
        input: &PairInput,
        flow: &[Vector3],
    ) -> Result<Vec<Vec<f32>>, SamplingError> {
        self.soft_segments_given(input, flow, None)
    }

    /// [`Self::soft_segments`] with the RPEN fed `support` (an `s × s` row-major matrix of
    /// probabilities on the segmentation subset, as [`Self::supports`] orders it) instead
    /// of the support module's: an oracle substitute for diagnosis.
    pub fn soft_segments_given(
        &self,
        input: &PairInput,
        flow: &[Vector3],
        support: Option<&[f32]>,
    ) -> Result<Vec<Vec<f32>>, SamplingError> {
        let SegmentationInput { prep, p_m, p, flow: f } = self.segmentation_input(input, flow)?;
        let steps = self.max_segments();
        let s = self.seg_points();
        let segments = match support {
            None => self.segment(p, f, steps)?.segments.expect("max_segments is at least 1"),
            Some(values) => {
                let device = self.device();
                let support = Tensor::<1>::from_floats(values, &device).reshape([1, s, s]); // [1, s, s]
                self.extract_parts(p.slice([0..1, 0..s]), support, steps)
            }
        };
        let go_on = floats(segments.continuation);
        let kept = go_on.iter().position(|&r| r < 0.0).map_or(steps, |t| t + 1);
        let y = floats(segments.segments.swap_dims(1, 2)); // [s, steps] row-major
        let probs = interpolate(&prep.p, &p_m[..s], &y, steps)?;
        Ok(probs.chunks(steps).map(|row| row[..kept].to_vec()).collect())
    }

    /// The raw network's single pass, as the trainer validates it: [`Self::flow_pass`],
    /// [`Self::soft_segments`], labels by argmax, one motion per segment and Q labelled
    /// by its nearest moved point (`pairs::segments`). No calibration and no graph cut: the
    /// evaluator's `net` row is [`PartInductionNet::infer`] with
    /// [`InferenceParams::single_pass`](crate::inference::InferenceParams::single_pass).
    pub fn predict(&self, input: &PairInput) -> Result<Prediction, SamplingError> {
        let (flow, mask) = self.flow_pass(input)?;
        let mut prediction = self.segment_flow(input, &flow)?;
        prediction.flow = Some(flow);
        prediction.corr_mask = Some(mask);
        Ok(prediction)
    }

    /// The segmentation module alone on a given flow of P (one vector per point, Q's
    /// normalised units), labels by argmax as in [`Self::predict`]. The prediction reports
    /// no flow of its own.
    pub fn segment_flow(
        &self,
        input: &PairInput,
        flow: &[Vector3],
    ) -> Result<Prediction, SamplingError> {
        let probs = self.soft_segments(input, flow)?;
        let raw: Vec<usize> = probs
            .iter()
            .map(|row| {
                (0..row.len())
                    .max_by(|&a, &b| row[a].total_cmp(&row[b]).then(b.cmp(&a)))
                    .unwrap_or(0)
            })
            .collect();
        let mut prediction = complete_prediction(input, flow, &raw, false);
        let mut order: Vec<usize> = Vec::new();
        for &r in &raw {
            if !order.contains(&r) {
                order.push(r);
            }
        }
        prediction.segment_probs =
            Some(probs.iter().map(|row| order.iter().map(|&o| row[o]).collect()).collect());
        Ok(prediction)
    }
}
