//! Spectral clustering of a flow by rigidity affinities.
//!
//! After Tzionas & Gall 2016 ("Reconstructing articulated rigged models from RGB-D
//! videos"), the paper's SC row: two points of one rigid part keep their distance and the
//! angle between their normals when the flow moves them. The affinity of every pair of
//! points ([`affinity_flow`]) feeds normalised spectral clustering (Ng, Jordan & Weiss
//! 2001): the number of clusters comes from the largest eigengap among the first
//! [`SpectralParams::max_clusters`] eigenvalues, the row-normalised eigenvectors are
//! clustered by k-means. Normals come from local PCA on P; their images under the flow are
//! P's normals turned by the local rigid fit of each neighbourhood's flow.
//!
//! The dense eigen-decomposition is cubic in the number of points, so the clustering runs
//! on [`SpectralParams::samples`] farthest-point samples (as the paper's network works on
//! 128- or 256-point subsets) and the other points take their nearest sample's label.
//! Samples whose affinity degree is far below the median (flow outliers, affine to nothing)
//! are left out of the eigen-decomposition (each would otherwise be a near-isolated block
//! with an eigenvalue near 1, inflating the eigengap's count) and relabelled from their
//! neighbours; segments smaller than [`SpectralParams::min_segment_fraction`] are dissolved
//! the same way, and one refit-and-reassign round settles the boundary.
//!
//! Use it when the flow is smooth but its noise level is unknown: it needs no inlier
//! threshold, only two soft scales. Limitations: as the paper notes it looks at motion
//! cues only and can over-group parts whose relative motion is small; the eigengap picks
//! too few clusters when a small part is barely affine to the rest.

use pairs::math::{Point3, Real, Vector3};
use pairs::{MethodError, PairInput, Prediction, Segmenter};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use super::affinity::{affinity_flow, estimate_pair_scale, transport_normals};
use super::embedding::embed_spectral;
use super::kmeans::cluster_kmeans;
use crate::geometry::{
    estimate_normals_pca, moved_points, sample_farthest_points, InputError, Neighbours,
};
use crate::labels::{absorb_small_segments, fill_from_nearest, reassign_by_motion};
use crate::predict::run_segmenter;

/// Parameters of [`segment_spectral`]; defaults chosen on the validation split's true flow
/// (`examples/sweep.rs`, `reports/baselines_sweep.csv`). The evaluator does not use them as
/// they are: it cross-validates the swept fields per flow source (`reports/tuning/`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpectralParams {
    /// Scale (Q's normalised units) of the change of a pair's distance. Default 0.01.
    pub sigma_distance: Real,
    /// Scale (radians) of the change of the angle between a pair's normals. Default 0.1.
    pub sigma_angle: Real,
    /// Scale (P's normalised units) of the distance between two points, beyond Tzionas &
    /// Gall (infinity disables it). Default 0.3.
    pub sigma_space: Real,
    /// Most clusters the eigengap may choose. Default 10 (the paper's part limit).
    pub max_clusters: usize,
    /// Farthest-point samples clustered. Default 256.
    pub samples: usize,
    /// Neighbours of the local-PCA normals. Default 12.
    pub normal_neighbours: usize,
    /// Constant added to the affinity, as a fraction of the mean degree. Default 0.01.
    pub regularisation: f64,
    /// Samples whose degree is below this fraction of the median are treated as flow
    /// outliers. Default 0.1.
    pub outlier_degree: f64,
    /// Segments with fewer than this fraction of P's points are dissolved. Default 0.03.
    pub min_segment_fraction: Real,
    /// Refit-and-reassign rounds after clustering (beyond the paper: as for SeqRANSAC and
    /// JLC, it settles boundary points whose normals mix both parts). Default 1.
    pub refine_rounds: usize,
    /// Largest residual (Q's normalised units) of a point explained by a segment's motion
    /// in those rounds. Default 0.03.
    pub refine_threshold: Real,
    /// k-means restarts. Default 8.
    pub kmeans_restarts: usize,
    /// Seed, mixed with each pair's id. Default 0.
    pub seed: u64,
}

