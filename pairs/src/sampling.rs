//! The two samplers every crate shares: farthest point sampling (the virtual scanner's
//! pixels, the baselines' graph nodes and features, the network's PointNet++ centres and
//! input subsets) and area-weighted surface sampling (the generator's objects and the
//! meshes given to `model infer`).
//!
//! **Start rule.** [`farthest_point_sampling`] starts at the index its caller gives. A
//! caller that wants a choice independent of the order of the points (the network, so that
//! permuting a cloud permutes its outputs) passes [`farthest_from_centroid`]; the scanner
//! passes a seeded random index and the baselines index 0. After the start, each new point
//! is the one farthest from those already chosen, the first in index order on ties; points
//! already chosen come last, so exact duplicates are picked before any point repeats.
//!
//! ```
//! use pairs::math::Point3;
//! use pairs::sampling::{farthest_from_centroid, farthest_point_sampling};
//!
//! let line: Vec<Point3> = (0..11).map(|i| Point3::new(i as f32, 0.0, 0.0)).collect();
//! // Both ends are farthest from the centroid; the first wins, then the other end, then the middle.
//! let start = farthest_from_centroid(&line);
//! assert_eq!(farthest_point_sampling(&line, 3, start), vec![0, 10, 5]);
//! ```

use rand::Rng;

use crate::math::{Point3, Real};

/// Indices of `min(n, points.len())` points chosen by farthest point sampling from
/// `start` (see the module docs for the rule), in order of choice. Every index is chosen
/// when `n >= points.len()`, still in farthest-point order. `start` must be an index of
/// `points` unless `points` is empty.
///
/// # Panics
/// When `points` is not empty and `start >= points.len()`.
pub fn farthest_point_sampling(points: &[Point3], n: usize, start: usize) -> Vec<usize> {
    let n = n.min(points.len());
    let mut chosen = Vec::with_capacity(n);
    let mut nearest = vec![Real::INFINITY; points.len()];
    let mut taken = vec![false; points.len()];
    let mut next = start;
    for _ in 0..n {
        chosen.push(next);
        taken[next] = true;
        let latest = points[next];
        let mut best = (0, Real::NEG_INFINITY);
        for (i, ((p, d), &t)) in points.iter().zip(nearest.iter_mut()).zip(&taken).enumerate() {
            *d = d.min((p - latest).norm_squared());
            // Taken points score -1 so that exact duplicates (distance 0) come before them.
            let score = if t { -1.0 } else { *d };
            if score > best.1 {
                best = (i, score);
            }
        }
        next = best.0;
    }
    chosen
}

/// The index of the point farthest from the cloud's centroid, the first on ties; 0 for an
/// empty cloud. As a start for [`farthest_point_sampling`] it makes the chosen points
/// independent of the order of the input (ties aside), where the authors' CUDA kernel
/// starts at index 0.
pub fn farthest_from_centroid(points: &[Point3]) -> usize {
    let n = points.len() as Real;
    let centroid = points.iter().fold(Point3::origin(), |acc, p| acc + p.coords / n);
    let mut best = (0, Real::NEG_INFINITY);
    for (i, p) in points.iter().enumerate() {
        let d = (p - centroid).norm_squared();
        if d > best.1 {
            best = (i, d);
        }
    }
    best.0
}

/// Draws triangles with probability proportional to their area. Areas are summed in `f64`
/// so that the small triangles of a large mesh keep their share; triangles of zero (or
/// negative, or NaN) area are never drawn.
#[derive(Debug, Clone, Default)]
pub struct AreaSampler {
    /// Index (in the caller's order) of each triangle with an area.
    triangles: Vec<usize>,
    /// Running sum of those triangles' areas.
    cumulative: Vec<f64>,
}

impl AreaSampler {
    /// The table of triangles with the given areas, in the caller's order.
    pub fn new(areas: impl IntoIterator<Item = Real>) -> Self {
        let mut sampler = Self::default();
        let mut total = 0.0f64;
        for (i, area) in areas.into_iter().enumerate() {
            let area = f64::from(area);
            if area > 0.0 {
                total += area;
                sampler.triangles.push(i);
                sampler.cumulative.push(total);
            }
        }
        sampler
    }

    /// Total area.
    pub fn total_area(&self) -> f64 {
        self.cumulative.last().copied().unwrap_or(0.0)
    }

    /// The index of a triangle drawn by area, `None` when no triangle has an area.
    pub fn draw<R: Rng + ?Sized>(&self, rng: &mut R) -> Option<usize> {
        let total = self.total_area();
        if total <= 0.0 {
            return None;
        }
        let u = rng.random::<f64>() * total;
        let i = self.cumulative.partition_point(|&c| c <= u).min(self.triangles.len() - 1);
        Some(self.triangles[i])
    }
}

