//! The fixed validation set (pairs of the validation categories) and the scores the trainer
//! reports on it: EPE, Rand index and matched IoU (`pairs::metrics`), from the same
//! single-pass prediction the evaluator scores; and the support IoU, the segmentation
//! module's hypotheses and supports on the true flow, which is what stage 2 trains (the
//! single pass takes its labels from RPEN steps that only stage 3 trains, so it cannot
//! tell one stage-2 network from another).

use articulated::categories::Split;
use generator::config::GeneratorConfig;
use generator::generate::{object_pairs_with, GenerateError, Variant};
use pairs::math::Vector3;
use pairs::metrics::{score_pair, MetricError};
use pairs::PairKind;
use pairs::{Pair, PairInput, PartId, Prediction};

use crate::inference::align_globally;
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
    /// The prediction could not be scored (`pairs::metrics::score_pair`).
    #[error("pair {pair}: {source}")]
    Score {
        /// The pair's id.
        pair: String,
        /// What went wrong.
        #[source]
        source: pairs::metrics::ScoreError,
    },
    /// The inference procedure failed on a pair (the error names the pair).
    #[error(transparent)]
    Procedure(#[from] pairs::MethodError),
    /// A cross-instance pair (XF2F, XF2P) has no true flow to score or train on.
    #[error("pair {pair}: a {kind} pair has no true flow (two different objects); validation, training and diagnosis need SF2F, SF2P or SP2P pairs")]
    NoFlow {
        /// The pair's id.
        pair: String,
        /// Its kind.
        kind: &'static str,
    },
}

/// The pair's true flow, or [`ScoreError::NoFlow`] for a cross-instance pair.
pub fn true_flow(pair: &Pair) -> Result<&[Vector3], ScoreError> {
    pair.truth().flow.as_deref().ok_or_else(|| ScoreError::NoFlow {
        pair: pair.id().to_owned(),
        kind: pair.input().kind.as_str(),
    })
}

/// One pair's scores, the terms that [`Scores`] averages.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PairScores {
    /// End-point error of the flow.
    pub epe: f64,
    /// Rand index of P's segmentation.
    pub rand_index: f64,
    /// Sum of the matched IoU over the pair's ground-truth parts.
    pub iou_sum: f64,
    /// The pair's ground-truth parts.
    pub parts: usize,
    /// Support IoU on the true flow ([`support_iou`]).
    pub support_iou: f64,
}

impl Scores {
    /// The mean scores of a set of pairs: EPE, Rand index and support IoU averaged over
    /// pairs, the IoU over every ground-truth part of every pair.
    pub fn of(pairs: &[PairScores]) -> Self {
        Self::of_indices(pairs, 0..pairs.len())
    }

    /// [`Scores::of`] the pairs at `indices` (repeats count once each time).
    fn of_indices(pairs: &[PairScores], indices: impl Iterator<Item = usize>) -> Self {
        let (mut n, mut parts) = (0usize, 0usize);
        let (mut epe, mut ri, mut iou, mut support) = (0.0, 0.0, 0.0, 0.0);
        for p in indices.map(|i| &pairs[i]) {
            n += 1;
            parts += p.parts;
            epe += p.epe;
            ri += p.rand_index;
            iou += p.iou_sum;
            support += p.support_iou;
        }
        let n = n.max(1) as f64;
        Self {
            epe: epe / n,
            rand_index: ri / n,
            iou: iou / parts.max(1) as f64,
            support_iou: support / n,
        }
    }
}

/// Scores the network's single-pass predictions on `pairs`.
pub fn score(net: &PartInductionNet, pairs: &[Pair]) -> Result<Scores, ScoreError> {
    Ok(Scores::of(&score_pairs(net, pairs)?))
}

/// Scores the network's single-pass predictions on every pair of `pairs`, in order.
pub fn score_pairs(net: &PartInductionNet, pairs: &[Pair]) -> Result<Vec<PairScores>, ScoreError> {
    score_pairs_aligned(net, pairs, 0)
}

/// [`score_pairs`] after `alignments` global alignments of P (the authors' release: 2):
/// each predicts the flow of P' (P to begin with) and moves P' by the one rigid motion
/// that fits it ([`align_globally`]); the pass then runs on (P', Q) and its flow is
/// `P' - P` plus the predicted one. For weights trained without relative pose, which
/// expect the global motion removed first.
pub fn score_pairs_aligned(
    net: &PartInductionNet,
    pairs: &[Pair],
    alignments: usize,
) -> Result<Vec<PairScores>, ScoreError> {
    pairs
        .iter()
        .map(|pair| {
            let id = || pair.id().to_string();
            let prediction = predict_aligned(net, pair.input(), alignments)
                .map_err(|source| ScoreError::Predict { pair: id(), source })?;
            let truth = pair.truth();
            let (subset, probs) = net
                .supports(pair.input(), true_flow(pair)?)
                .map_err(|source| ScoreError::Predict { pair: id(), source })?;
            let parts_s: Vec<PartId> = subset.iter().map(|&i| truth.part_p[i]).collect();
            PairScores::of(pair, &prediction, support_iou(&probs, &parts_s))
        })
        .collect()
}

