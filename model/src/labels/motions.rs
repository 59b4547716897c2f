//! One rigid motion per segment with one scale shared by all of them, fitted to a flow by
//! weighted least squares. A pair's true part motions share one scale (the two clouds'
//! normalisations differ by it, DESIGN.md), and a scale fitted per segment drifts on small
//! segments and compounds over the iterations; the shared one is fitted on every point.

use nalgebra::{Matrix3 as Matrix3d, Vector3 as Vector3d};
use pairs::math::{Point3, Real, Vector3};
use pairs::transform::Similarity;

/// Per-segment sums of a weighted Umeyama fit.
struct SegmentFit {
    rotation: Matrix3d<f64>,
    mean_src: Vector3d<f64>,
    mean_dst: Vector3d<f64>,
    /// `Σ w σ_i d_i` (the scale numerator) and `Σ w |x - mean|²` (its denominator).
    trace: f64,
    variance: f64,
}

fn fit_segment(src: &[Point3], dst: &[Point3], weights: &[Real]) -> Option<SegmentFit> {
    let to64 = |p: &Point3| Vector3d::new(f64::from(p.x), f64::from(p.y), f64::from(p.z));
    let total: f64 = weights.iter().map(|&w| f64::from(w.max(0.0))).sum();
    if !(total > 0.0 && total.is_finite()) {
        return None;
    }
    let (mut mean_src, mut mean_dst) = (Vector3d::zeros(), Vector3d::zeros());
    for ((s, d), &w) in src.iter().zip(dst).zip(weights) {
        mean_src += to64(s) * f64::from(w.max(0.0));
        mean_dst += to64(d) * f64::from(w.max(0.0));
    }
    mean_src /= total;
    mean_dst /= total;
    let (mut cov, mut variance) = (Matrix3d::zeros(), 0.0);
    for ((s, d), &w) in src.iter().zip(dst).zip(weights) {
        let w = f64::from(w.max(0.0));
        let (cs, cd) = (to64(s) - mean_src, to64(d) - mean_dst);
        cov += cd * cs.transpose() * w;
        variance += cs.norm_squared() * w;
    }
    if !cov.iter().all(|v| v.is_finite()) {
        return None;
    }
    let svd = cov.svd(true, true);
    let (u, v_t) = (svd.u?, svd.v_t?);
    let mut d = Matrix3d::identity();
    if (u * v_t).determinant() < 0.0 {
        d[(2, 2)] = -1.0;
    }
    let trace = svd.singular_values.component_mul(&d.diagonal()).sum();
    Some(SegmentFit { rotation: u * d * v_t, mean_src, mean_dst, trace, variance })
}

/// The motions of segments `0..count` (`labels`, weights per point) mapping `p` onto
/// `p + flow`: rotations and translations per segment, one scale for all (the least-squares
/// optimum given the rotations, `Σ traces / Σ variances`; 1 if degenerate). A segment
/// without weight gets the identity.
pub fn fit_motions_shared_scale(
    p: &[Point3],
    flow: &[Vector3],
    labels: &[u32],
    weights: &[Real],
    count: usize,
) -> Vec<Similarity> {
    let moved: Vec<Point3> = p.iter().zip(flow).map(|(x, f)| x + f).collect();
    let fits: Vec<Option<SegmentFit>> = (0..count)
        .map(|k| {
            let w: Vec<Real> = labels
                .iter()
                .zip(weights)
                .map(|(&l, &w)| if l as usize == k { w } else { 0.0 })
                .collect();
            fit_segment(p, &moved, &w)
        })
        .collect();
    let (trace, variance) =
        fits.iter().flatten().fold((0.0, 0.0), |(t, v), f| (t + f.trace, v + f.variance));
    let scale = if variance > 0.0 && trace > 0.0 { trace / variance } else { 1.0 };
    fits.into_iter()
        .map(|fit| {
            fit.map_or_else(Similarity::identity, |f| Similarity {
                rotation: f.rotation.cast::<Real>(),
                translation: (f.mean_dst - f.rotation * f.mean_src * scale).cast::<Real>(),
                scale: scale as Real,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use pairs::synthetic::hinge_pair;

    #[test]
    fn recovers_the_parts_motions_and_their_shared_scale() {
        let pair = hinge_pair("t", 6, 0.9);
        let (input, truth) = (pair.input(), pair.truth());
        let labels: Vec<u32> = truth.part_p.iter().map(|&l| u32::from(l)).collect();
        let weights = vec![1.0; labels.len()];
        let fit = fit_motions_shared_scale(&input.p.points, &truth.flow, &labels, &weights, 3);
        for (m, gt) in fit.iter().zip(&truth.motions) {
            assert!((m.rotation - gt.rotation).norm() < 1e-4);
            assert!((m.translation - gt.translation).norm() < 1e-4);
            assert!((m.scale - gt.scale).abs() < 1e-4);
        }
        assert_eq!(fit[2], Similarity::identity());
    }
}
