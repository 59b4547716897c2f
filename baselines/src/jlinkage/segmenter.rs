//! J-Linkage motion segmentation of a flow.
//!
//! After Toldo & Fusiello 2008 ("Robust multiple structures estimation with J-Linkage",
//! ECCV), used for motion segmentation as in the paper's JLC row (Yi et al. 2018 cite Yuan
//! et al. 2016): draw many rigid-motion hypotheses from local minimal samples, describe
//! every point by the binary set of hypotheses that explain its flow, and merge clusters
//! agglomeratively by the Jaccard distance of their sets until no two clusters share a
//! hypothesis. Clusters smaller than [`JLinkageParams::min_segment_fraction`] (outliers,
//! slivers) join their nearest large cluster in P; a final refit-and-reassign round, as in
//! [`crate::ransac`], settles boundary points.
//!
//! Use it when the number of parts is unknown and parts differ in size: it needs no model
//! count. Limitations: one inlier threshold for every pair; parts whose motions differ by
//! less than the threshold near their joint merge ("over-grouping", as the paper notes);
//! the cost grows with the square of the number of points.

use pairs::math::{Point3, Real, Vector3};
use pairs::{MethodError, PairInput, Prediction, Segmenter};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use super::merge::cluster_jaccard;
use super::preference::{sample_hypotheses, Preferences};
use crate::geometry::{moved_points, InputError, Neighbours};
use crate::labels::{absorb_small_segments, reassign_by_motion};
use crate::predict::run_segmenter;

/// Parameters of [`segment_jlinkage`]; defaults chosen on the validation split's true flow
/// (`examples/sweep.rs`, `reports/baselines_sweep.csv`). The evaluator does not use them as
/// they are: it cross-validates the swept fields per flow source (`reports/tuning/`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JLinkageParams {
    /// Largest residual (Q's normalised units) for a hypothesis to explain a point.
    /// Default 0.03.
    pub inlier_threshold: Real,
    /// Motion hypotheses drawn. Default 512.
    pub hypotheses: usize,
    /// Neighbours a sample's second and third points are drawn from. Default 16.
    pub neighbours: usize,
    /// Clusters with fewer than this fraction of P's points are dissolved into their
    /// nearest large cluster. Default 0.03.
    pub min_segment_fraction: Real,
    /// Refit-and-reassign rounds after clustering. Default 1.
    pub reassign_rounds: usize,
    /// Seed, mixed with each pair's id. Default 0.
    pub seed: u64,
}

impl Default for JLinkageParams {
    fn default() -> Self {
        Self {
            inlier_threshold: 0.03,
            hypotheses: 512,
            neighbours: 16,
            min_segment_fraction: 0.03,
            reassign_rounds: 1,
            seed: 0,
        }
    }
}

/// Why J-Linkage could not segment a pair.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum JLinkageError {
    /// The pair or flow is unusable (see [`InputError`]).
    #[error(transparent)]
    Input(#[from] InputError),
    /// No motion hypothesis could be drawn: every sampled triplet of P was degenerate
    /// (collinear or repeated points).
    #[error("no motion hypothesis could be fitted to any sample of the {points} points")]
    NoHypothesis {
        /// Points of P.
        points: usize,
    },
}

/// J-Linkage labels of P's points under `flow` (ids `0..K`), or
/// [`JLinkageError::NoHypothesis`] when no hypothesis can be drawn (collinear or too few
/// points).
pub fn segment_jlinkage(
    p: &[Point3],
    flow: &[Vector3],
    params: &JLinkageParams,
    seed: u64,
) -> Result<Vec<u32>, JLinkageError> {
    let n = p.len();
    let moved = moved_points(p, flow);
    let neighbours = Neighbours::build(p).knn_table(p, params.neighbours);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let hypotheses = sample_hypotheses(
        p,
        &moved,
        &neighbours,
        params.hypotheses,
        params.inlier_threshold,
        &mut rng,
    );
    if hypotheses.is_empty() {
        return Err(JLinkageError::NoHypothesis { points: n });
    }
    let prefs = Preferences::of_points(p, &moved, &hypotheses, params.inlier_threshold);
    let clusters = cluster_jaccard(&prefs, n);
    let min_size = ((params.min_segment_fraction * n as Real).ceil() as usize).max(1);
    let (labels, known) = absorb_small_segments(p, &clusters, min_size);
    Ok(reassign_by_motion(
        p,
        &moved,
        &labels,
        &known,
        params.inlier_threshold,
        params.reassign_rounds,
    ))
}

/// The J-Linkage segmenter (name `"jlc"`).
#[derive(Debug, Clone, Default)]
pub struct JLinkage {
    /// Its parameters.
    pub params: JLinkageParams,
}

impl JLinkage {
    /// A J-Linkage segmenter with the given parameters.
    pub fn with_params(params: JLinkageParams) -> Self {
        Self { params }
    }
}

impl Segmenter for JLinkage {
    fn name(&self) -> &str {
        "jlc"
    }

    fn segment(&self, input: &PairInput, flow: &[Vector3]) -> Result<Prediction, MethodError> {
        run_segmenter(self.name(), input, flow, self.params.seed, |input, flow, seed| {
            segment_jlinkage(&input.p.points, flow, &self.params, seed)
        })
    }
}
