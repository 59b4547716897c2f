//! From the network's soft segment probabilities to hard labels on P and Q and one rigid
//! motion per segment, as the paper's "Segmentation" and supplementary "Graph Cuts"
//! describe: a Potts graph cut on P's k-NN graph with `-ln p` as the data term, small
//! fragments merged into their best-fitting neighbour, a weighted Kabsch/Umeyama fit per
//! segment, then P's segments moved onto Q, Q labelled by its nearest moved points and the
//! same graph cut run on Q.

use pairs::math::{Point3, Real, Vector3};
use pairs::segments::{compact_labels, fit_segment_motions};
use pairs::transform::Similarity;

use super::expansion::alpha_expansion;
use super::fragments::merge_fragments;
use super::graph::KnnGraph;
use super::motions::fit_motions_shared_scale;

/// Parameters of the hard-label step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HardLabelParams {
    /// Neighbours per point in the k-NN graph (paper: 10).
    pub neighbours: usize,
    /// Width of the Gaussian edge weight, normalised units (paper: 0.05).
    pub sigma: Real,
    /// Weight λ of the Potts term against the `-ln p` data term. The paper's formula has
    /// none (λ = 1); 0.3 scored better on the validation categories (40 pairs, with the
    /// motion term below: RI 0.715 / IoU 0.531 after the iterations, against 0.682 / 0.504
    /// for λ = 1 without it; measured before the shared scale and the stopping rule, with 10
    /// passes), because the shipped network's probabilities are flatter.
    pub smoothness: Real,
    /// Probabilities are clamped below at this value before the logarithm, which bounds
    /// the data term at `-ln(floor)`.
    pub probability_floor: Real,
    /// Fragments smaller than this fraction of the cloud are merged (0.02: 10 of 512).
    pub min_fragment: Real,
    /// At most this many sweeps of alpha-expansion over the labels.
    pub max_cycles: usize,
    /// Weight μ of a second cut's motion term (0: one cut on the probabilities alone, as
    /// in the paper; 3 by default, chosen with λ on the validation categories). After the first cut, each segment's rigid motion is fitted to the
    /// flow and a second cut adds `μ min(r², 9 σ_r²) / 2σ_r²` to the data term, `r` the
    /// distance between where the segment's motion puts the point and where the flow does:
    /// points move to the segment whose motion explains their flow. A departure from the
    /// paper: with it, a better flow (later iterations) gives better labels.
    pub motion_weight: Real,
    /// Width σ_r of the motion term, normalised units.
    pub motion_sigma: Real,
}

impl Default for HardLabelParams {
    fn default() -> Self {
        Self {
            neighbours: 10,
            sigma: 0.05,
            smoothness: 0.3,
            probability_floor: 1e-4,
            min_fragment: 0.02,
            max_cycles: 5,
            motion_weight: 3.0,
            motion_sigma: 0.03,
        }
    }
}

/// Hard segments of a pair and their motions.
#[derive(Debug, Clone, PartialEq)]
pub struct HardSegmentation {
    /// Segment id `0..K` of every point of P (in order of first appearance).
    pub labels_p: Vec<u32>,
    /// Segment id of every point of Q (P's ids).
    pub labels_q: Vec<u32>,
    /// The motion of each segment, P's to Q's normalised frame.
    pub motions: Vec<Similarity>,
    /// The soft probabilities with columns reordered to the segment ids (columns of
    /// segments that vanished are dropped; rows renormalised).
    pub probs: Vec<Vec<Real>>,
}

/// Rows normalised to sum 1 (a zero row becomes uniform).
fn normalised(probs: &[Vec<Real>]) -> Vec<Vec<Real>> {
    probs
        .iter()
        .map(|row| {
            let sum: Real = row.iter().map(|v| v.max(0.0)).sum();
            if sum > 0.0 {
                row.iter().map(|v| v.max(0.0) / sum).collect()
            } else {
                vec![1.0 / row.len().max(1) as Real; row.len()]
            }
        })
        .collect()
}

/// The column of the largest entry of each row (ties to the lower column): the labels of
/// soft segment probabilities without a graph cut.
pub fn argmax(rows: &[Vec<Real>]) -> Vec<u32> {
    rows.iter()
        .map(|row| {
            (0..row.len()).max_by(|&a, &b| row[a].total_cmp(&row[b]).then(b.cmp(&a))).unwrap_or(0)
                as u32
        })
        .collect()
}

