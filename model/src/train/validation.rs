//! The fixed validation set (pairs of the validation categories) and the scores the trainer
//! reports on it: EPE, Rand index and matched IoU (`pairs::metrics`), from the same
//! single-pass prediction the evaluator scores; and the support IoU, the segmentation
//! module's hypotheses and supports on the true flow, which is what stage 2 trains (the
//! single pass takes its labels from RPEN steps that only stage 3 trains, so it cannot
//! tell one stage-2 network from another).

use generator::categories::Split;
use generator::config::GeneratorConfig;
use generator::generate::{object_pairs_with, GenerateError, Variant};
use pairs::metrics::{epe, matched_iou, rand_index};
use pairs::PairKind;
use pairs::{Pair, PartId};

use crate::network::sampling::SamplingError;
use crate::network::PartInductionNet;

/// Seed of the validation pairs; fixed so that every run is scored on the same pairs.
pub const VALIDATION_SEED: u64 = 20_181_201;

/// The fixed validation set: `count` pairs of the validation categories at `points` points
/// per cloud. With `scanned`, for runs whose training stream mixes in scans, a quarter of
/// them are SF2P and a quarter SP2P pairs (of objects of their own), the rest full shapes.
pub fn validation_pairs(
    points: u32,
    count: u32,
    scanned: bool,
) -> Result<Vec<Pair>, GenerateError> {
    let (full, sf2p, sp2p) =
        if scanned { (count - 2 * (count / 4), count / 4, count / 4) } else { (count, 0, 0) };
    let mut pairs = pairs_of_kind(PairKind::Sf2f, points, full)?;
    pairs.extend(pairs_of_kind(PairKind::Sf2p, points, sf2p)?);
    pairs.extend(pairs_of_kind(PairKind::Sp2p, points, sp2p)?);
    Ok(pairs)
}

/// The first `count` validation pairs of one kind, object after object (no images).
fn pairs_of_kind(kind: PairKind, points: u32, count: u32) -> Result<Vec<Pair>, GenerateError> {
    let config = GeneratorConfig {
        split: Split::Validation,
        points,
        seed: VALIDATION_SEED,
        ..GeneratorConfig::of_kind(kind)
    };
    let variant = Variant { index: 0, kind, images: false };
    let mut pairs = Vec::with_capacity(count as usize);
    let mut object = 0;
    while pairs.len() < count as usize {
        match object_pairs_with(&config, object, variant) {
            Ok(made) => pairs.extend(made.into_iter().map(|g| g.pair)),
            Err(GenerateError::TooFewPairs { .. }) => {}
            Err(e) => return Err(e),
        }
        object += 1;
    }
    pairs.truncate(count as usize);
    Ok(pairs)
}

/// Mean scores over a set of pairs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scores {
    /// End-point error of the flow, averaged over pairs.
    pub epe: f64,
    /// Rand index of P's segmentation, averaged over pairs.
    pub rand_index: f64,
    /// Matched IoU averaged over every ground-truth part of every pair.
    pub iou: f64,
    /// Support IoU on the true flow, averaged over pairs ([`support_iou`]).
    pub support_iou: f64,
}

/// Why scoring failed.
#[derive(Debug, thiserror::Error)]
pub enum ScoreError {
    /// The network could not run on a pair.
    #[error("pair {pair}: {source}")]
    Predict {
        /// The pair's id.
        pair: String,
        /// What went wrong.
        #[source]
        source: SamplingError,
    },
    /// A metric rejected the prediction.
    #[error("pair {pair}: {source}")]
    Metric {
        /// The pair's id.
        pair: String,
        /// What went wrong.
        #[source]
        source: pairs::metrics::MetricError,
    },
}

/// Scores the network's single-pass predictions on `pairs`.
pub fn score(net: &PartInductionNet, pairs: &[Pair]) -> Result<Scores, ScoreError> {
    let (mut epe_sum, mut ri_sum, mut iou_sum, mut parts) = (0.0, 0.0, 0.0, 0usize);
    let mut support_sum = 0.0;
    for pair in pairs {
        let id = || pair.id().to_string();
        let prediction = net
            .predict(pair.input())
            .map_err(|source| ScoreError::Predict { pair: id(), source })?;
        let truth = pair.truth();
        let metric = |source| ScoreError::Metric { pair: id(), source };
        let flow = prediction.flow.as_deref().unwrap_or_default();
        epe_sum += epe(flow, &truth.flow).map_err(metric)?;
        ri_sum += rand_index(&prediction.segments_p, &truth.part_p).map_err(metric)?;
        let matching = matched_iou(&prediction.segments_p, &truth.part_p).map_err(metric)?;
        iou_sum += matching.iou.iter().sum::<f64>();
        parts += matching.iou.len();
        let (subset, probs) = net
            .supports(pair.input(), &truth.flow)
            .map_err(|source| ScoreError::Predict { pair: id(), source })?;
        let parts_s: Vec<PartId> = subset.iter().map(|&i| truth.part_p[i]).collect();
        support_sum += support_iou(&probs, &parts_s);
    }
    let n = pairs.len().max(1) as f64;
    Ok(Scores {
        epe: epe_sum / n,
        rand_index: ri_sum / n,
        iou: iou_sum / parts.max(1) as f64,
        support_iou: support_sum / n,
    })
}

/// How well the supports pick out parts: for every hypothesis `i` (one per point of the
/// subset), the IoU of the points it supports (probability above one half) with the points
/// of the part of `i`, averaged over hypotheses. 1 when every hypothesis supports exactly its
/// part; a module that supports everything scores the mean fraction of the subset in a
/// point's part. `probs` holds `parts.len()` squared values, row-major, as
/// [`PartInductionNet::supports`] returns them.
pub fn support_iou(probs: &[f32], parts: &[PartId]) -> f64 {
    let s = parts.len();
    if s == 0 {
        return 0.0;
    }
    let mut total = 0.0;
    for (row, &own) in probs.chunks(s).zip(parts) {
        let (mut inter, mut union) = (0usize, 0usize);
        for (&p, &part) in row.iter().zip(parts) {
            let (predicted, truth) = (p > 0.5, part == own);
            inter += usize::from(predicted && truth);
            union += usize::from(predicted || truth);
        }
        total += inter as f64 / union.max(1) as f64;
    }
    total / s as f64
}

#[cfg(test)]
mod tests {
    use super::support_iou;

    #[test]
    fn support_iou_on_hand_computed_cases() {
        // Parts [0, 0, 1]: supports that pick exactly each point's part score 1.
        let parts = [0, 0, 1];
        let perfect = [0.9, 0.8, 0.1, 0.7, 0.6, 0.2, 0.3, 0.4, 0.9];
        assert!((support_iou(&perfect, &parts) - 1.0).abs() < 1e-12);
        // Everything supported: the rows of part 0 have IoU 2/3, the row of part 1 1/3.
        let everything = (2.0 / 3.0 + 2.0 / 3.0 + 1.0 / 3.0) / 3.0;
        assert!((support_iou(&[0.9; 9], &parts) - everything).abs() < 1e-12);
        // Nothing supported: every IoU is 0.
        assert_eq!(support_iou(&[0.1; 9], &parts), 0.0);
        // Row 0 supports only point 2 (IoU 0), the others are exact.
        let mut one_wrong = perfect;
        one_wrong[..3].copy_from_slice(&[0.1, 0.1, 0.9]);
        assert!((support_iou(&one_wrong, &parts) - 2.0 / 3.0).abs() < 1e-12);
    }
}
