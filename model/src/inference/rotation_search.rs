//! Initialisation by rotation search (the paper's "Initialization" paragraph): P is turned
//! by each of 48 rotations covering SO(3), the flow module predicts a flow for every
//! candidate in one batch of 48, and the candidate with the smallest mean flow magnitude
//! starts the iterative procedure.
//!
//! The rotations are a super-Fibonacci spiral (Alexa, "Super-Fibonacci Spirals: Fast,
//! Low-Discrepancy Sampling of SO(3)", CVPR 2022): for `i = 0..n`, with `s = i + 1/2`,
//! `r = sqrt(s/n)`, `R = sqrt(1 - s/n)`, `α = 2πs/√2`, `β = 2πs/ψ` (ψ = 1.533751168755…,
//! the real root of ψ⁴ = ψ + 4), the unit quaternion `(r sin α, r cos α, R sin β, R cos β)`.
//! It is deterministic, needs no tables and spreads any `n` evenly (the paper says only
//! "uniformly sampled"). For n = 48 every rotation is within [`COVERING_RADIUS_DEG`] of one
//! of the samples (measured on 20,000 random rotations, see the tests): the search's
//! resolution. The candidates are that set turned so that one of them is the identity
//! ([`search_candidates`]).
//!
//! Departure from the paper, for speed on a CPU: candidates are scored on farthest-point
//! subsets of 64 points by the magnitude of the expected displacement under the
//! correspondence module's matching probabilities (`Σ_j M_ij q_j - p_i`), not by the flow
//! module's flow on the full subsets. On 2 shared cores the paper's scoring took 10 s for
//! the 48 candidates, this one about 1.2 s; with the shipped weights (trained with
//! rotations up to 30° only) both found an orientation within the resolution for about
//! half of 12 randomly rotated validation pairs (6 of 12 this way, 4 of 12 with the flow
//! module at 64 points; `examples/rotation_search.rs` reruns it).

use burn::tensor::activation;
use pairs::math::{Matrix3, Real, UnitQuaternion};
use pairs::PairInput;

use crate::network::input::{PairTensors, Prepared};
use crate::network::predict::floats;
use crate::network::sampling::SamplingError;
use crate::network::PartInductionNet;

/// Points of the subsets the search scores candidates on.
pub const SEARCH_POINTS: usize = 64;

/// Candidates of the search (the paper's 48).
pub const SEARCH_ROTATIONS: usize = 48;

/// Largest angle, in degrees, from any rotation to the nearest of the 48 samples (66.4°
/// measured on 20,000 uniformly random rotations, rounded up).
pub const COVERING_RADIUS_DEG: Real = 67.0;

/// `n` rotations of the super-Fibonacci spiral (see the module docs).
pub fn super_fibonacci(n: usize) -> Vec<Matrix3> {
    const PSI: f64 = 1.533_751_168_755_204_3;
    let tau = std::f64::consts::TAU;
    (0..n)
        .map(|i| {
            let s = i as f64 + 0.5;
            let (r, big_r) = ((s / n as f64).sqrt(), (1.0 - s / n as f64).sqrt());
            let (alpha, beta) = (tau * s / std::f64::consts::SQRT_2, tau * s / PSI);
            let q = nalgebra::Quaternion::new(
                (big_r * beta.cos()) as Real,
                (r * alpha.sin()) as Real,
                (r * alpha.cos()) as Real,
                (big_r * beta.sin()) as Real,
            );
            UnitQuaternion::from_quaternion(q).to_rotation_matrix().into_inner()
        })
        .collect()
}

/// The 48 candidates of the search: the super-Fibonacci set turned so that its first
/// element is the identity (`R_0ᵀ R_i`; the geodesic distance on SO(3) is invariant under
/// this, so the covering radius is the same), so that a pair already in a consistent
/// orientation keeps it when the search finds nothing better.
pub fn search_candidates() -> Vec<Matrix3> {
    let set = super_fibonacci(SEARCH_ROTATIONS);
    let first = set[0].transpose();
    set.iter().map(|r| first * r).collect()
}