/// Hard labels of P (ids are columns of `probs`, not compacted): graph cut from the
/// argmax, then fragments merged by `flow`.
pub fn hard_labels(
    points: &[Point3],
    probs: &[Vec<Real>],
    flow: &[Vector3],
    params: &HardLabelParams,
) -> Vec<u32> {
    let probs = normalised(probs);
    let costs: Vec<Vec<Real>> = probs
        .iter()
        .map(|row| row.iter().map(|&p| -p.max(params.probability_floor).ln()).collect())
        .collect();
    let graph = KnnGraph::build(points, params.neighbours, params.sigma);
    let mut cut =
        alpha_expansion(&costs, &graph, params.smoothness, &argmax(&probs), params.max_cycles);
    if params.motion_weight > 0.0 {
        let costs = with_motion_term(points, flow, &costs, &cut, params);
        cut = alpha_expansion(&costs, &graph, params.smoothness, &cut, params.max_cycles);
    }
    let min_size = (params.min_fragment * points.len() as Real).ceil() as usize;
    merge_fragments(points, flow, &cut, &graph, min_size)
}

/// `costs` plus the motion term of [`HardLabelParams::motion_weight`] for the segments of
/// `labels`; a column no point holds gets a prohibitive cost, so that the second cut
/// cannot bring back a segment the first one removed.
fn with_motion_term(
    points: &[Point3],
    flow: &[Vector3],
    costs: &[Vec<Real>],
    labels: &[u32],
    params: &HardLabelParams,
) -> Vec<Vec<Real>> {
    const ABSENT: Real = 1e4;
    let motions = fit_segment_motions(points, flow, labels);
    let present: Vec<bool> =
        (0..motions.len()).map(|k| labels.iter().any(|&l| l as usize == k)).collect();
    let two_var = 2.0 * params.motion_sigma * params.motion_sigma;
    costs
        .iter()
        .zip(points.iter().zip(flow))
        .map(|(row, (x, f))| {
            let target = x + f;
            row.iter()
                .enumerate()
                .map(|(k, &c)| match motions.get(k) {
                    Some(m) if present[k] => {
                        let r2 = (m.apply(x) - target).norm_squared().min(4.5 * two_var);
                        c + params.motion_weight * r2 / two_var
                    }
                    _ => c + ABSENT,
                })
                .collect()
        })
        .collect()
}

/// Q's labels: each point of Q takes the label of its nearest point of P moved by its
/// segment's motion, then the same graph cut runs on Q with the data term
/// `d_k² / 2σ²` (`d_k`: distance to the nearest moved point of segment k, the negative log
/// of a Gaussian likelihood), clamped like P's at `-ln(floor)`.
pub fn label_q(
    p: &[Point3],
    labels_p: &[u32],
    motions: &[Similarity],
    q: &[Point3],
    params: &HardLabelParams,
) -> Vec<u32> {
    let k = motions.len();
    if k == 0 || p.is_empty() {
        return vec![0; q.len()];
    }
    let placed: Vec<Point3> = p
        .iter()
        .zip(labels_p)
        .map(|(x, &l)| motions.get(l as usize).map_or(*x, |m| m.apply(x)))
        .collect();
    let cap = -params.probability_floor.ln();
    let costs: Vec<Vec<Real>> = q
        .iter()
        .map(|y| {
            let mut nearest = vec![Real::INFINITY; k];
            for (x, &l) in placed.iter().zip(labels_p) {
                let d = &mut nearest[l as usize];
                *d = d.min((x - y).norm_squared());
            }
            nearest.iter().map(|d2| (d2 / (2.0 * params.sigma * params.sigma)).min(cap)).collect()
        })
        .collect();
    let initial = argmax(
        &costs.iter().map(|row| row.iter().map(|c| -c).collect()).collect::<Vec<Vec<Real>>>(),
    );
    let graph = KnnGraph::build(q, params.neighbours, params.sigma);
    alpha_expansion(&costs, &graph, params.smoothness, &initial, params.max_cycles)
}

