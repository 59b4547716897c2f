//! Closest-point correspondences from a moved copy of P to Q, trimmed to the closest
//! fraction (Chetverikov et al. 2002's trimmed ICP): the farthest pairs are most often
//! points of P with no counterpart in Q (missing data, outliers).

use pairs::math::{Point3, Real};

use crate::geometry::Neighbours;

/// Closest points in Q of moved points of P, with 0/1 weights that drop the farthest ones.
#[derive(Debug, Clone, PartialEq)]
pub struct Matches {
    /// Per point of P, the index of its closest point in Q.
    pub target: Vec<usize>,
    /// Per point of P, 1 if its match is among the kept fraction, else 0.
    pub weight: Vec<Real>,
    /// Mean distance of the kept matches.
    pub mean_distance: Real,
}

/// Matches every point of `moved` to its closest point of Q (`q_tree` indexes Q) and keeps
/// the `keep_fraction` closest pairs (at least three, or all when fewer).
pub fn match_closest(moved: &[Point3], q_tree: &Neighbours, keep_fraction: Real) -> Matches {
    let hits: Vec<(usize, Real)> = moved
        .iter()
        .map(|x| q_tree.nearest(x).map_or((0, Real::MAX), |(j, d2)| (j, d2.sqrt())))
        .collect();
    let mut order: Vec<usize> = (0..hits.len()).collect();
    order.sort_by(|&a, &b| hits[a].1.total_cmp(&hits[b].1));
    let keep = ((keep_fraction.clamp(0.0, 1.0) * hits.len() as Real).ceil() as usize)
        .max(3)
        .min(hits.len());
    let mut weight = vec![0.0; hits.len()];
    for &i in &order[..keep] {
        weight[i] = 1.0;
    }
    let mean_distance =
        order[..keep].iter().map(|&i| hits[i].1).sum::<Real>() / keep.max(1) as Real;
    Matches { target: hits.iter().map(|h| h.0).collect(), weight, mean_distance }
}

/// Mean distance from each point of `points` to its closest point of `q` (how well a
/// deformed P covers Q; the one-sided Chamfer distance).
pub fn mean_closest_distance(points: &[Point3], q: &[Point3]) -> Real {
    let tree = Neighbours::build(q);
    let total: Real = points.iter().filter_map(|x| tree.nearest(x)).map(|(_, d2)| d2.sqrt()).sum();
    total / points.len().max(1) as Real
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trimming_drops_the_farthest_pairs() {
        let q = [
            Point3::origin(),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(0.0, 1.0, 0.0),
            Point3::new(0.0, 0.0, 1.0),
        ];
        let mut moved = q.to_vec();
        moved[2].y += 0.5;
        let m = match_closest(&moved, &Neighbours::build(&q), 0.75);
        assert_eq!(m.target, vec![0, 1, 2, 3]);
        assert_eq!(m.weight, vec![1.0, 1.0, 0.0, 1.0]);
        assert_eq!(m.mean_distance, 0.0);
        assert!((mean_closest_distance(&moved, &q) - 0.125).abs() < 1e-6);
    }
}
