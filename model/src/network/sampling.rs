//! Index computations of PointNet++ that need no gradient: farthest point sampling, ball
//! queries and 3-nearest-neighbour interpolation weights, on plain `[f32; 3]` points.
//!
//! Farthest point sampling is `pairs`' one ([`pairs::sampling::farthest_point_sampling`])
//! started at the point farthest from the cloud's centroid instead of at index 0 (the
//! authors' CUDA kernel), so the chosen points, as a set and in order, do not depend on the order of the
//! input points (ties aside): permuting a cloud permutes every per-point output of the
//! network the same way.

/// Why indices could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SamplingError {
    /// More samples asked for than there are points.
    #[error("asked for {wanted} samples of a cloud of {points} points")]
    TooFewPoints {
        /// Samples asked for.
        wanted: usize,
        /// Points in the cloud.
        points: usize,
    },
    /// A point is NaN or infinite.
    #[error("point {0} is not finite")]
    NotFinite(usize),
    /// A training pair has no true flow: a cross-instance pair (XF2F, XF2P).
    #[error("pair {0} has no true flow (a cross-instance pair); training needs SF2F, SF2P or SP2P pairs")]
    NoFlow(String),
    /// A module that runs on every point (`features_on_cloud`, `flow_on_cloud`) was given
    /// only the subsets.
    #[error("the network runs on whole clouds (features_on_cloud or flow_on_cloud) but was given only the subsets")]
    NoClouds,
}

use pairs::math::Point3;
use pairs::sampling::farthest_from_centroid;

/// Squared Euclidean distance of two points.
pub(crate) fn distance2(a: &[f32; 3], b: &[f32; 3]) -> f32 {
    (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)
}

/// Indices of `m` points of `points` chosen by farthest point sampling (see the module
/// docs for the start). Duplicate points are picked last, so `m` up to the cloud's size
/// always succeeds, even when every point is the same.
pub fn farthest_point_sampling(points: &[[f32; 3]], m: usize) -> Result<Vec<usize>, SamplingError> {
    if m > points.len() {
        return Err(SamplingError::TooFewPoints { wanted: m, points: points.len() });
    }
    if let Some(bad) = points.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
        return Err(SamplingError::NotFinite(bad));
    }
    let cloud: Vec<Point3> = points.iter().map(|&p| Point3::from(p)).collect();
    Ok(pairs::sampling::farthest_point_sampling(&cloud, m, farthest_from_centroid(&cloud)))
}

/// For each centre, `k` indices of points within `radius` of it, nearest first; a ball with
/// fewer than `k` points repeats its nearest point, and an empty ball (a centre far from
/// every point) takes the nearest point of the cloud. PointNet++ pads with the first point
/// found in index order instead; nearest-first keeps the result independent of the order.
pub fn ball_query(points: &[[f32; 3]], centres: &[[f32; 3]], radius: f32, k: usize) -> Vec<usize> {
    let r2 = radius * radius;
    let mut out = Vec::with_capacity(centres.len() * k);
    let mut ranked: Vec<(f32, usize)> = Vec::with_capacity(points.len());
    for c in centres {
        ranked.clear();
        ranked.extend(points.iter().enumerate().map(|(i, p)| (distance2(p, c), i)));
        // Ties broken by index keep equal inputs deterministic; a permutation can only
        // reorder exact ties, whose features differ only if the points are duplicates.
        ranked.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let inside = ranked.iter().take(k).take_while(|(d, _)| *d <= r2).count().max(1);
        out.extend((0..k).map(|j| ranked[if j < inside { j } else { 0 }].1));
    }
    out
}

/// For each point of `targets`, its 3 nearest `sources` and inverse-distance weights that
/// sum to 1 (PointNet++'s feature propagation). Needs at least 3 sources.
pub fn three_nn(
    targets: &[[f32; 3]],
    sources: &[[f32; 3]],
) -> Result<(Vec<usize>, Vec<f32>), SamplingError> {
    three_nn_weighted(targets, sources, 1)
}

