//! FPFH descriptors and flow by descriptor matching.
//!
//! Fast Point Feature Histograms (Rusu, Blodow & Beetz 2009): for each point and each
//! neighbour, the Darboux frame `u = n_s, v = u x d, w = u x v` of the pair gives three
//! angles (`alpha = v . n_t`, `phi = u . d`, `theta = atan2(w . n_t, u . n_t)`); their
//! 11-bin histograms over the neighbourhood form the SPFH, and the FPFH adds the
//! neighbours' SPFHs weighted by inverse distance. Normals come from local PCA, oriented
//! away from the centroid.
//!
//! The flow method matches every point of P to the point of Q with the nearest descriptor
//! (Euclidean, brute force) and moves it there. It is the hand-crafted stand-in for the
//! paper's 3DMatch and LMVCNN rows, which match learned descriptors the same way; it is
//! named `"fpfh"`, not after them. Limitations (the paper's for those rows, and worse for a
//! hand-crafted descriptor): symmetric and flat regions look alike, nothing makes the flow
//! smooth, and missing data changes the descriptors.

use pairs::math::{Point3, Real, Vector3};
use pairs::{Method, MethodError, PairInput, Prediction};

use crate::geometry::{estimate_normals_pca, InputError, Neighbours};
use crate::predict::run_method;

/// Bins per angle (11, as in PCL); a descriptor has `3 * FPFH_BINS` entries.
pub const FPFH_BINS: usize = 11;
const LEN: usize = 3 * FPFH_BINS;

/// Parameters of [`flow_fpfh`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FpfhParams {
    /// Neighbours of the normals. Default 12.
    pub normal_neighbours: usize,
    /// Neighbours of the histograms. Default 24.
    pub feature_neighbours: usize,
}

impl Default for FpfhParams {
    fn default() -> Self {
        Self { normal_neighbours: 12, feature_neighbours: 24 }
    }
}

/// Why FPFH matching failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum FpfhError {
    /// The pair is unusable (see [`InputError`]).
    #[error(transparent)]
    Input(#[from] InputError),
}

fn bin(value: Real, lo: Real, hi: Real) -> usize {
    (((value - lo) / (hi - lo) * FPFH_BINS as Real) as usize).min(FPFH_BINS - 1)
}

/// The simplified point feature histogram of point `s` over `hood`, each sub-histogram
/// summing to 1 (all zero for an empty neighbourhood).
fn spfh(points: &[Point3], normals: &[Vector3], s: usize, hood: &[usize]) -> [Real; LEN] {
    let mut h = [0.0; LEN];
    let u = normals[s];
    let mut count = 0.0;
    for &t in hood {
        let d = points[t] - points[s];
        let dist = d.norm();
        let v = u.cross(&d);
        if dist < 1e-9 || v.norm() < 1e-9 {
            continue;
        }
        let (d, v) = (d / dist, v / v.norm());
        let w = u.cross(&v);
        let n = normals[t];
        h[bin(v.dot(&n), -1.0, 1.0)] += 1.0;
        h[FPFH_BINS + bin(u.dot(&d), -1.0, 1.0)] += 1.0;
        h[2 * FPFH_BINS
            + bin(w.dot(&n).atan2(u.dot(&n)), -std::f32::consts::PI, std::f32::consts::PI)] += 1.0;
        count += 1.0;
    }
    if count > 0.0 {
        h.iter_mut().for_each(|x| *x /= count);
    }
    h
}

/// The FPFH of every point, over the neighbourhoods `hoods` (indices into `points`).
pub fn describe_fpfh(
    points: &[Point3],
    normals: &[Vector3],
    hoods: &[Vec<usize>],
) -> Vec<[Real; LEN]> {
    let simple: Vec<[Real; LEN]> =
        (0..points.len()).map(|s| spfh(points, normals, s, &hoods[s])).collect();
    (0..points.len())
        .map(|s| {
            let mut f = simple[s];
            let k = hoods[s].len().max(1) as Real;
            for &t in &hoods[s] {
                let dist = (points[t] - points[s]).norm().max(1e-6);
                for (a, b) in f.iter_mut().zip(&simple[t]) {
                    *a += b / (k * dist);
                }
            }
            for part in f.chunks_mut(FPFH_BINS) {
                let total: Real = part.iter().sum();
                if total > 0.0 {
                    part.iter_mut().for_each(|x| *x /= total);
                }
            }
            f
        })
        .collect()
}

/// For every descriptor of `from`, the index of the nearest descriptor of `to` (Euclidean).
pub fn match_descriptors(from: &[[Real; LEN]], to: &[[Real; LEN]]) -> Vec<usize> {
    from.iter()
        .map(|a| {
            let dist =
                |b: &[Real; LEN]| a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum::<Real>();
            (0..to.len()).min_by(|&i, &j| dist(&to[i]).total_cmp(&dist(&to[j]))).unwrap_or(0)
        })
        .collect()
}

/// FPFH descriptors of a cloud with the given parameters.
fn describe_cloud(points: &[Point3], params: &FpfhParams) -> Vec<[Real; LEN]> {
    let tree = Neighbours::build(points);
    let normals = estimate_normals_pca(points, &tree.knn_table(points, params.normal_neighbours));
    describe_fpfh(points, &normals, &tree.knn_table(points, params.feature_neighbours))
}

/// Per point of P, the index of its FPFH match in Q.
pub fn match_fpfh(p: &[Point3], q: &[Point3], params: &FpfhParams) -> Vec<usize> {
    match_descriptors(&describe_cloud(p, params), &describe_cloud(q, params))
}

/// The flow moving every point of P to its FPFH match in Q.
pub fn flow_fpfh(p: &[Point3], q: &[Point3], params: &FpfhParams) -> Vec<Vector3> {
    match_fpfh(p, q, params).into_iter().zip(p).map(|(j, x)| q[j] - x).collect()
}

/// FPFH descriptor matching as a flow method (name `"fpfh"`): one segment.
#[derive(Debug, Clone, Default)]
pub struct FpfhFlow {
    /// Its parameters.
    pub params: FpfhParams,
}

impl Method for FpfhFlow {
    fn name(&self) -> &str {
        "fpfh"
    }

    fn predict(&self, input: &PairInput) -> Result<Prediction, MethodError> {
        run_method(self.name(), input, 0, |input, _| {
            let flow = flow_fpfh(&input.p.points, &input.q.points, &self.params);
            Ok::<_, FpfhError>((flow, vec![0; input.p.len()]))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use pairs::math::Rotation3;

    #[test]
    fn descriptors_are_rotation_invariant_and_normalised() {
        let points: Vec<Point3> = (0..150)
            .map(|i| {
                let (u, v) = ((i % 15) as Real / 15.0 - 0.5, (i / 15) as Real / 10.0 - 0.5);
                Point3::new(u, v, 0.8 * u * u + 0.3 * v * v * v)
            })
            .collect();
        let rot = Rotation3::new(Vector3::new(0.4, 0.1, -0.3));
        let turned: Vec<Point3> = points.iter().map(|x| rot * x).collect();
        let params = FpfhParams::default();
        let (a, b) = (describe_cloud(&points, &params), describe_cloud(&turned, &params));
        for (x, y) in a.iter().zip(&b) {
            assert!((x.iter().sum::<Real>() - 3.0).abs() < 1e-4);
            let change: Real = x.iter().zip(y).map(|(s, t)| (s - t).abs()).sum();
            assert!(change < 0.05, "descriptor changed by {change}");
        }
    }
}
