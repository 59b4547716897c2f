//! The deformation graph of embedded deformation (Sumner, Schmid & Pauly 2007): nodes
//! spread over P by farthest point sampling, each carrying a local transform; every point
//! moves by the blend of its nearest nodes' transforms, with weights
//! `(1 - d / d_max)^2` normalised, `d_max` the distance to the next-nearest node.

use nalgebra::{Matrix3, Vector3 as Vector3d};
use pairs::math::{Point3, Real};

use crate::geometry::{sample_farthest_points, Neighbours};

/// A node's local transform `x -> matrix (x - g) + g + translation`, in f64.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NodeTransform {
    /// Affine part (a rotation for NRR, any matrix for ED).
    pub matrix: Matrix3<f64>,
    /// Translation of the node.
    pub translation: Vector3d<f64>,
}

impl NodeTransform {
    /// The identity transform.
    pub fn identity() -> Self {
        Self { matrix: Matrix3::identity(), translation: Vector3d::zeros() }
    }

    /// Where the transform of node `node` takes `x`.
    pub fn apply(&self, node: &Vector3d<f64>, x: &Vector3d<f64>) -> Vector3d<f64> {
        self.matrix * (x - node) + node + self.translation
    }
}

/// Nodes, their edges and every point's blending weights.
#[derive(Debug, Clone, PartialEq)]
pub struct DeformationGraph {
    /// Node positions (f64).
    pub nodes: Vec<Vector3d<f64>>,
    /// Directed edges `(j, k)`: node `k` is among node `j`'s nearest nodes.
    pub edges: Vec<(usize, usize)>,
    /// Per point, `(node, weight)` pairs summing to 1.
    pub weights: Vec<Vec<(usize, f64)>>,
}

/// f64 coordinates of a point.
pub fn to64(p: &Point3) -> Vector3d<f64> {
    Vector3d::new(f64::from(p.x), f64::from(p.y), f64::from(p.z))
}

/// The graph of `count` nodes over `points`, each point blended from its `influence`
/// nearest nodes, each node linked to its `graph_neighbours` nearest nodes.
pub fn build_graph(
    points: &[Point3],
    count: usize,
    influence: usize,
    graph_neighbours: usize,
) -> DeformationGraph {
    let chosen = sample_farthest_points(points, count.max(1));
    let node_points: Vec<Point3> = chosen.iter().map(|&i| points[i]).collect();
    let tree = Neighbours::build(&node_points);
    let edges = tree
        .knn_table(&node_points, graph_neighbours)
        .into_iter()
        .enumerate()
        .flat_map(|(j, near)| near.into_iter().map(move |k| (j, k)))
        .collect();
    let weights = points
        .iter()
        .map(|x| {
            let near = tree.knn(x, influence + 1);
            let dist = |j: usize| f64::from((node_points[j] - x).norm());
            let d_max = near.last().map_or(0.0, |&j| dist(j));
            let used = &near[..near.len().min(influence.max(1))];
            let raw: Vec<f64> = used
                .iter()
                .map(|&j| if d_max > 0.0 { (1.0 - dist(j) / d_max).max(0.0).powi(2) } else { 1.0 })
                .collect();
            let total: f64 = raw.iter().sum();
            used.iter()
                .zip(&raw)
                .map(|(&j, &w)| {
                    (j, if total > 1e-12 { w / total } else { 1.0 / used.len() as f64 })
                })
                .collect()
        })
        .collect();
    DeformationGraph { nodes: node_points.iter().map(to64).collect(), edges, weights }
}

impl DeformationGraph {
    /// `points` (the ones the graph was built on) moved by the blended node transforms.
    pub fn deform(&self, points: &[Point3], transforms: &[NodeTransform]) -> Vec<Point3> {
        points
            .iter()
            .zip(&self.weights)
            .map(|(x, weights)| {
                let x = to64(x);
                let moved = weights.iter().fold(Vector3d::zeros(), |acc, &(j, w)| {
                    acc + transforms[j].apply(&self.nodes[j], &x) * w
                });
                Point3::new(moved.x as Real, moved.y as Real, moved.z as Real)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_sum_to_one_and_identity_keeps_points() {
        let points: Vec<Point3> = (0..60)
            .map(|i| Point3::new((i % 6) as Real * 0.1, (i / 6) as Real * 0.1, 0.0))
            .collect();
        let graph = build_graph(&points, 8, 4, 3);
        assert_eq!(graph.nodes.len(), 8);
        assert_eq!(graph.edges.len(), 24);
        for w in &graph.weights {
            assert!((w.iter().map(|x| x.1).sum::<f64>() - 1.0).abs() < 1e-9);
        }
        let same = graph.deform(&points, &vec![NodeTransform::identity(); 8]);
        assert!(same.iter().zip(&points).all(|(a, b)| (a - b).norm() < 1e-6));
        let shift = NodeTransform {
            translation: Vector3d::new(0.0, 0.0, 1.0),
            ..NodeTransform::identity()
        };
        let up = graph.deform(&points, &vec![shift; 8]);
        assert!(up.iter().zip(&points).all(|(a, b)| (a.z - b.z - 1.0).abs() < 1e-6));
    }
}