/// The single pass on `input` after `alignments` global alignments of P, in P's frame.
fn predict_aligned(
    net: &PartInductionNet,
    input: &PairInput,
    alignments: usize,
) -> Result<Prediction, SamplingError> {
    let mut moved = input.clone();
    for _ in 0..alignments {
        let flow = net.predict(&moved)?.flow.unwrap_or_default();
        moved.p.points = align_globally(&moved.p.points, &flow);
    }
    let mut prediction = net.predict(&moved)?;
    if alignments > 0 {
        if let Some(flow) = prediction.flow.as_mut() {
            for ((f, x), start) in flow.iter_mut().zip(&moved.p.points).zip(&input.p.points) {
                *f += x - start;
            }
        }
    }
    Ok(prediction)
}

impl PairScores {
    /// The scores of `prediction` (its flow and P's labels) on `pair`, with a support IoU
    /// scored elsewhere (NaN where none is).
    pub fn of(pair: &Pair, prediction: &Prediction, support_iou: f64) -> Result<Self, ScoreError> {
        let true_flow = true_flow(pair)?;
        let id = || pair.id().to_string();
        let score = score_pair(prediction, pair.input(), pair.truth())
            .map_err(|source| ScoreError::Score { pair: id(), source })?;
        let no_flow =
            MetricError::LengthMismatch { what: "flow", predicted: 0, truth: true_flow.len() };
        let flow = score.flow.ok_or(ScoreError::Metric { pair: id(), source: no_flow })?;
        Ok(Self {
            epe: flow.epe,
            rand_index: score.p.rand_index,
            iou_sum: score.p.iou_sum,
            parts: score.p.parts as usize,
            support_iou,
        })
    }
}

/// A difference of one score between two networks on the same pairs, with a 95% interval.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Difference {
    /// The first network's score minus the second's, on the whole set.
    pub value: f64,
    /// The 2.5th percentile of the difference over the bootstrap resamples.
    pub low: f64,
    /// The 97.5th percentile.
    pub high: f64,
}

impl Difference {
    /// Whether the interval lies wholly above zero.
    pub fn above_zero(&self) -> bool {
        self.low > 0.0
    }

    /// Whether the interval lies wholly below zero.
    pub fn below_zero(&self) -> bool {
        self.high < 0.0
    }
}

/// Differences of every score between two networks, `a` minus `b`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Comparison {
    /// EPE difference (negative: `a` has the better flow).
    pub epe: Difference,
    /// Rand index difference.
    pub rand_index: Difference,
    /// IoU difference.
    pub iou: Difference,
    /// Support IoU difference.
    pub support_iou: Difference,
}

/// Why two sets of scores cannot be compared.
#[derive(Debug, thiserror::Error)]
pub enum CompareError {
    /// The two sets score different numbers of pairs.
    #[error("the first network was scored on {a} pairs and the second on {b}")]
    Lengths {
        /// Pairs of the first.
        a: usize,
        /// Pairs of the second.
        b: usize,
    },
    /// Nothing to compare.
    #[error("no pairs to compare")]
    Empty,
    /// Pair `index` has different parts in the two sets: they are not the same pairs.
    #[error("pair {index} has {a} parts in the first set and {b} in the second")]
    Parts {
        /// The pair's position.
        index: usize,
        /// Its parts in the first set.
        a: usize,
        /// Its parts in the second.
        b: usize,
    },
}

