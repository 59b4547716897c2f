//! The k-nearest-neighbour graph of a point cloud that the graph cut smooths over, with the
//! paper's edge weights `exp(-|p_i - p_j|² / 2σ²)` (supplementary material, "Graph Cuts":
//! k = 10, σ = 0.05 normalised units).

use pairs::math::Point3;

/// An undirected weighted graph on the points of a cloud.
#[derive(Debug, Clone, PartialEq)]
pub struct KnnGraph {
    /// Number of nodes (points).
    pub nodes: usize,
    /// Edges `(i, j, weight)` with `i < j`, each once (an edge is kept when either point is
    /// among the other's k nearest).
    pub edges: Vec<(usize, usize, f32)>,
}

impl KnnGraph {
    /// The graph joining every point to its `k` nearest others, weighted by a Gaussian of
    /// their distance with width `sigma`.
    pub fn build(points: &[Point3], k: usize, sigma: f32) -> Self {
        let n = points.len();
        let k = k.min(n.saturating_sub(1));
        let mut edges = Vec::with_capacity(n * k);
        let mut order: Vec<(f32, usize)> = Vec::with_capacity(n);
        for (i, p) in points.iter().enumerate() {
            order.clear();
            order.extend(
                points
                    .iter()
                    .enumerate()
                    .filter(|&(j, _)| j != i)
                    .map(|(j, q)| ((p - q).norm_squared(), j)),
            );
            if k < order.len() {
                order.select_nth_unstable_by(k, |a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            }
            for &(d2, j) in &order[..k] {
                let w = (-d2 / (2.0 * sigma * sigma)).exp();
                edges.push((i.min(j), i.max(j), w));
            }
        }
        edges.sort_by_key(|e| (e.0, e.1));
        edges.dedup_by(|a, b| a.0 == b.0 && a.1 == b.1);
        Self { nodes: n, edges }
    }

    /// Neighbour lists, one per node.
    pub fn adjacency(&self) -> Vec<Vec<usize>> {
        let mut adjacency = vec![Vec::new(); self.nodes];
        for &(i, j, _) in &self.edges {
            adjacency[i].push(j);
            adjacency[j].push(i);
        }
        adjacency
    }

    /// Connected components of the subgraph whose edges join equal `labels`: a component
    /// id per node (`0..count`, in order of first node) and the count.
    pub fn fragments(&self, labels: &[u32]) -> (Vec<usize>, usize) {
        let adjacency = self.adjacency();
        let mut component = vec![usize::MAX; self.nodes];
        let mut count = 0;
        for start in 0..self.nodes {
            if component[start] != usize::MAX {
                continue;
            }
            component[start] = count;
            let mut stack = vec![start];
            while let Some(u) = stack.pop() {
                for &v in &adjacency[u] {
                    if component[v] == usize::MAX && labels[v] == labels[u] {
                        component[v] = count;
                        stack.push(v);
                    }
                }
            }
            count += 1;
        }
        (component, count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(n: usize, spacing: f32) -> Vec<Point3> {
        (0..n).map(|i| Point3::new(i as f32 * spacing, 0.0, 0.0)).collect()
    }

    #[test]
    fn a_line_joins_neighbours_once() {
        let g = KnnGraph::build(&line(5, 0.125), 1, 0.05);
        let pairs: Vec<(usize, usize)> = g.edges.iter().map(|e| (e.0, e.1)).collect();
        assert_eq!(pairs, vec![(0, 1), (1, 2), (2, 3), (3, 4)]);
        // Spacing 1/8 is exact in f32, so ties go to the lower index.
        let expected = (-0.015625f32 / (2.0 * 0.0025)).exp();
        assert!(g.edges.iter().all(|e| (e.2 - expected).abs() < 1e-5));
    }

    #[test]
    fn fragments_split_at_label_changes() {
        let g = KnnGraph::build(&line(6, 0.1), 1, 0.05);
        let (component, count) = g.fragments(&[0, 0, 1, 0, 0, 1]);
        assert_eq!(count, 4);
        assert_eq!(component, vec![0, 0, 1, 2, 2, 3]);
    }

    #[test]
    fn tiny_clouds_do_not_panic() {
        assert!(KnnGraph::build(&[], 10, 0.05).edges.is_empty());
        assert!(KnnGraph::build(&[Point3::origin()], 10, 0.05).edges.is_empty());
    }
}
