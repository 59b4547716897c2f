//! Sequential RANSAC for rigid motion modes of a flow.
//!
//! The baseline the paper's segmentation module is a learned version of (Yi et al. 2018,
//! "Segmentation"): repeatedly find the rigid motion that most points of P follow under the
//! flow, take its inliers as a part, remove them and search again; stop after
//! [`SeqRansacParams::max_modes`] modes or when fewer than
//! [`SeqRansacParams::stop_fraction`] of the points remain. Leftover points join the mode
//! with the smallest residual, and each segment's motion is refitted on all its points.
//!
//! Hypotheses come from minimal samples of three points (RANSAC, Fischler & Bolles 1981);
//! the second and third points are drawn among the first one's nearest neighbours, which
//! makes all-inlier samples of small parts far more likely than uniform triplets. The best
//! hypothesis of each round is refitted on its inliers once or twice (a local optimisation
//! step, Chum et al. 2003) before its inliers are removed. Beyond the paper's description,
//! two refinements keep the baseline from being a strawman: after the greedy extraction,
//! [`SeqRansacParams::reassign_rounds`] rounds refit every mode on its explained points and
//! give every point the mode of smallest residual (returning boundary points the first mode
//! took greedily), and points no mode explains within the threshold (flow outliers) take
//! the label of their nearest explained neighbour in P rather than a random mode's.
//!
//! Use it when the flow is accurate up to a known noise level: it is fast and exact on
//! clean flows. Its limitations are those the paper reports: one global inlier threshold
//! cannot suit every pair, greedy removal takes boundary points for the first mode, and
//! noisy flows leave small discontinuous pieces. Motions are similarities (P and Q are
//! normalised separately), see [`crate::geometry::motion`].

use pairs::math::{Point3, Real, Vector3};
use pairs::transform::Similarity;
use pairs::{MethodError, PairInput, Prediction, Segmenter};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use crate::geometry::{
    assign_by_residual, fit_motion_indices, fit_motion_sample, moved_points, residual,
    sample_local_triplet, InputError, Neighbours,
};
use crate::labels::reassign_by_motion;
use crate::predict::run_segmenter;

/// Parameters of [`segment_ransac`]; defaults chosen on the validation split's true flow
/// (`examples/sweep.rs`, `reports/baselines_sweep.csv`). The evaluator does not use them as
/// they are: it cross-validates the swept fields per flow source (`reports/tuning/`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeqRansacParams {
    /// Largest residual (Q's normalised units) of an inlier. Default 0.02.
    pub inlier_threshold: Real,
    /// Minimal samples drawn per mode. Default 500.
    pub iterations: usize,
    /// Most modes extracted. Default 10 (the paper's).
    pub max_modes: usize,
    /// Search stops when fewer than this fraction of P's points remain. Default 0.05 (the
    /// paper's).
    pub stop_fraction: Real,
    /// A mode needs at least this fraction of P's points (and three) to be accepted; below
    /// it the search stops. Default 0.02.
    pub min_mode_fraction: Real,
    /// Neighbours a sample's second and third points are drawn from. Default 16.
    pub neighbours: usize,
    /// Rounds of refitting every mode on its points and reassigning every point to the
    /// mode of smallest residual after the greedy extraction (0 is the paper's plain
    /// SeqRANSAC). Default 2: greedy removal gives the first mode the boundary points that
    /// fit both modes within the threshold; these rounds return them.
    pub reassign_rounds: usize,
    /// Seed, mixed with each pair's id. Default 0.
    pub seed: u64,
}

impl Default for SeqRansacParams {
    fn default() -> Self {
        Self {
            inlier_threshold: 0.02,
            iterations: 500,
            max_modes: 10,
            stop_fraction: 0.05,
            min_mode_fraction: 0.02,
            neighbours: 16,
            reassign_rounds: 2,
            seed: 0,
        }
    }
}

/// Why SeqRANSAC could not segment a pair.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SeqRansacError {
    /// The pair or flow is unusable (see [`InputError`]).
    #[error(transparent)]
    Input(#[from] InputError),
    /// No rigid motion is supported by enough points to make a first mode: the flow is
    /// explained by no motion (or P's points are too few or collinear to fit one).
    #[error("no consensus: the best motion explains {support} points, a mode needs {needed}")]
    NoConsensus {
        /// Inliers of the best motion found (0 when none could be fitted).
        support: usize,
        /// Inliers a mode needs (`min_mode_fraction` of the points, at least 3).
        needed: usize,
    },
}

/// The points of `pool` whose residual under `motion` is below `threshold`.
fn inliers(
    p: &[Point3],
    moved: &[Point3],
    pool: &[usize],
    motion: &Similarity,
    threshold: Real,
) -> Vec<usize> {
    pool.iter().copied().filter(|&i| residual(motion, &p[i], &moved[i]) < threshold).collect()
}

/// The best mode among `pool`: its motion and inliers, after local optimisation.
fn best_mode(
    p: &[Point3],
    moved: &[Point3],
    pool: &[usize],
    in_pool: &[bool],
    neighbours: &[Vec<usize>],
    params: &SeqRansacParams,
    rng: &mut ChaCha8Rng,
) -> Option<(Similarity, Vec<usize>)> {
    let mut best: Option<(Similarity, Vec<usize>)> = None;
    for _ in 0..params.iterations {
        let Some(sample) = sample_local_triplet(rng, pool, in_pool, neighbours) else { break };
        let Some(motion) = fit_motion_sample(p, moved, sample) else { continue };
        let support = inliers(p, moved, pool, &motion, params.inlier_threshold);
        if best.as_ref().is_none_or(|(_, b)| support.len() > b.len()) {
            best = Some((motion, support));
        }
    }
    let (mut motion, mut support) = best?;
    for _ in 0..2 {
        let Some(refit) = fit_motion_indices(p, moved, &support) else { break };
        let refined = inliers(p, moved, pool, &refit, params.inlier_threshold);
        if refined.len() < support.len() {
            break;
        }
        (motion, support) = (refit, refined);
    }
    Some((motion, support))
}

