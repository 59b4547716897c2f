//! Small fragments merged into their best-fitting neighbour: after the graph cut a segment
//! may still fall into several connected pieces on the k-NN graph; pieces smaller than a
//! threshold join the adjacent segment whose rigid motion explains their flow best.

use pairs::math::{Point3, Vector3};
use pairs::segments::fit_segment_motions;

use super::graph::KnnGraph;

/// Relabels every connected fragment of fewer than `min_size` points with the adjacent
/// label (on `graph`) whose rigid motion, fitted to `flow` on that label's points, has the
/// smallest mean residual on the fragment. Fragments are visited from the smallest; a
/// fragment with no differently labelled neighbour is kept. Labels are not compacted.
pub fn merge_fragments(
    points: &[Point3],
    flow: &[Vector3],
    labels: &[u32],
    graph: &KnnGraph,
    min_size: usize,
) -> Vec<u32> {
    let mut labels = labels.to_vec();
    let motions = fit_segment_motions(points, flow, &labels);
    let adjacency = graph.adjacency();
    let (component, count) = graph.fragments(&labels);
    let mut members: Vec<Vec<usize>> = vec![Vec::new(); count];
    for (i, &c) in component.iter().enumerate() {
        members[c].push(i);
    }
    let mut order: Vec<usize> = (0..count).filter(|&c| members[c].len() < min_size).collect();
    order.sort_by_key(|&c| (members[c].len(), c));
    for c in order {
        let own = labels[members[c][0]];
        let mut candidates: Vec<u32> = members[c]
            .iter()
            .flat_map(|&i| adjacency[i].iter().map(|&j| labels[j]))
            .filter(|&l| l != own)
            .collect();
        candidates.sort_unstable();
        candidates.dedup();
        let residual = |l: u32| -> f32 {
            let Some(m) = motions.get(l as usize) else { return f32::INFINITY };
            members[c].iter().map(|&i| (m.apply(&points[i]) - (points[i] + flow[i])).norm()).sum()
        };
        if let Some(best) =
            candidates.into_iter().min_by(|&a, &b| residual(a).total_cmp(&residual(b)))
        {
            for &i in &members[c] {
                labels[i] = best;
            }
        }
    }
    labels
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_island_joins_the_segment_that_moves_like_it() {
        // Two rows of points: the left half still, the right half moving up; a stray point
        // labelled 2 in the right half moves with it and must join label 1, not label 0.
        let points: Vec<Point3> = (0..20).map(|i| Point3::new(i as f32 * 0.05, 0.0, 0.0)).collect();
        let flow: Vec<Vector3> = (0..20)
            .map(|i| if i < 10 { Vector3::zeros() } else { Vector3::new(0.0, 0.1, 0.0) })
            .collect();
        let mut labels: Vec<u32> = (0..20).map(|i| u32::from(i >= 10)).collect();
        labels[15] = 2;
        labels[3] = 1;
        let graph = KnnGraph::build(&points, 2, 0.05);
        let merged = merge_fragments(&points, &flow, &labels, &graph, 3);
        let expected: Vec<u32> = (0..20).map(|i| u32::from(i >= 10)).collect();
        assert_eq!(merged, expected);
    }
}