/// The index of the smallest magnitude (the first of equal ones); 0 when empty.
pub fn pick_rotation(magnitudes: &[Real]) -> usize {
    (0..magnitudes.len())
        .min_by(|&a, &b| magnitudes[a].total_cmp(&magnitudes[b]).then(a.cmp(&b)))
        .unwrap_or(0)
}

/// The outcome of a search.
#[derive(Debug, Clone, PartialEq)]
pub struct RotationSearch {
    /// The chosen rotation of P.
    pub rotation: Matrix3,
    /// Its index among the candidates.
    pub index: usize,
    /// Mean predicted flow magnitude of every candidate.
    pub magnitudes: Vec<Real>,
}

impl PartInductionNet {
    /// Mean flow magnitude on P's correspondence subset for each rotation of P, in one
    /// batch. (Farthest-point sampling depends only on distances, so P's subset rotated is
    /// the rotated P's subset.)
    pub fn flow_magnitudes(
        &self,
        input: &PairInput,
        rotations: &[Matrix3],
    ) -> Result<Vec<Real>, SamplingError> {
        self.flow_magnitudes_with(input, rotations, self.corr_points(), false)
    }

    /// [`Self::flow_magnitudes`] on farthest-point subsets of `points` points instead of the
    /// network's correspondence subsets (fewer points: a faster, coarser ranking); with
    /// `matching_only`, the magnitude of the expected displacement under the correspondence
    /// module's matching probabilities instead of the flow module's flow (no flow module:
    /// about a third of the cost).
    pub fn flow_magnitudes_with(
        &self,
        input: &PairInput,
        rotations: &[Matrix3],
        points: usize,
        matching_only: bool,
    ) -> Result<Vec<Real>, SamplingError> {
        let device = self.device();
        let prep = Prepared::new(input, points, &Matrix3::identity())?;
        // P turned by each rotation, its subsets kept.
        let turned: Vec<Prepared> = rotations
            .iter()
            .map(|r| Prepared {
                p: prep
                    .p
                    .iter()
                    .map(|x| {
                        let v = r * pairs::math::Vector3::new(x[0], x[1], x[2]);
                        [v.x, v.y, v.z]
                    })
                    .collect(),
                ..prep.clone()
            })
            .collect();
        let tensors = PairTensors::new(&turned, self.reads_clouds(), &device); // [rotations, m, 3]
        let flow = if matching_only {
            // The expected displacement under the matching probabilities, Σ_j M_ij q_j - p_i.
            let c = self.correspondences(&tensors)?;
            activation::softmax(c.logits, 2).matmul(tensors.q.clone()) - tensors.p
        // [rotations, m, 3]
        } else {
            self.flow(&tensors)?.flow // [rotations, m, 3] ([rotations, n, 3] on the cloud)
        };
        Ok(floats(flow.powi_scalar(2).sum_dim(2).sqrt().mean_dim(1))) // [rotations, 1, 1]
    }