impl Default for SpectralParams {
    fn default() -> Self {
        Self {
            sigma_distance: 0.01,
            sigma_angle: 0.1,
            sigma_space: 0.3,
            max_clusters: 10,
            samples: 256,
            normal_neighbours: 12,
            regularisation: 0.01,
            outlier_degree: 0.1,
            min_segment_fraction: 0.03,
            refine_rounds: 1,
            refine_threshold: 0.03,
            kmeans_restarts: 8,
            seed: 0,
        }
    }
}

/// Why spectral clustering could not segment a pair.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SpectralError {
    /// The pair or flow is unusable (see [`InputError`]).
    #[error(transparent)]
    Input(#[from] InputError),
}

/// Spectral-clustering labels of P's points under `flow` (ids `0..K`).
pub fn segment_spectral(
    p: &[Point3],
    flow: &[Vector3],
    params: &SpectralParams,
    seed: u64,
) -> Vec<u32> {
    let n = p.len();
    let moved = moved_points(p, flow);
    let hoods = Neighbours::build(p).knn_table(p, params.normal_neighbours);
    let normals_p = estimate_normals_pca(p, &hoods);
    let normals_moved = transport_normals(p, &moved, &normals_p, &hoods);
    let samples = sample_farthest_points(p, params.samples);
    let scale = estimate_pair_scale(p, &moved, &samples);
    let w = affinity_flow(
        p,
        &moved,
        &normals_p,
        &normals_moved,
        &samples,
        scale,
        params.sigma_distance,
        params.sigma_angle,
        params.sigma_space,
    );
    // Flow outliers are affine to almost nothing; left in, each would be a near-isolated
    // block with an eigenvalue near 1 and the eigengap would count them as clusters.
    let degrees: Vec<f64> = w.row_iter().map(|row| row.sum()).collect();
    let median = {
        let mut sorted = degrees.clone();
        sorted.sort_by(f64::total_cmp);
        sorted.get(sorted.len() / 2).copied().unwrap_or(0.0)
    };
    let kept: Vec<usize> =
        (0..samples.len()).filter(|&a| degrees[a] >= params.outlier_degree * median).collect();
    let w = w.select_rows(&kept).select_columns(&kept);
    let embedding = embed_spectral(&w, params.max_clusters, params.regularisation);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let sample_labels =
        cluster_kmeans(&embedding.rows, embedding.clusters, params.kmeans_restarts, 100, &mut rng);
    let (mut labels, mut known) = (vec![0u32; n], vec![false; n]);
    for (&a, &label) in kept.iter().zip(&sample_labels) {
        labels[samples[a]] = label;
        known[samples[a]] = true;
    }
    let labels = fill_from_nearest(p, &labels, &known);
    let min_size = ((params.min_segment_fraction * n as Real).ceil() as usize).max(1);
    let (labels, known) = absorb_small_segments(p, &labels, min_size);
    reassign_by_motion(p, &moved, &labels, &known, params.refine_threshold, params.refine_rounds)
}

/// The spectral-clustering segmenter (name `"sc"`).
#[derive(Debug, Clone, Default)]
pub struct Spectral {
    /// Its parameters.
    pub params: SpectralParams,
}

impl Spectral {
    /// A spectral-clustering segmenter with the given parameters.
    pub fn with_params(params: SpectralParams) -> Self {
        Self { params }
    }
}

impl Segmenter for Spectral {
    fn name(&self) -> &str {
        "sc"
    }

    fn segment(&self, input: &PairInput, flow: &[Vector3]) -> Result<Prediction, MethodError> {
        run_segmenter(self.name(), input, flow, self.params.seed, |input, flow, seed| {
            Ok::<_, SpectralError>(segment_spectral(&input.p.points, flow, &self.params, seed))
        })
    }
}
