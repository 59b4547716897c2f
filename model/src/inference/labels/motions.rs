//! One rigid motion per segment with one scale shared by all of them, fitted to a flow by
//! weighted least squares. A pair's true part motions share one scale (the two clouds'
//! normalisations differ by it, DESIGN.md), and a scale fitted per segment drifts on small
//! segments and compounds over the iterations; the shared one is fitted on every point.

use pairs::math::{Point3, Real, Vector3};
use pairs::transform::{Similarity, UmeyamaFit};

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
    let fits: Vec<Option<UmeyamaFit>> = (0..count)
        .map(|k| {
            let w: Vec<Real> = labels
                .iter()
                .zip(weights)
                .map(|(&l, &w)| if l as usize == k { w } else { 0.0 })
                .collect();
            UmeyamaFit::new(p, &moved, &w)
        })
        .collect();
    let (trace, variance) =
        fits.iter().flatten().fold((0.0, 0.0), |(t, v), f| (t + f.trace, v + f.variance));
    let scale = if variance > 0.0 && trace > 0.0 { trace / variance } else { 1.0 };
    fits.into_iter()
        .map(|fit| fit.map_or_else(Similarity::identity, |f| f.with_scale(scale)))
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
        let labels = pairs::parts::part_segments(&truth.part_p);
        let weights = vec![1.0; labels.len()];
        let fit = fit_motions_shared_scale(
            &input.p.points,
            truth.flow.as_deref().expect("a flow"),
            &labels,
            &weights,
            3,
        );
        for (m, gt) in fit.iter().zip(&truth.motions) {
            assert!((m.rotation - gt.rotation).norm() < 1e-4);
            assert!((m.translation - gt.translation).norm() < 1e-4);
            assert!((m.scale - gt.scale).abs() < 1e-4);
        }
        assert_eq!(fit[2], Similarity::identity());
    }
}