    /// The search of the module docs over the 48 [`search_candidates`], scored by the
    /// expected displacement under the matching probabilities on subsets of
    /// [`SEARCH_POINTS`] points.
    pub fn search_rotation(&self, input: &PairInput) -> Result<RotationSearch, SamplingError> {
        let candidates = search_candidates();
        let points = SEARCH_POINTS.min(self.corr_points());
        let magnitudes = self.flow_magnitudes_with(input, &candidates, points, true)?;
        let index = pick_rotation(&magnitudes);
        Ok(RotationSearch { rotation: candidates[index], index, magnitudes })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use pairs::math::Point3;
    use pairs::transform::rotation_error_deg;
    use rand::{Rng, SeedableRng};

    fn random_rotation(rng: &mut rand_chacha::ChaCha8Rng) -> Matrix3 {
        // Uniform on SO(3): a normalised 4D Gaussian-like direction (Shoemake's method).
        let (u1, u2, u3): (f32, f32, f32) = (rng.random(), rng.random(), rng.random());
        let tau = std::f32::consts::TAU;
        let q = nalgebra::Quaternion::new(
            (1.0 - u1).sqrt() * (tau * u2).sin(),
            (1.0 - u1).sqrt() * (tau * u2).cos(),
            u1.sqrt() * (tau * u3).sin(),
            u1.sqrt() * (tau * u3).cos(),
        );
        UnitQuaternion::from_quaternion(q).to_rotation_matrix().into_inner()
    }

    fn nearest_deg(set: &[Matrix3], r: &Matrix3) -> Real {
        set.iter().map(|s| rotation_error_deg(s, r)).fold(Real::INFINITY, Real::min)
    }

    #[test]
    fn the_samples_are_rotations_and_cover_so3() {
        let set = super_fibonacci(SEARCH_ROTATIONS);
        assert_eq!(set.len(), 48);
        let candidates = search_candidates();
        assert!((candidates[0] - Matrix3::identity()).amax() < 1e-6);
        for (i, j) in [(1, 2), (5, 30), (0, 47)] {
            let (a, b) = (
                rotation_error_deg(&set[i], &set[j]),
                rotation_error_deg(&candidates[i], &candidates[j]),
            );
            assert!((a - b).abs() < 1e-2, "distances are kept: {a} vs {b}");
        }
        for r in &set {
            assert!((r.transpose() * r - Matrix3::identity()).amax() < 1e-5);
            assert!((r.determinant() - 1.0).abs() < 1e-5);
        }
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(4);
        let worst =
            (0..20_000).map(|_| nearest_deg(&set, &random_rotation(&mut rng))).fold(0.0, Real::max);
        assert!(worst <= COVERING_RADIUS_DEG, "covering radius {worst}°");
        assert!(worst > COVERING_RADIUS_DEG - 8.0, "the documented radius is tight: {worst}°");
    }

    #[test]
    fn picks_the_smallest_magnitude_first_on_ties() {
        assert_eq!(pick_rotation(&[0.3, 0.1, 0.2, 0.1]), 1);
        assert_eq!(pick_rotation(&[]), 0);
    }

    /// The selection logic with a flow-magnitude stub: a perfect flow module, whose flow
    /// from each turned P to Q is the true one (`T x - R x` per point). A chamfer stub is
    /// not used: on coarse samples it prefers axis-permuting rotations of box-like shapes.
    #[test]
    fn a_perfect_flow_stub_recovers_a_global_rotation_within_the_resolution() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(8);
        // Points spread evenly in all directions (a ball): then a candidate's magnitude grows
        // with its angle to the truth alone, so the search must find the nearest sample. (On
        // a long box the magnitude also depends on the axis, and the pick can sit a few
        // degrees beyond the covering radius.)
        let p: Vec<Point3> = std::iter::repeat_with(|| {
            let (x, y, z): (f32, f32, f32) = (rng.random(), rng.random(), rng.random());
            Point3::new(x - 0.5, y - 0.5, z - 0.5)
        })
        .filter(|x| x.coords.norm() < 0.5)
        .take(400)
        .collect();
        let set = super_fibonacci(SEARCH_ROTATIONS);
        for _ in 0..50 {
            let truth = random_rotation(&mut rng);
            let magnitudes: Vec<Real> = set
                .iter()
                .map(|r| {
                    let total: Real =
                        p.iter().map(|x| (truth * x.coords - r * x.coords).norm()).sum();
                    total / p.len() as Real
                })
                .collect();
            let error = rotation_error_deg(&set[pick_rotation(&magnitudes)], &truth);
            assert!(error <= COVERING_RADIUS_DEG, "{error}° from the true rotation");
        }
    }
}
