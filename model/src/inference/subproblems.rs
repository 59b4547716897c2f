//! The authors' release's per-segment sub-problems (`seg_util.gen_attention_mask` and
//! `motion_modes_aggreg_watt` in `ericyi/articulated-part-induction`): after a pass has
//! segmented P, every segment gets a sub-pair of its own, the part of P within a geodesic
//! distance `expand_eps` of the segment (its attention mask) moved by the segment's motion,
//! and the part of Q within the same distance of Q's points of that segment; the
//! correspondence and flow modules run on each sub-pair, and every point of P takes the
//! prediction of the sub-pair, among those whose mask holds it, that moved it least (the
//! sub-pair whose segment motion already explained it best).
//!
//! Geodesic distances are shortest paths on the graph joining every point to its 5 nearest
//! others, weighted by their Euclidean distance (the release: the same graph, Floyd-Warshall);
//! points the graph cannot reach are infinitely far.
//!
//! Departures from the release, each forced by our pipeline or by determinism: the segments
//! are our hard labels (the release's inlier sets of its per-segment ICP, widened by a
//! nearest-motion assignment that our labels, covering every point, already are); a sub-pair
//! is padded to the clouds' sizes with the segment's own points in turn (the release: drawn at
//! random); a segment with no point on Q uses the whole of Q (the release: a cloud of zeros).

use pairs::math::{Point3, Real, Vector3};
use pairs::transform::Similarity;
use pairs::PairInput;

use crate::inference::labels::KnnGraph;
use crate::network::sampling::SamplingError;
use crate::network::PartInductionNet;

/// Neighbours per point of the geodesic graph (the release's `nnbr`).
pub const GEODESIC_NEIGHBOURS: usize = 5;

/// The release's attention radii, one per refinement pass after the first (normalised
/// units): 0.2, then 0.15 four times, then 0.1 four times; later passes keep the last.
pub const EXPAND_EPS: [Real; 9] = [0.2, 0.15, 0.15, 0.15, 0.15, 0.1, 0.1, 0.1, 0.1];

/// The attention radius of refinement pass `k` (1 for the first pass after the whole-pair one).
pub fn expand_eps(k: usize) -> Real {
    EXPAND_EPS[k.saturating_sub(1).min(EXPAND_EPS.len() - 1)]
}

/// Micro-units of the normalised frame: Dijkstra's integer path lengths (pathfinding needs
/// an ordered cost; a rounding of 5e-7 per edge is far below any radius used).
const UNITS: Real = 1e6;

/// Geodesic distances on one cloud's 5-nearest-neighbour graph.
#[derive(Debug, Clone)]
pub struct Geodesic {
    /// Neighbours of every point with the edge's length in micro-units.
    adjacency: Vec<Vec<(usize, u64)>>,
}

impl Geodesic {
    /// The graph of `points`.
    pub fn new(points: &[Point3]) -> Self {
        let graph = KnnGraph::build(points, GEODESIC_NEIGHBOURS, 1.0);
        let mut adjacency = vec![Vec::new(); points.len()];
        for &(i, j, _) in &graph.edges {
            let length = ((points[i] - points[j]).norm() * UNITS).round() as u64;
            adjacency[i].push((j, length));
            adjacency[j].push((i, length));
        }
        Self { adjacency }
    }

    /// Every point's geodesic distance to the nearest point of `sources` (0 on the sources;
    /// infinite where no path leads; infinite everywhere when `sources` is empty).
    pub fn distances_from(&self, sources: &[usize]) -> Vec<Real> {
        let n = self.adjacency.len();
        let mut distance = vec![Real::INFINITY; n];
        if sources.is_empty() {
            return distance;
        }
        // A virtual node `n` joined to every source at no cost.
        let reached = pathfinding::prelude::dijkstra_all(&n, |&node| -> Vec<(usize, u64)> {
            if node == n {
                sources.iter().map(|&s| (s, 0)).collect()
            } else {
                self.adjacency[node].clone()
            }
        });
        for (node, (_, cost)) in reached {
            distance[node] = cost as Real / UNITS;
        }
        distance
    }
}