/// Hard segments of a pair from soft probabilities on P (`probs[i][k]`) and a flow on P:
/// [`hard_labels`], one motion per segment by Kabsch weighted with each point's probability
/// of its segment, with one scale for all segments ([`fit_motions_shared_scale`]), and
/// [`label_q`].
pub fn segment_pair(
    p: &[Point3],
    q: &[Point3],
    probs: &[Vec<Real>],
    flow: &[Vector3],
    params: &HardLabelParams,
) -> HardSegmentation {
    let raw = hard_labels(p, probs, flow, params);
    let labels_p = compact_labels(&raw);
    let k = labels_p.iter().max().map_or(0, |&m| m as usize + 1);
    // The raw id (probability column) of every compact id.
    let mut column = vec![0usize; k];
    for (&r, &l) in raw.iter().zip(&labels_p) {
        column[l as usize] = r as usize;
    }
    let probs = normalised(probs);
    let weights: Vec<Real> =
        labels_p.iter().zip(&probs).map(|(&l, row)| row[column[l as usize]].max(1e-3)).collect();
    let motions = fit_motions_shared_scale(p, flow, &labels_p, &weights, k);
    let labels_q = label_q(p, &labels_p, &motions, q, params);
    let probs = normalised(
        &probs.iter().map(|row| column.iter().map(|&c| row[c]).collect()).collect::<Vec<_>>(),
    );
    HardSegmentation { labels_p, labels_q, motions, probs }
}

#[cfg(test)]
mod tests {
    use super::*;
    use pairs::synthetic::hinge_pair;
    use rand::{Rng, SeedableRng};

    /// Soft probabilities over `k` columns that favour the true part, with a fraction of the
    /// points favouring a wrong column instead (salt-and-pepper noise).
    fn noisy_probs(parts: &[u8], k: usize, flip: f64, seed: u64) -> Vec<Vec<Real>> {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        parts
            .iter()
            .map(|&t| {
                let favoured =
                    if rng.random_bool(flip) { rng.random_range(0..k) } else { usize::from(t) };
                (0..k).map(|c| if c == favoured { 0.6 } else { 0.4 / (k - 1) as Real }).collect()
            })
            .collect()
    }

    /// Fraction of points whose label equals the true part (the ids agree by construction).
    fn agreement(labels: &[u32], truth: &[u8]) -> f64 {
        let same = labels.iter().zip(truth).filter(|(&l, &t)| l == u32::from(t)).count();
        same as f64 / truth.len() as f64
    }

    #[test]
    fn graph_cut_cleans_salt_and_pepper_labels() {
        let pair = hinge_pair("t", 12, 0.8);
        let (input, truth) = (pair.input(), pair.truth());
        let probs = noisy_probs(&truth.part_p, 4, 0.2, 3);
        let params = HardLabelParams::default();
        let graph = KnnGraph::build(&input.p.points, params.neighbours, params.sigma);
        let before = argmax(&probs);
        let after =
            hard_labels(&input.p.points, &probs, truth.flow.as_deref().expect("a flow"), &params);
        let count = |l: &[u32]| {
            let mut v = l.to_vec();
            v.sort_unstable();
            v.dedup();
            v.len()
        };
        assert!(count(&after) <= count(&before));
        assert!(graph.fragments(&after).1 < graph.fragments(&before).1);
        let seg = segment_pair(
            &input.p.points,
            &input.q.points,
            &probs,
            truth.flow.as_deref().expect("a flow"),
            &params,
        );
        // Points at the hinge sit closer to the other part than to their own rows, so the
        // smoothness term may move that one column: compare by agreement, not equality.
        assert!(agreement(&seg.labels_p, &truth.part_p) > 0.95);
        assert!(agreement(&seg.labels_q, &truth.part_q) > 0.9);
        for (k, m) in seg.motions.iter().enumerate() {
            let part = truth.part_p[seg.labels_p.iter().position(|&l| l as usize == k).unwrap()];
            let gt = &truth.motions[usize::from(part)];
            assert!((m.rotation - gt.rotation).norm() < 0.02);
            assert!((m.translation - gt.translation).norm() < 0.02);
        }
        assert!(seg.probs.iter().all(|row| row.len() == seg.motions.len()));
    }

    #[test]
    fn q_labels_follow_the_moved_segments_without_probabilities() {
        let pair = hinge_pair("t", 8, 1.2);
        let (input, truth) = (pair.input(), pair.truth());
        let labels = compact_labels(&truth.part_p);
        let q = label_q(
            &input.p.points,
            &labels,
            &truth.motions,
            &input.q.points,
            &HardLabelParams::default(),
        );
        assert!(agreement(&q, &truth.part_q) > 0.9);
        assert_eq!(label_q(&[], &[], &[], &input.q.points, &HardLabelParams::default()).len(), 128);
    }
}