/// Compares two networks scored on the same pairs (`a[i]` and `b[i]` are one pair) by the
/// paired bootstrap: `resamples` times, draw as many pairs as there are with replacement
/// (the same draw for both networks), and take the difference of the mean scores; the
/// interval is the 2.5th to 97.5th percentile of those differences. The draws come from
/// `seed` alone.
pub fn compare(
    a: &[PairScores],
    b: &[PairScores],
    resamples: usize,
    seed: u64,
) -> Result<Comparison, CompareError> {
    use rand::{Rng, SeedableRng};
    if a.len() != b.len() {
        return Err(CompareError::Lengths { a: a.len(), b: b.len() });
    }
    if a.is_empty() {
        return Err(CompareError::Empty);
    }
    if let Some(index) = (0..a.len()).find(|&i| a[i].parts != b[i].parts) {
        return Err(CompareError::Parts { index, a: a[index].parts, b: b[index].parts });
    }
    let diff = |x: Scores, y: Scores| {
        [x.epe - y.epe, x.rand_index - y.rand_index, x.iou - y.iou, x.support_iou - y.support_iou]
    };
    let whole = diff(Scores::of(a), Scores::of(b));
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut draws: [Vec<f64>; 4] = Default::default();
    let mut sample = vec![0usize; a.len()];
    for _ in 0..resamples {
        sample.iter_mut().for_each(|s| *s = rng.random_range(0..a.len()));
        let d = diff(
            Scores::of_indices(a, sample.iter().copied()),
            Scores::of_indices(b, sample.iter().copied()),
        );
        for (draw, v) in draws.iter_mut().zip(d) {
            draw.push(v);
        }
    }
    let mut interval = |k: usize| {
        let mut d = std::mem::take(&mut draws[k]);
        d.sort_by(f64::total_cmp);
        let at = |q: f64| {
            if d.is_empty() {
                whole[k]
            } else {
                d[((q * (d.len() - 1) as f64).round() as usize).min(d.len() - 1)]
            }
        };
        Difference { value: whole[k], low: at(0.025), high: at(0.975) }
    };
    Ok(Comparison {
        epe: interval(0),
        rand_index: interval(1),
        iou: interval(2),
        support_iou: interval(3),
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
    use super::{compare, support_iou, true_flow, CompareError, PairScores, ScoreError, Scores};
    use pairs::synthetic::{cross_instance, hinge_pair};

    fn pair(epe: f64, iou_sum: f64, parts: usize) -> PairScores {
        PairScores { epe, rand_index: 0.5, iou_sum, parts, support_iou: 0.25 }
    }

    #[test]
    fn a_cross_instance_pair_has_no_true_flow_to_score() {
        let single = hinge_pair("h", 4, 0.5);
        assert_eq!(true_flow(&single).expect("a flow").len(), single.input().p.len());
        let cross = cross_instance(hinge_pair("x", 4, 0.5), 1.2);
        let err = true_flow(&cross).expect_err("no flow");
        assert!(matches!(&err, ScoreError::NoFlow { pair, kind: "XF2F" } if pair == "x"), "{err}");
        assert!(err.to_string().contains("SF2F, SF2P or SP2P"), "{err}");
    }

    #[test]
    fn scores_average_over_pairs_and_the_iou_over_parts() {
        let s = Scores::of(&[pair(0.1, 1.5, 2), pair(0.3, 0.2, 1)]);
        assert!((s.epe - 0.2).abs() < 1e-12);
        assert!((s.iou - 1.7 / 3.0).abs() < 1e-12);
        assert!((s.rand_index - 0.5).abs() < 1e-12);
        assert!((s.support_iou - 0.25).abs() < 1e-12);
    }

    #[test]
    fn a_uniform_gain_has_a_point_interval_and_a_mixed_one_straddles_zero() {
        let b: Vec<_> = (0..50).map(|i| pair(0.05 + 0.001 * i as f64, 0.4, 1)).collect();
        // Every pair 0.1 better in IoU and 0.01 better in EPE: every resample says so.
        let a: Vec<_> = b.iter().map(|p| pair(p.epe - 0.01, p.iou_sum + 0.1, 1)).collect();
        let c = compare(&a, &b, 500, 1).unwrap();
        for (d, want) in [(c.iou, 0.1), (c.epe, -0.01)] {
            assert!((d.value - want).abs() < 1e-9, "{d:?}");
            assert!((d.low - want).abs() < 1e-9 && (d.high - want).abs() < 1e-9, "{d:?}");
        }
        assert!(c.iou.above_zero() && c.epe.below_zero());
        assert_eq!(c.rand_index.value, 0.0);
        assert!(!c.rand_index.above_zero() && !c.rand_index.below_zero());
        // Half the pairs 0.2 better, half 0.2 worse: no difference on the whole set, and
        // resamples on both sides of it.
        let mixed: Vec<_> = b
            .iter()
            .enumerate()
            .map(|(i, p)| pair(p.epe, p.iou_sum + if i % 2 == 0 { 0.2 } else { -0.2 }, 1))
            .collect();
        let c = compare(&mixed, &b, 500, 1).unwrap();
        assert!(c.iou.value.abs() < 1e-9);
        assert!(c.iou.low < -0.01 && c.iou.high > 0.01, "{:?}", c.iou);
        // The draws come from the seed alone.
        assert_eq!(c, compare(&mixed, &b, 500, 1).unwrap());
    }

    #[test]
    fn comparing_different_pairs_is_an_error() {
        let a = [pair(0.1, 1.0, 2)];
        assert!(matches!(compare(&a, &[], 10, 0), Err(CompareError::Lengths { a: 1, b: 0 })));
        assert!(matches!(compare(&[], &[], 10, 0), Err(CompareError::Empty)));
        assert!(matches!(
            compare(&a, &[pair(0.1, 1.0, 3)], 10, 0),
            Err(CompareError::Parts { index: 0, a: 2, b: 3 })
        ));
    }

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