/// One segment's sub-pair: which points of P and of Q it holds.
#[derive(Debug, Clone, PartialEq)]
pub struct Attention {
    /// Indices of P's points within the radius of the segment (its attention mask).
    pub p: Vec<usize>,
    /// Indices of Q's points within the radius of Q's points of the segment; all of Q when
    /// the segment has none there.
    pub q: Vec<usize>,
}

/// The attention masks of segments `0..k` (labels on P and Q) at geodesic radius `eps`; a
/// segment with no point on P gets none.
pub fn attention_masks(
    p_graph: &Geodesic,
    q_graph: &Geodesic,
    labels_p: &[u32],
    labels_q: &[u32],
    k: usize,
    eps: Real,
) -> Vec<Option<Attention>> {
    let members = |labels: &[u32], s: usize| -> Vec<usize> {
        labels.iter().enumerate().filter(|&(_, &l)| l as usize == s).map(|(i, _)| i).collect()
    };
    let within = |graph: &Geodesic, sources: &[usize]| -> Vec<usize> {
        let d = graph.distances_from(sources);
        (0..d.len()).filter(|&i| d[i] < eps).collect()
    };
    (0..k)
        .map(|s| {
            let on_p = members(labels_p, s);
            if on_p.is_empty() {
                return None;
            }
            let on_q = members(labels_q, s);
            let q = if on_q.is_empty() {
                (0..labels_q.len()).collect()
            } else {
                within(q_graph, &on_q)
            };
            Some(Attention { p: within(p_graph, &on_p), q })
        })
        .collect()
}

/// `points[indices]` followed by `pad` in turn up to `size` points.
fn padded(points: &[Point3], indices: &[usize], pad: &[usize], size: usize) -> Vec<Point3> {
    let mut out: Vec<Point3> = indices.iter().map(|&i| points[i]).collect();
    let mut cycle = pad.iter().cycle();
    while out.len() < size {
        match cycle.next() {
            Some(&i) => out.push(points[i]),
            None => break,
        }
    }
    out
}

/// What one refinement pass by sub-problems gives.
#[derive(Debug, Clone, PartialEq)]
pub struct SubProblemFlow {
    /// The merged flow of every point of P.
    pub flow: Vec<Vector3>,
    /// The correspondence mask of every point of P, from the sub-pair its flow came from.
    pub mask: Vec<f32>,
    /// Mean norm of the chosen sub-pair residuals: how far each moved piece still is from Q.
    pub residual: Real,
}

impl PartInductionNet {
    /// One refinement pass by per-segment sub-problems (module docs): `start` is P (in the
    /// frame the flow starts from), `labels` (on P and Q) and `motions` the previous pass's
    /// segments, `eps` the attention radius. With `null` (the network's flow from Q to
    /// itself, on Q's points), every sub-pair's residual is calibrated as the whole pair's
    /// is ([`InferenceParams::calibrate`](super::InferenceParams::calibrate)): minus the
    /// null flow at the moved point's nearest point of Q. A point no mask holds (none does,
    /// since every point is in its own segment's mask) keeps `previous`.
    #[allow(clippy::too_many_arguments)]
    pub fn sub_problem_flow(
        &self,
        input: &PairInput,
        start: &[Point3],
        graphs: (&Geodesic, &Geodesic),
        labels: (&[u32], &[u32]),
        motions: &[Similarity],
        previous: &[Vector3],
        null: Option<&[Vector3]>,
        eps: Real,
    ) -> Result<SubProblemFlow, SamplingError> {
        let n = start.len();
        let masks = attention_masks(graphs.0, graphs.1, labels.0, labels.1, motions.len(), eps);
        let mut pieces = Vec::with_capacity(masks.len());
        for (s, attention) in masks.iter().enumerate() {
            let Some(attention) = attention else { continue };
            let segment: Vec<usize> = (0..n).filter(|&i| labels.0[i] as usize == s).collect();
            let segment_q: Vec<usize> =
                (0..labels.1.len()).filter(|&i| labels.1[i] as usize == s).collect();
            let pad_q = if segment_q.is_empty() { &attention.q } else { &segment_q };
            let mut sub = input.clone();
            sub.p.points = padded(start, &attention.p, &segment, n)
                .iter()
                .map(|x| motions[s].apply(x))
                .collect();
            sub.q.points = padded(&input.q.points, &attention.q, pad_q, input.q.len());
            let (mut residual, mask) = self.flow_pass(&sub)?;
            if let Some(null) = null {
                for (r, x) in residual.iter_mut().zip(&sub.p.points) {
                    *r -= null[super::nearest(&input.q.points, x)];
                }
            }
            let k = attention.p.len();
            pieces.push(Piece {
                indices: attention.p.clone(),
                moved: sub.p.points[..k].to_vec(),
                residual: residual[..k].to_vec(),
                mask: mask[..k].to_vec(),
            });
        }
        Ok(merge_pieces(start, previous, &pieces))
    }
}