/// A point drawn uniformly on the triangle `a b c` (Osada et al. 2002).
pub fn point_on_triangle<R: Rng + ?Sized>(rng: &mut R, [a, b, c]: [Point3; 3]) -> Point3 {
    let r1 = rng.random::<Real>().sqrt();
    let r2 = rng.random::<Real>();
    Point3::from(a.coords * (1.0 - r1) + b.coords * (r1 * (1.0 - r2)) + c.coords * (r1 * r2))
}

/// Area of the triangle `a b c`.
pub fn triangle_area([a, b, c]: &[Point3; 3]) -> Real {
    (b - a).cross(&(c - a)).norm() * 0.5
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    fn line(n: usize) -> Vec<Point3> {
        (0..n).map(|i| Point3::new(i as Real, 0.0, 0.0)).collect()
    }

    #[test]
    fn farthest_points_follow_the_rule_from_any_start() {
        let points = line(11);
        assert_eq!(farthest_point_sampling(&points, 3, 3), vec![3, 10, 0]);
        assert_eq!(farthest_point_sampling(&points, 4, 0), vec![0, 10, 5, 2]);
        // Asking for more than there are gives every point once, in farthest-point order.
        assert_eq!(farthest_point_sampling(&points[..3], 5, 1), vec![1, 0, 2]);
        assert_eq!(farthest_point_sampling(&[], 3, 0), Vec::<usize>::new());
    }

    #[test]
    fn duplicates_come_before_repeats() {
        let same = vec![Point3::new(1.0, 2.0, 3.0); 5];
        let mut chosen = farthest_point_sampling(&same, 5, farthest_from_centroid(&same));
        chosen.sort_unstable();
        assert_eq!(chosen, vec![0, 1, 2, 3, 4]);
        let grid: Vec<Point3> =
            (0..50).map(|i| Point3::new((i % 7) as Real, (i % 5) as Real, 0.0)).collect();
        let mut chosen = farthest_point_sampling(&grid, 50, 0);
        chosen.sort_unstable();
        chosen.dedup();
        assert_eq!(chosen.len(), 50);
    }

    #[test]
    fn the_centroid_start_ignores_the_order_of_the_points() {
        let points: Vec<Point3> = (0..40)
            .map(|i| {
                let t = i as Real * 0.37;
                Point3::new(t.cos() * (1.0 + 0.1 * t), t.sin(), 0.05 * t)
            })
            .collect();
        let chosen = |cloud: &[Point3]| {
            let mut picked: Vec<[Real; 3]> =
                farthest_point_sampling(cloud, 12, farthest_from_centroid(cloud))
                    .into_iter()
                    .map(|i| cloud[i].coords.into())
                    .collect();
            picked.sort_by(|a, b| a.partial_cmp(b).expect("finite"));
            picked
        };
        let reversed: Vec<Point3> = points.iter().rev().copied().collect();
        assert_eq!(chosen(&points), chosen(&reversed));
        assert_eq!(farthest_from_centroid(&[]), 0);
    }

    #[test]
    fn surface_samples_split_by_area_and_lie_on_their_triangle() {
        let small = [Point3::origin(), Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)];
        let flat = [Point3::origin(), Point3::new(1.0, 0.0, 0.0), Point3::new(2.0, 0.0, 0.0)];
        let big = small.map(|p| Point3::from(p.coords * 2.0 + crate::math::Vector3::z()));
        let triangles = [small, flat, big];
        let sampler = AreaSampler::new(triangles.iter().map(triangle_area));
        assert!((sampler.total_area() - 2.5).abs() < 1e-6);
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let mut on_big = 0;
        for _ in 0..4000 {
            let t = sampler.draw(&mut rng).expect("an area");
            assert_ne!(t, 1, "a triangle without area is never drawn");
            on_big += usize::from(t == 2);
            let p = point_on_triangle(&mut rng, triangles[t]);
            let (scale, z) = if t == 2 { (2.0, 1.0) } else { (1.0, 0.0) };
            assert!((p.z - z).abs() < 1e-6 && p.x >= -1e-6 && p.y >= -1e-6);
            assert!(p.x + p.y <= scale + 1e-5, "{p:?} outside triangle {t}");
        }
        let share = on_big as f64 / 4000.0;
        assert!((share - 0.8).abs() < 0.03, "{share}");
        assert_eq!(AreaSampler::new([0.0, Real::NAN]).draw(&mut rng), None);
    }
}