/// [`three_nn`] with weights `1/d^power` (normalised to sum 1): `power` 1 is [`three_nn`],
/// 2 the weights of the release's `three_interpolate`, which takes the squared distances.
pub fn three_nn_weighted(
    targets: &[[f32; 3]],
    sources: &[[f32; 3]],
    power: i32,
) -> Result<(Vec<usize>, Vec<f32>), SamplingError> {
    if sources.len() < 3 {
        return Err(SamplingError::TooFewPoints { wanted: 3, points: sources.len() });
    }
    let mut indices = Vec::with_capacity(targets.len() * 3);
    let mut weights = Vec::with_capacity(targets.len() * 3);
    for t in targets {
        let mut best = [(f32::INFINITY, 0usize); 3];
        for (i, s) in sources.iter().enumerate() {
            let d = distance2(t, s);
            if d < best[2].0 {
                best[2] = (d, i);
                best.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            }
        }
        // 1e-8 as in the authors' kernel: a target on a source takes (almost) all its weight.
        let inverse = best.map(|(d, _)| {
            if power == 1 {
                1.0 / (d.sqrt() + 1e-8)
            } else {
                1.0 / (d.sqrt().powi(power) + 1e-8)
            }
        });
        let total: f32 = inverse.iter().sum();
        indices.extend(best.map(|(_, i)| i));
        weights.extend(inverse.map(|w| w / total));
    }
    Ok((indices, weights))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(n: usize) -> Vec<[f32; 3]> {
        (0..n).map(|i| [i as f32, 0.0, 0.0]).collect()
    }

    #[test]
    fn fps_spreads_out_and_ignores_order() {
        let points = line(11);
        let chosen = farthest_point_sampling(&points, 3).expect("enough points");
        // Ends first (both are farthest from the centroid; the first wins), then the middle.
        assert_eq!(chosen, vec![0, 10, 5]);
        let reversed: Vec<[f32; 3]> = points.iter().rev().copied().collect();
        let again = farthest_point_sampling(&reversed, 3).expect("enough points");
        let as_points = |c: &[usize], p: &[[f32; 3]]| c.iter().map(|&i| p[i]).collect::<Vec<_>>();
        let mut a = as_points(&chosen, &points);
        let mut b = as_points(&again, &reversed);
        a.sort_by(|x, y| x[0].total_cmp(&y[0]));
        b.sort_by(|x, y| x[0].total_cmp(&y[0]));
        assert_eq!(a, b);
    }

    #[test]
    fn degenerate_clouds_give_indices_or_clear_errors() {
        let same = vec![[1.0, 2.0, 3.0]; 5];
        let mut chosen = farthest_point_sampling(&same, 5).expect("duplicates are fine");
        chosen.sort_unstable();
        assert_eq!(chosen, vec![0, 1, 2, 3, 4]);
        assert_eq!(
            farthest_point_sampling(&same, 6),
            Err(SamplingError::TooFewPoints { wanted: 6, points: 5 })
        );
        assert_eq!(
            farthest_point_sampling(&[[f32::NAN, 0.0, 0.0]], 1),
            Err(SamplingError::NotFinite(0))
        );
        assert!(three_nn(&same, &same[..2]).is_err());
    }

    #[test]
    fn ball_query_pads_with_the_nearest_point() {
        let points = line(10);
        let idx =
            ball_query(&points, &[[0.0, 0.0, 0.0], [4.2, 0.0, 0.0], [100.0, 0.0, 0.0]], 1.5, 4);
        assert_eq!(&idx[0..4], &[0, 1, 0, 0]);
        assert_eq!(&idx[4..8], &[4, 5, 3, 4]);
        // Nothing within the radius: the nearest point of the cloud.
        assert_eq!(&idx[8..12], &[9, 9, 9, 9]);
    }

    #[test]
    fn three_nn_weights_are_inverse_distances() {
        let (idx, w) = three_nn(&[[1.0, 0.0, 0.0]], &line(5)).expect("5 sources");
        assert_eq!(idx, vec![1, 0, 2]);
        assert!((w[0] - 1.0).abs() < 1e-6 && w[1] < 1e-6);
        let (_, w) = three_nn(&[[0.5, 0.0, 0.0]], &line(5)).expect("5 sources");
        assert!((w[0] - w[1]).abs() < 1e-6 && (w.iter().sum::<f32>() - 1.0).abs() < 1e-6);
        assert!((w[0] / w[2] - 3.0).abs() < 1e-4);
    }
}
