//! Normals by local PCA: the direction of least variance of each point's neighbourhood,
//! oriented away from the cloud's centroid so that descriptors see consistent signs.

use nalgebra::{Matrix3 as Matrix3d, SymmetricEigen, Vector3 as Vector3d};
use pairs::math::{Point3, Real, Vector3};

/// Unit normal of every point from the covariance of itself and its `neighbourhoods[i]`
/// (indices into `points`), flipped to point away from the centroid. A neighbourhood with
/// no spread gives an arbitrary unit vector, never NaN.
pub fn estimate_normals_pca(points: &[Point3], neighbourhoods: &[Vec<usize>]) -> Vec<Vector3> {
    let to64 = |p: &Point3| Vector3d::new(f64::from(p.x), f64::from(p.y), f64::from(p.z));
    let centroid = points.iter().map(to64).sum::<Vector3d<f64>>() / points.len().max(1) as f64;
    points
        .iter()
        .zip(neighbourhoods)
        .map(|(x, hood)| {
            let members = || std::iter::once(x).chain(hood.iter().map(|&j| &points[j]));
            let count = (hood.len() + 1) as f64;
            let mean = members().map(to64).sum::<Vector3d<f64>>() / count;
            let cov = members().fold(Matrix3d::zeros(), |acc, p| {
                let d = to64(p) - mean;
                acc + d * d.transpose()
            });
            let eigen = SymmetricEigen::new(cov);
            let smallest = eigen.eigenvalues.imin();
            let mut n = eigen.eigenvectors.column(smallest).into_owned();
            let norm = n.norm();
            n = if norm > 1e-12 && norm.is_finite() { n / norm } else { Vector3d::z() };
            if n.dot(&(to64(x) - centroid)) < 0.0 {
                n = -n;
            }
            n.cast::<Real>()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Neighbours;

    #[test]
    fn plane_normals_are_its_axis_and_degenerate_hoods_stay_finite() {
        let plane: Vec<Point3> = (0..100)
            .map(|i| Point3::new((i % 10) as Real * 0.1, (i / 10) as Real * 0.1, 0.3))
            .collect();
        let hoods = Neighbours::build(&plane).knn_table(&plane, 8);
        for n in estimate_normals_pca(&plane, &hoods) {
            assert!((n.z.abs() - 1.0).abs() < 1e-4);
        }
        let same = vec![Point3::new(1.0, 1.0, 1.0); 5];
        let hoods = Neighbours::build(&same).knn_table(&same, 3);
        for n in estimate_normals_pca(&same, &hoods) {
            assert!((n.norm() - 1.0).abs() < 1e-5);
        }
    }
}
