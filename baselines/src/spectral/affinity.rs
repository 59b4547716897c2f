//! Rigidity affinities between points under a flow (after Tzionas & Gall 2016,
//! "Reconstructing articulated rigged models from RGB-D videos"): two points of one rigid
//! part keep their Euclidean distance and the angle between their normals when the flow
//! moves them; points of different parts generally do not.

use nalgebra::DMatrix;
use pairs::math::{Point3, Real, Vector3};

use crate::geometry::fit_motion_trimmed;

/// The pair's shared scale between P's and Q's frames (P and Q are normalised separately):
/// the median ratio of moved to original distance over pairs of `samples` at least 0.05
/// apart; 1 when there is no such pair.
pub fn estimate_pair_scale(p: &[Point3], moved: &[Point3], samples: &[usize]) -> Real {
    let mut ratios: Vec<Real> = Vec::new();
    for (a, &i) in samples.iter().enumerate() {
        for &j in &samples[a + 1..] {
            let d = (p[i] - p[j]).norm();
            if d > 0.05 {
                ratios.push((moved[i] - moved[j]).norm() / d);
            }
        }
    }
    if ratios.is_empty() {
        return 1.0;
    }
    let mid = ratios.len() / 2;
    *ratios.select_nth_unstable_by(mid, Real::total_cmp).1
}

/// P's normals carried along by the flow: each normal turned by the rotation of the rigid
/// fit of its neighbourhood's flow ([`fit_motion_trimmed`], so a few flow outliers do not
/// tilt it). Recomputing normals on the moved cloud
/// instead would turn every bit of flow noise into normal noise.
pub fn transport_normals(
    p: &[Point3],
    moved: &[Point3],
    normals: &[Vector3],
    hoods: &[Vec<usize>],
) -> Vec<Vector3> {
    normals
        .iter()
        .enumerate()
        .map(|(i, n)| {
            let members: Vec<usize> = std::iter::once(i).chain(hoods[i].iter().copied()).collect();
            fit_motion_trimmed(p, moved, &members, 0.0).map_or(*n, |fit| fit.rotate(n))
        })
        .collect()
}

/// Unsigned angle between two lines (normals' signs are arbitrary), radians.
fn line_angle(a: &Vector3, b: &Vector3) -> Real {
    a.dot(b).abs().clamp(0.0, 1.0).acos()
}

/// Dense affinity between the points `samples`, `exp(-(dist_change / sigma_distance)^2 -
/// (angle_change / sigma_angle)^2 - (|p_i - p_j| / sigma_space)^2)`, where
/// `dist_change = |scale * |p_i - p_j| - |m_i - m_j||` (m = p + flow) and `angle_change` is
/// the change of the angle between the two points' normals (normals of P, and the same
/// normals carried by the flow, [`transport_normals`]); the last term (beyond Tzionas &
/// Gall, infinite `sigma_space` disables it) keeps far-apart points from being affine only
/// because the flow happens to keep their distance, which lets small parts stand out.
/// Diagonal 1.
#[allow(clippy::too_many_arguments)]
pub fn affinity_flow(
    p: &[Point3],
    moved: &[Point3],
    normals_p: &[Vector3],
    normals_moved: &[Vector3],
    samples: &[usize],
    scale: Real,
    sigma_distance: Real,
    sigma_angle: Real,
    sigma_space: Real,
) -> DMatrix<f64> {
    let m = samples.len();
    let mut w = DMatrix::from_element(m, m, 1.0);
    for a in 0..m {
        for b in a + 1..m {
            let (i, j) = (samples[a], samples[b]);
            let dist =
                (scale * (p[i] - p[j]).norm() - (moved[i] - moved[j]).norm()) / sigma_distance;
            let angle = (line_angle(&normals_p[i], &normals_p[j])
                - line_angle(&normals_moved[i], &normals_moved[j]))
                / sigma_angle;
            let space = (p[i] - p[j]).norm() / sigma_space;
            let value = f64::from(-(dist * dist) - angle * angle - space * space).exp();
            w[(a, b)] = value;
            w[(b, a)] = value;
        }
    }
    w
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rigid_pairs_have_affinity_one_and_stretched_pairs_less() {
        let p = [Point3::origin(), Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)];
        // Points 0 and 1 translate together; point 2 moves away.
        let moved =
            [Point3::new(0.0, 0.0, 1.0), Point3::new(1.0, 0.0, 1.0), Point3::new(0.0, 1.5, 1.0)];
        let normals = [Vector3::z(); 3];
        let w = affinity_flow(
            &p,
            &moved,
            &normals,
            &normals,
            &[0, 1, 2],
            1.0,
            0.1,
            0.3,
            Real::INFINITY,
        );
        assert!((w[(0, 1)] - 1.0).abs() < 1e-9 && w[(1, 0)] == w[(0, 1)]);
        assert!(w[(0, 2)] < 1e-6);
        assert_eq!(estimate_pair_scale(&p, &moved, &[0, 1]), 1.0);
        let doubled: Vec<Point3> = p.iter().map(|x| Point3::from(x.coords * 2.0)).collect();
        assert_eq!(estimate_pair_scale(&p, &doubled, &[0, 1, 2]), 2.0);
    }
}