/// One sub-pair's prediction on the points of P its mask holds.
#[derive(Debug, Clone, PartialEq)]
pub struct Piece {
    /// Indices of the points of P (the attention mask).
    pub indices: Vec<usize>,
    /// Those points moved by the segment's motion.
    pub moved: Vec<Point3>,
    /// The residual flow the network predicted for each (calibrated where asked).
    pub residual: Vec<Vector3>,
    /// The correspondence mask of each.
    pub mask: Vec<f32>,
}

/// The release's merge (`motion_modes_aggreg_watt`): every point of P takes the prediction
/// (moved point plus residual) of the piece, among those holding it, with the smallest
/// residual; ties go to the earlier piece; a point no piece holds keeps `previous` (and a
/// mask of 1). The residual reported is the mean of the chosen residuals' norms.
pub fn merge_pieces(start: &[Point3], previous: &[Vector3], pieces: &[Piece]) -> SubProblemFlow {
    let n = start.len();
    let mut flow = previous.to_vec();
    let mut mask = vec![1.0f32; n];
    let mut best = vec![Real::INFINITY; n];
    for piece in pieces {
        for (j, &i) in piece.indices.iter().enumerate() {
            let norm = piece.residual[j].norm();
            if norm < best[i] {
                best[i] = norm;
                flow[i] = piece.moved[j] + piece.residual[j] - start[i];
                mask[i] = piece.mask[j];
            }
        }
    }
    let held: Vec<Real> = best.iter().copied().filter(|b| b.is_finite()).collect();
    let residual = held.iter().sum::<Real>() / held.len().max(1) as Real;
    SubProblemFlow { flow, mask, residual }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points on a line at spacing 0.1: geodesic distances along it are exact.
    fn line(n: usize) -> Vec<Point3> {
        (0..n).map(|i| Point3::new(i as Real * 0.1, 0.0, 0.0)).collect()
    }

    #[test]
    fn geodesic_distances_follow_the_graph() {
        let points = line(10);
        let g = Geodesic::new(&points);
        let d = g.distances_from(&[0, 9]);
        for (i, di) in d.iter().enumerate() {
            let expected = (i.min(9 - i)) as Real * 0.1;
            assert!((di - expected).abs() < 1e-5, "point {i}: {di} vs {expected}");
        }
        assert!(g.distances_from(&[]).iter().all(|d| d.is_infinite()));
    }

    #[test]
    fn geodesic_distance_goes_around_a_gap_not_across_it() {
        // A U: two arms 0.3 apart (farther than any point's 5th neighbour along its arm)
        // joined at the bottom: the way between the tops is 0.55 + 0.3 + 0.55 along the
        // points, a little less cutting the corners' diagonal edges, and 0.3 across the gap.
        let mut points: Vec<Point3> =
            (0..12).map(|i| Point3::new(0.0, i as Real * 0.05, 0.0)).collect();
        points.extend((1..6).map(|i| Point3::new(i as Real * 0.05, 0.0, 0.0)));
        points.extend((0..12).map(|i| Point3::new(0.3, i as Real * 0.05, 0.0)));
        let g = Geodesic::new(&points);
        let top_left = 11;
        let top_right = points.len() - 1;
        let d = g.distances_from(&[top_left])[top_right];
        assert!(d > 1.2 && d < 1.4 + 1e-4, "the path goes down one arm and up the other: {d}");
    }

    #[test]
    fn attention_masks_widen_segments_by_the_radius() {
        let points = line(20);
        let g = Geodesic::new(&points);
        let labels: Vec<u32> = (0..20).map(|i| u32::from(i >= 10)).collect();
        let masks = attention_masks(&g, &g, &labels, &labels, 3, 0.25);
        let a = masks[0].as_ref().unwrap();
        // Segment 0 is points 0..10; within 0.25 of point 9 are 10 and 11 (0.1, 0.2).
        assert_eq!(a.p, (0..12).collect::<Vec<_>>());
        let b = masks[1].as_ref().unwrap();
        assert_eq!(b.p, (8..20).collect::<Vec<_>>());
        assert!(masks[2].is_none(), "an empty segment has no sub-pair");
        // A segment absent from Q takes the whole of Q.
        let q_labels = vec![0u32; 20];
        let masks = attention_masks(&g, &g, &labels, &q_labels, 2, 0.25);
        assert_eq!(masks[1].as_ref().unwrap().q, (0..20).collect::<Vec<_>>());
    }

    #[test]
    fn the_merge_takes_the_least_residual_of_the_pieces_holding_a_point() {
        let start = line(4);
        let previous = vec![Vector3::new(9.0, 0.0, 0.0); 4];
        let shift = |d: Real| Vector3::new(0.0, d, 0.0);
        // Piece A holds 0, 1, 2 moved up by 1; piece B holds 1, 2 moved up by 2.
        let a = Piece {
            indices: vec![0, 1, 2],
            moved: [0, 1, 2].iter().map(|&i| start[i] + shift(1.0)).collect(),
            residual: vec![shift(0.1), shift(0.3), shift(0.2)],
            mask: vec![0.1, 0.2, 0.3],
        };
        let b = Piece {
            indices: vec![1, 2],
            moved: [1, 2].iter().map(|&i| start[i] + shift(2.0)).collect(),
            residual: vec![shift(0.05), shift(-0.2)],
            mask: vec![0.4, 0.5],
        };
        let merged = merge_pieces(&start, &previous, &[a, b]);
        // 0: A only; 1: B's residual is smaller; 2: a tie, the earlier piece (A) keeps it;
        // 3: no piece, the previous flow.
        let expected = [shift(1.1), shift(2.05), shift(1.2), Vector3::new(9.0, 0.0, 0.0)];
        for (got, want) in merged.flow.iter().zip(&expected) {
            assert!((got - want).norm() < 1e-6, "{got} vs {want}");
        }
        assert_eq!(merged.mask, vec![0.1, 0.4, 0.3, 1.0]);
        assert!((merged.residual - (0.1 + 0.05 + 0.2) / 3.0).abs() < 1e-6);
    }

    #[test]
    fn padding_repeats_the_segment_in_turn() {
        let points = line(6);
        let out = padded(&points, &[0, 1], &[4, 5], 5);
        let expected: Vec<Point3> = [0, 1, 4, 5, 4].iter().map(|&i| points[i]).collect();
        assert_eq!(out, expected);
        assert_eq!(padded(&points, &[0], &[], 3).len(), 1, "nothing to pad with");
        assert_eq!(expand_eps(1), 0.2);
        assert_eq!(expand_eps(5), 0.15);
        assert_eq!(expand_eps(6), 0.1);
        assert_eq!(expand_eps(40), 0.1);
    }
}
