//! Nearest-neighbour queries on a point cloud through kiddo's immutable k-d tree (which,
//! unlike its mutable tree, accepts any number of points sharing a coordinate).

use std::num::NonZero;

use kiddo::{ImmutableKdTree, SquaredEuclidean};
use pairs::math::{Point3, Real};

/// A k-d tree over a cloud's points, answering nearest and k-nearest queries by index.
pub struct Neighbours {
    tree: ImmutableKdTree<Real, 3>,
    len: usize,
}

impl Neighbours {
    /// Builds the tree over `points` (finite coordinates; may be empty).
    pub fn build(points: &[Point3]) -> Self {
        let coords: Vec<[Real; 3]> = points.iter().map(|p| [p.x, p.y, p.z]).collect();
        Self { tree: ImmutableKdTree::new_from_slice(&coords), len: points.len() }
    }

    /// Number of indexed points.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether no point is indexed.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Index and squared distance of the point nearest to `x`; `None` for an empty cloud.
    pub fn nearest(&self, x: &Point3) -> Option<(usize, Real)> {
        if self.len == 0 {
            return None;
        }
        let hit = self.tree.nearest_one::<SquaredEuclidean>(&[x.x, x.y, x.z]);
        Some((hit.item as usize, hit.distance))
    }

    /// Indices of the `k` points nearest to `x`, nearest first (fewer if the cloud is small).
    pub fn knn(&self, x: &Point3, k: usize) -> Vec<usize> {
        match NonZero::new(k.min(self.len)) {
            Some(k) => self
                .tree
                .nearest_n::<SquaredEuclidean>(&[x.x, x.y, x.z], k)
                .into_iter()
                .map(|hit| hit.item as usize)
                .collect(),
            None => Vec::new(),
        }
    }

    /// For every point of the indexed cloud `points`, its `k` nearest other points.
    pub fn knn_table(&self, points: &[Point3], k: usize) -> Vec<Vec<usize>> {
        points
            .iter()
            .enumerate()
            .map(|(i, x)| self.knn(x, k + 1).into_iter().filter(|&j| j != i).take(k).collect())
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_matches_brute_force_even_on_a_line_of_duplicates() {
        let points: Vec<Point3> =
            (0..200).map(|i| Point3::new((i / 4) as Real * 0.01, 0.0, 0.0)).collect();
        let tree = Neighbours::build(&points);
        let query = Point3::new(0.123, 0.01, 0.0);
        let (i, d2) = tree.nearest(&query).expect("non-empty");
        let best = points.iter().map(|p| (p - query).norm_squared()).fold(Real::MAX, Real::min);
        assert!((d2 - best).abs() < 1e-9 && ((points[i] - query).norm_squared() - best) < 1e-9);
        let table = tree.knn_table(&points, 5);
        assert!(table.iter().enumerate().all(|(i, row)| row.len() == 5 && !row.contains(&i)));
        assert!(Neighbours::build(&[]).nearest(&query).is_none());
        assert_eq!(Neighbours::build(&points[..2]).knn(&query, 9).len(), 2);
    }
}