/// SeqRANSAC labels of P's points under `flow` (one label per point, ids `0..K`), or
/// [`SeqRansacError::NoConsensus`] when not even a first mode is found.
pub fn segment_ransac(
    p: &[Point3],
    flow: &[Vector3],
    params: &SeqRansacParams,
    seed: u64,
) -> Result<Vec<u32>, SeqRansacError> {
    let n = p.len();
    let moved = moved_points(p, flow);
    let neighbours = Neighbours::build(p).knn_table(p, params.neighbours);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut in_pool = vec![true; n];
    let mut pool: Vec<usize> = (0..n).collect();
    let mut modes: Vec<Similarity> = Vec::new();
    let mut labels = vec![u32::MAX; n];
    let min_support = ((params.min_mode_fraction * n as Real).ceil() as usize).max(3);
    let mut first_support = 0;
    while modes.len() < params.max_modes && pool.len() as Real >= params.stop_fraction * n as Real {
        let Some((motion, support)) =
            best_mode(p, &moved, &pool, &in_pool, &neighbours, params, &mut rng)
        else {
            break;
        };
        if modes.is_empty() {
            first_support = support.len();
        }
        if support.len() < min_support {
            break;
        }
        for &i in &support {
            in_pool[i] = false;
            labels[i] = modes.len() as u32;
        }
        pool.retain(|&i| in_pool[i]);
        modes.push(motion);
    }
    if modes.is_empty() {
        return Err(SeqRansacError::NoConsensus { support: first_support, needed: min_support });
    }
    // Leftovers join the mode of smallest residual (the paper's rule); those that no mode
    // explains within the threshold (flow outliers) take their nearest neighbour's label.
    let nearest = assign_by_residual(p, &moved, &modes);
    let explained: Vec<bool> = (0..n)
        .map(|i| residual(&modes[nearest[i] as usize], &p[i], &moved[i]) < params.inlier_threshold)
        .collect();
    let labels: Vec<u32> =
        labels.iter().zip(nearest).map(|(&l, best)| if l == u32::MAX { best } else { l }).collect();
    Ok(reassign_by_motion(
        p,
        &moved,
        &labels,
        &explained,
        params.inlier_threshold,
        params.reassign_rounds,
    ))
}

/// The SeqRANSAC segmenter (name `"seqransac"`).
#[derive(Debug, Clone, Default)]
pub struct SeqRansac {
    /// Its parameters.
    pub params: SeqRansacParams,
}

impl SeqRansac {
    /// A SeqRANSAC segmenter with the given parameters.
    pub fn with_params(params: SeqRansacParams) -> Self {
        Self { params }
    }
}

impl Segmenter for SeqRansac {
    fn name(&self) -> &str {
        "seqransac"
    }

    fn segment(&self, input: &PairInput, flow: &[Vector3]) -> Result<Prediction, MethodError> {
        run_segmenter(self.name(), input, flow, self.params.seed, |input, flow, seed| {
            segment_ransac(&input.p.points, flow, &self.params, seed)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use pairs::math::Rotation3;
    use rand::Rng;

    #[test]
    fn recovers_a_planted_motion_under_half_outliers() {
        let mut rng = ChaCha8Rng::seed_from_u64(4);
        let p: Vec<Point3> = (0..300)
            .map(|_| {
                Point3::new(
                    rng.random::<Real>() - 0.5,
                    rng.random::<Real>() - 0.5,
                    rng.random::<Real>() * 0.2,
                )
            })
            .collect();
        let truth = Similarity {
            rotation: Rotation3::new(Vector3::new(0.1, 0.5, -0.2)).into_inner(),
            translation: Vector3::new(0.05, 0.1, 0.0),
            scale: 1.0,
        };
        // Even points follow the planted motion, odd points get random flow.
        let flow: Vec<Vector3> = p
            .iter()
            .enumerate()
            .map(|(i, x)| match i % 2 {
                0 => truth.apply(x) - x,
                _ => Vector3::new(rng.random(), rng.random(), rng.random()) - Vector3::repeat(0.5),
            })
            .collect();
        let labels = segment_ransac(&p, &flow, &SeqRansacParams::default(), 1).expect("a mode");
        let planted = labels[0];
        assert!((0..300).step_by(2).all(|i| labels[i] == planted));
        let members: Vec<usize> =
            (0..300).filter(|&i| labels[i] == planted && i % 2 == 0).collect();
        let fit = fit_motion_indices(&p, &moved_points(&p, &flow), &members).expect("well posed");
        assert!(pairs::transform::rotation_error_deg(&fit.rotation, &truth.rotation) < 0.1);
    }

    #[test]
    fn flow_that_no_motion_explains_is_no_consensus() {
        let mut rng = ChaCha8Rng::seed_from_u64(9);
        let p: Vec<Point3> =
            (0..200).map(|_| Point3::new(rng.random(), rng.random(), rng.random())).collect();
        let flow: Vec<Vector3> = (0..200)
            .map(|_| Vector3::new(rng.random(), rng.random(), rng.random()) - Vector3::repeat(0.5))
            .collect();
        let params = SeqRansacParams { min_mode_fraction: 0.2, ..SeqRansacParams::default() };
        match segment_ransac(&p, &flow, &params, 1) {
            Err(SeqRansacError::NoConsensus { support, needed }) => {
                assert_eq!(needed, 40);
                assert!(support < 40, "{support}");
            }
            other => panic!("expected no consensus, got {other:?}"),
        }
    }
}
