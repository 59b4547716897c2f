//! Motion fits on point samples. P and Q are normalised separately, so a part's motion
//! between their frames is a rigid motion times the pair's one shared scale (close to 1):
//! every baseline fits a similarity (Umeyama) and rejects scales outside [`SCALE_RANGE`],
//! which only degenerate samples produce.

use pairs::math::{Point3, Real, Vector3};
use pairs::transform::{fit_similarity_weighted, Similarity};

/// Scales a fitted motion may have; anything outside comes from a degenerate sample.
pub const SCALE_RANGE: (Real, Real) = (0.5, 2.0);

/// Smallest triangle area (normalised units, squared diagonal) of a minimal sample: below
/// it the three points are too close to collinear to fix a rotation.
const MIN_SAMPLE_AREA: Real = 1e-5;

/// `p + flow`, the positions P's points move to.
pub fn moved_points(p: &[Point3], flow: &[Vector3]) -> Vec<Point3> {
    p.iter().zip(flow).map(|(x, f)| x + f).collect()
}

/// The similarity best mapping `src` onto `dst` (least squares), or `None` if the fit is
/// undefined or its scale leaves [`SCALE_RANGE`].
pub fn fit_motion_svd(src: &[Point3], dst: &[Point3]) -> Option<Similarity> {
    let weights = vec![1.0; src.len()];
    fit_similarity_weighted(src, dst, &weights, true)
        .filter(|m| m.is_finite() && (SCALE_RANGE.0..=SCALE_RANGE.1).contains(&m.scale))
}

/// [`fit_motion_svd`] of the points `indices` of `p` onto the same points of `moved`.
pub fn fit_motion_indices(p: &[Point3], moved: &[Point3], indices: &[usize]) -> Option<Similarity> {
    let src: Vec<Point3> = indices.iter().map(|&i| p[i]).collect();
    let dst: Vec<Point3> = indices.iter().map(|&i| moved[i]).collect();
    fit_motion_svd(&src, &dst)
}

/// A robust fit of the points `members`: fitted on all, then three times refitted on those
/// with residual under `max(threshold, 2 * median residual)` (so gross flow outliers among
/// them stop biasing it); `None` if the first fit fails.
pub fn fit_motion_trimmed(
    p: &[Point3],
    moved: &[Point3],
    members: &[usize],
    threshold: Real,
) -> Option<Similarity> {
    let mut fit = fit_motion_indices(p, moved, members)?;
    for _ in 0..3 {
        let mut residuals: Vec<Real> =
            members.iter().map(|&i| residual(&fit, &p[i], &moved[i])).collect();
        let median = *residuals.select_nth_unstable_by(members.len() / 2, Real::total_cmp).1;
        let cut = threshold.max(2.0 * median);
        let kept: Vec<usize> =
            members.iter().copied().filter(|&i| residual(&fit, &p[i], &moved[i]) <= cut).collect();
        match fit_motion_indices(p, moved, &kept) {
            Some(next) if kept.len() >= 3 => fit = next,
            _ => break,
        }
    }
    Some(fit)
}

/// The motion of a minimal sample of three points, or `None` when they are (nearly)
/// collinear in P or their fit is degenerate.
pub fn fit_motion_sample(p: &[Point3], moved: &[Point3], sample: [usize; 3]) -> Option<Similarity> {
    let [a, b, c] = sample.map(|i| p[i]);
    let area = 0.5 * (b - a).cross(&(c - a)).norm();
    (area > MIN_SAMPLE_AREA).then(|| fit_motion_indices(p, moved, &sample)).flatten()
}

/// How far `motion` puts `x` from where the flow moved it (`y`).
pub fn residual(motion: &Similarity, x: &Point3, y: &Point3) -> Real {
    (motion.apply(x) - y).norm()
}

/// For every point, the index of the motion with the smallest residual (0 if none).
pub fn assign_by_residual(p: &[Point3], moved: &[Point3], motions: &[Similarity]) -> Vec<u32> {
    p.iter()
        .zip(moved)
        .map(|(x, y)| {
            motions
                .iter()
                .map(|m| residual(m, x, y))
                .enumerate()
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .map_or(0, |(k, _)| k as u32)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use pairs::math::Rotation3;

    #[test]
    fn samples_recover_a_motion_and_reject_collinear_ones() {
        let rot = Rotation3::new(Vector3::new(0.2, -0.5, 0.3)).into_inner();
        let truth =
            Similarity { rotation: rot, translation: Vector3::new(0.1, 0.0, -0.2), scale: 0.9 };
        let p = [
            Point3::origin(),
            Point3::new(0.3, 0.0, 0.0),
            Point3::new(0.0, 0.2, 0.1),
            Point3::new(0.6, 0.0, 0.0),
        ];
        let moved: Vec<Point3> = p.iter().map(|x| truth.apply(x)).collect();
        let fit = fit_motion_sample(&p, &moved, [0, 1, 2]).expect("well posed");
        assert!(p.iter().zip(&moved).all(|(x, y)| residual(&fit, x, y) < 1e-5));
        assert!(fit_motion_sample(&p, &moved, [0, 1, 3]).is_none());
        let zero = [Point3::origin(); 3];
        assert!(fit_motion_svd(&zero, &zero).is_none_or(|m| m.is_finite()));
        assert_eq!(assign_by_residual(&p, &moved, &[Similarity::identity(), fit]), vec![1; 4]);
        assert_eq!(assign_by_residual(&p, &p, &[fit, Similarity::identity()]), vec![1; 4]);
    }
}
