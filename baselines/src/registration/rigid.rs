//! Rigid ICP, point to point, with trimming.
//!
//! Iterative closest points (Besl & McKay 1992): match every point of the moved P to its
//! closest point of Q, fit the motion that best maps P onto its matches, repeat. Trimming
//! (Chetverikov et al. 2002) fits on the [`IcpParams::keep_fraction`] closest matches only,
//! so parts of P with no counterpart nearby do not drag the fit. The motion is a similarity
//! because P and Q are normalised separately (scale kept in [`crate::geometry::SCALE_RANGE`]).
//! Its flow is `motion(p) - p`: one rigid motion for the whole shape.
//!
//! Use it as the rigid reference every non-rigid method must beat, and as their
//! initialisation. Limitations: local convergence from the identity (both clouds are
//! centred by their normalisation), and no articulation at all.

use pairs::math::{Point3, Real, Vector3};
use pairs::transform::{fit_similarity_weighted, Similarity};
use pairs::{Method, MethodError, PairInput, Prediction};

use super::correspondence::match_closest;
use crate::geometry::{InputError, Neighbours, SCALE_RANGE};
use crate::predict::run_method;

/// Parameters of [`register_rigid_icp`]; the trimming default was chosen on the validation
/// split (`examples/sweep.rs`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IcpParams {
    /// Most iterations. Default 50.
    pub iterations: usize,
    /// Fraction of closest matches fitted each iteration. Default 0.9.
    pub keep_fraction: Real,
    /// Stop when the mean kept distance improves by less than this. Default 1e-6.
    pub tolerance: Real,
    /// Fit a uniform scale too (P and Q are normalised separately). Default true.
    pub with_scale: bool,
}

impl Default for IcpParams {
    fn default() -> Self {
        Self { iterations: 50, keep_fraction: 0.9, tolerance: 1e-6, with_scale: true }
    }
}

/// Why ICP could not register a pair.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum IcpError {
    /// The pair is unusable (see [`InputError`]).
    #[error(transparent)]
    Input(#[from] InputError),
}

/// The motion that trimmed ICP finds from P (`p`) onto Q (`q`, indexed by `q_tree`),
/// starting from the identity; the identity if no fit is ever valid.
pub fn register_rigid_icp(
    p: &[Point3],
    q: &[Point3],
    q_tree: &Neighbours,
    params: &IcpParams,
) -> Similarity {
    let mut motion = Similarity::identity();
    let mut last = Real::MAX;
    for _ in 0..params.iterations {
        let moved: Vec<Point3> = p.iter().map(|x| motion.apply(x)).collect();
        let matches = match_closest(&moved, q_tree, params.keep_fraction);
        if last - matches.mean_distance < params.tolerance {
            break;
        }
        last = matches.mean_distance;
        let targets: Vec<Point3> = matches.target.iter().map(|&j| q[j]).collect();
        match fit_similarity_weighted(p, &targets, &matches.weight, params.with_scale) {
            Some(next)
                if next.is_finite() && (SCALE_RANGE.0..=SCALE_RANGE.1).contains(&next.scale) =>
            {
                motion = next;
            }
            _ => break,
        }
    }
    motion
}

/// Trimmed rigid ICP as a flow method (name `"icp"`): one motion, one segment.
#[derive(Debug, Clone, Default)]
pub struct IcpFlow {
    /// Its parameters.
    pub params: IcpParams,
}

impl IcpFlow {
    /// An ICP flow method with the given parameters.
    pub fn with_params(params: IcpParams) -> Self {
        Self { params }
    }
}

impl Method for IcpFlow {
    fn name(&self) -> &str {
        "icp"
    }

    fn predict(&self, input: &PairInput) -> Result<Prediction, MethodError> {
        run_method(self.name(), input, 0, |input, _| {
            let (p, q) = (&input.p.points, &input.q.points);
            let motion = register_rigid_icp(p, q, &Neighbours::build(q), &self.params);
            let flow: Vec<Vector3> = p.iter().map(|x| motion.apply(x) - x).collect();
            Ok::<_, IcpError>((flow, vec![0; p.len()]))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use pairs::math::Rotation3;

    #[test]
    fn icp_recovers_a_small_rigid_motion() {
        let p: Vec<Point3> = (0..200)
            .map(|i| {
                let (u, v) = ((i % 20) as Real / 20.0 - 0.5, (i / 20) as Real / 10.0 - 0.5);
                Point3::new(u, v, 0.3 * u * u - 0.2 * v)
            })
            .collect();
        let truth = Similarity {
            rotation: Rotation3::new(Vector3::new(0.0, 0.0, 0.1)).into_inner(),
            translation: Vector3::new(0.02, -0.01, 0.0),
            scale: 1.0,
        };
        let q: Vec<Point3> = p.iter().map(|x| truth.apply(x)).collect();
        let params = IcpParams { keep_fraction: 1.0, ..IcpParams::default() };
        let fit = register_rigid_icp(&p, &q, &Neighbours::build(&q), &params);
        assert!(p.iter().all(|x| (fit.apply(x) - truth.apply(x)).norm() < 1e-3));
    }
}
