//! Farthest point sampling: each new point is the one farthest from those already chosen,
//! which spreads a scan's points evenly over what the camera saw.

use pairs::math::{Point3, Real};

/// Indices of `n` points of `points` chosen by farthest point sampling from `start`; all
/// indices (in order of choice) if there are at most `n` points.
pub fn farthest_point_sampling(points: &[Point3], n: usize, start: usize) -> Vec<usize> {
    if points.len() <= n {
        return (0..points.len()).collect();
    }
    let mut chosen = Vec::with_capacity(n);
    let mut nearest = vec![Real::INFINITY; points.len()];
    let mut current = start;
    for _ in 0..n {
        chosen.push(current);
        let c = points[current];
        let mut best = (0, -1.0);
        for (i, (p, d)) in points.iter().zip(nearest.iter_mut()).enumerate() {
            *d = d.min((p - c).norm_squared());
            if *d > best.1 {
                best = (i, *d);
            }
        }
        current = best.0;
    }
    chosen
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn picks_the_extremes_of_a_line_first() {
        let points: Vec<Point3> = (0..11).map(|i| Point3::new(i as Real, 0.0, 0.0)).collect();
        assert_eq!(farthest_point_sampling(&points, 3, 3), vec![3, 10, 0]);
        assert_eq!(farthest_point_sampling(&points[..2], 3, 0), vec![0, 1]);
    }

    #[test]
    fn never_repeats_a_point() {
        let points: Vec<Point3> =
            (0..50).map(|i| Point3::new((i % 7) as Real, (i % 5) as Real, 0.0)).collect();
        let mut chosen = farthest_point_sampling(&points, 35, 0);
        chosen.sort_unstable();
        chosen.dedup();
        assert_eq!(chosen.len(), 35);
    }
}
