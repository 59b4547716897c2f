//! Non-rigid registration under local rigidity, with parts from the node transforms (NRR).
//!
//! After Huang, Adams, Wicke & Guibas 2008 ("Non-rigid registration under isometric
//! deformations"), the paper's NRR row, which reports its own flow and segmentation:
//! 1. its own correspondences: FPFH matches ([`crate::descriptors`]) of farthest-point
//!    samples of P, filtered for geometric consistency by spectral matching (matches that
//!    preserve each other's distances, up to the pair's scale: the isometry assumption);
//! 2. a deformation graph ([`super::graph`]) whose nodes carry rigid transforms, fitted by
//!    iterative non-rigid registration from trimmed rigid ICP: each round takes closest
//!    points in Q (plus the consistent matches, with a weight that decays), then alternates
//!    a linear solve of the node translations and a Procrustes update of each node's
//!    rotation (as-rigid-as-possible local/global steps), with a regulariser asking
//!    neighbouring nodes to agree on each other's positions;
//! 3. parts: the node transforms are clustered by J-Linkage over the points (each point
//!    prefers the node transforms that move it to its deformed position within
//!    [`NrrParams::segment_threshold`]), small parts are dissolved, and the motions are
//!    fitted on NRR's own flow.
//!
//! Departures: Huang et al. cluster correspondences by geodesic consistency on meshes and
//! optimise with a different solver; point clouds here have no mesh, so consistency is
//! Euclidean and the solver is the local/global alternation above.
//!
//! Use it when parts bend smoothly or articulate a little. Limitations (the paper's):
//! closest points pull the wrong way under large articulations, the node clustering
//! under-segments parts whose relative motion is small and over-segments where the fit
//! bends rigid parts.

use nalgebra::{DMatrix, DVector, Matrix3, Vector3 as Vector3d};
use pairs::math::{Point3, Real, Vector3};
use pairs::{Method, MethodError, PairInput, Prediction};

use super::correspondence::match_closest;
use super::graph::{build_graph, to64, DeformationGraph, NodeTransform};
use super::rigid::{register_rigid_icp, IcpParams};
use super::solve::rotation_procrustes;
use crate::descriptors::{match_fpfh, FpfhParams};
use crate::geometry::{sample_farthest_points, InputError, Neighbours};
use crate::jlinkage::{cluster_jaccard, Preferences};
use crate::labels::absorb_small_segments;
use crate::predict::run_method;
use pairs::transform::Similarity;

/// Parameters of [`register_nonrigid_graph`]; the feature weight and part threshold were
/// chosen on the validation split (`examples/sweep.rs`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NrrParams {
    /// Graph nodes. Default 48.
    pub nodes: usize,
    /// Nodes blended per point. Default 4.
    pub influence: usize,
    /// Neighbours per node in the regulariser. Default 6.
    pub graph_neighbours: usize,
    /// Registration rounds (closest points recomputed each round). Default 15.
    pub iterations: usize,
    /// Translation/rotation alternations per round. Default 2.
    pub alternations: usize,
    /// Weight of the rigidity regulariser relative to the mean data term. Default 1.
    pub weight_reg: f64,
    /// Initial weight of the feature matches relative to the closest points; multiplied by
    /// `feature_decay` each round. Default 0.3.
    pub weight_features: f64,
    /// Decay of the feature weight per round. Default 0.7.
    pub feature_decay: f64,
    /// Fraction of closest matches kept each round. Default 0.9.
    pub keep_fraction: Real,
    /// Samples of P matched by descriptor. Default 128.
    pub feature_samples: usize,
    /// Scale (Q's units) of the difference of two matches' distances in the consistency
    /// matrix. Default 0.05.
    pub consistency_threshold: Real,
    /// A match is kept when its spectral-matching score is at least this fraction of the
    /// best match's. Default 0.5.
    pub consistency_fraction: Real,
    /// A node transform explains a point when it moves it to within this of its deformed
    /// position (Q's units). Default 0.03.
    pub segment_threshold: f64,
    /// Parts with fewer than this fraction of P's points are dissolved. Default 0.05.
    pub min_segment_fraction: Real,
    /// Descriptor parameters.
    pub fpfh: FpfhParams,
    /// The rigid initialisation.
    pub icp: IcpParams,
}

impl Default for NrrParams {
    fn default() -> Self {
        Self {
            nodes: 48,
            influence: 4,
            graph_neighbours: 6,
            iterations: 15,
            alternations: 2,
            weight_reg: 1.0,
            weight_features: 0.3,
            feature_decay: 0.7,
            keep_fraction: 0.9,
            feature_samples: 128,
            consistency_threshold: 0.05,
            consistency_fraction: 0.5,
            segment_threshold: 0.03,
            min_segment_fraction: 0.05,
            fpfh: FpfhParams::default(),
            icp: IcpParams::default(),
        }
    }
}

/// Why NRR failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum NrrError {
    /// The pair is unusable (see [`InputError`]).
    #[error(transparent)]
    Input(#[from] InputError),
}

/// NRR's output: P deformed onto Q, and P's segments.
#[derive(Debug, Clone, PartialEq)]
pub struct NrrResult {
    /// P's points after the deformation (Q's frame).
    pub deformed: Vec<Point3>,
    /// Segment of every point of P (ids `0..K`).
    pub segments: Vec<u32>,
}

/// Descriptor matches `(point of P, point of Q)` of samples of P that pass the
/// distance-consistency vote.
fn consistent_matches(
    p: &[Point3],
    q: &[Point3],
    scale: Real,
    params: &NrrParams,
) -> Vec<(usize, usize)> {
    let samples = sample_farthest_points(p, params.feature_samples);
    // Descriptors of the whole clouds (the same neighbourhood scale on both sides), then
    // the samples' matches.
    let matched = match_fpfh(p, q, &params.fpfh);
    let pairs: Vec<(usize, usize)> = samples.iter().map(|&i| (i, matched[i])).collect();
    // Spectral matching (Leordeanu & Hebert 2005): the principal eigenvector of the pairwise
    // consistency matrix scores each match by how consistent it is with the largest
    // mutually consistent group, which plain vote counts (easily won by chance on distances
    // in [0, 1]) are not.
    let sigma = f64::from(params.consistency_threshold.max(1e-6));
    let m = pairs.len();
    let mut consistency = DMatrix::<f64>::zeros(m, m);
    for (x, &(i, a)) in pairs.iter().enumerate() {
        for (y, &(j, b)) in pairs.iter().enumerate().skip(x + 1) {
            let change =
                f64::from((scale * (p[i] - p[j]).norm() - (q[a] - q[b]).norm()).abs()) / sigma;
            if change < 3.0 && i != j && a != b {
                let w = (-change * change).exp();
                consistency[(x, y)] = w;
                consistency[(y, x)] = w;
            }
        }
    }
    let mut score = DVector::<f64>::from_element(m, 1.0);
    for _ in 0..50 {
        let next = &consistency * &score;
        let norm = next.norm();
        if !(norm > 0.0 && norm.is_finite()) {
            return Vec::new();
        }
        score = next / norm;
    }
    let best = score.max();
    pairs
        .into_iter()
        .zip(score.iter())
        .filter(|&(_, &v)| best > 0.0 && v >= f64::from(params.consistency_fraction) * best)
        .map(|(pair, _)| pair)
        .collect()
}

/// One data term: point `index` of P should land on `target` with weight `weight`.
struct Datum {
    index: usize,
    target: Vector3d<f64>,
    weight: f64,
}

/// Solves the node translations with the rotations fixed (one linear system, shared by
/// the three coordinates).
fn solve_translations(
    graph: &DeformationGraph,
    points: &[Vector3d<f64>],
    data: &[Datum],
    transforms: &mut [NodeTransform],
    weight_reg: f64,
) {
    let n = graph.nodes.len();
    let mut a = DMatrix::<f64>::identity(n, n) * 1e-9;
    let mut b = DMatrix::<f64>::zeros(n, 3);
    let data_scale = 1.0 / data.iter().map(|d| d.weight).sum::<f64>().max(1e-12);
    for d in data {
        let blend = &graph.weights[d.index];
        let x = points[d.index];
        let rotated = blend.iter().fold(Vector3d::zeros(), |acc, &(j, w)| {
            acc + (transforms[j].matrix * (x - graph.nodes[j]) + graph.nodes[j]) * w
        });
        let rhs = d.target - rotated;
        let w = d.weight * data_scale;
        for &(j, wj) in blend {
            for &(k, wk) in blend {
                a[(j, k)] += w * wj * wk;
            }
            for c in 0..3 {
                b[(j, c)] += w * wj * rhs[c];
            }
        }
    }
    let reg = weight_reg / graph.edges.len().max(1) as f64;
    for &(j, k) in &graph.edges {
        let e = graph.nodes[k] - graph.nodes[j];
        // t_j - t_k should equal e - R_j e.
        let rhs = e - transforms[j].matrix * e;
        a[(j, j)] += reg;
        a[(k, k)] += reg;
        a[(j, k)] -= reg;
        a[(k, j)] -= reg;
        for c in 0..3 {
            b[(j, c)] += reg * rhs[c];
            b[(k, c)] -= reg * rhs[c];
        }
    }
    if let Some(solution) = a.cholesky().map(|ch| ch.solve(&b)) {
        if solution.iter().all(|v| v.is_finite()) {
            for (j, t) in transforms.iter_mut().enumerate() {
                t.translation = Vector3d::new(solution[(j, 0)], solution[(j, 1)], solution[(j, 2)]);
            }
        }
    }
}

/// Updates each node's rotation with the translations fixed (Procrustes over its
/// regulariser edges and the data terms it influences).
fn solve_rotations(
    graph: &DeformationGraph,
    points: &[Vector3d<f64>],
    data: &[Datum],
    transforms: &mut [NodeTransform],
    weight_reg: f64,
) {
    let mut cov = vec![Matrix3::<f64>::zeros(); graph.nodes.len()];
    let data_scale = 1.0 / data.iter().map(|d| d.weight).sum::<f64>().max(1e-12);
    for d in data {
        for &(j, w) in &graph.weights[d.index] {
            let source = points[d.index] - graph.nodes[j];
            let target = d.target - graph.nodes[j] - transforms[j].translation;
            cov[j] += target * source.transpose() * (w * d.weight * data_scale);
        }
    }
    let reg = weight_reg / graph.edges.len().max(1) as f64;
    for &(j, k) in &graph.edges {
        let source = graph.nodes[k] - graph.nodes[j];
        let target = source + transforms[k].translation - transforms[j].translation;
        cov[j] += target * source.transpose() * reg;
    }
    for (t, c) in transforms.iter_mut().zip(&cov) {
        t.matrix = rotation_procrustes(c);
    }
}

/// Parts from the node transforms, by J-Linkage ([`crate::jlinkage`]) with the node
/// transforms as the hypotheses: each point prefers the transforms that take it (P after
/// the rigid start, `start`) to its deformed position within `threshold`, and points
/// sharing preferences merge. Returns a cluster id per point.
fn cluster_node_transforms(
    graph: &DeformationGraph,
    transforms: &[NodeTransform],
    start: &[Point3],
    deformed: &[Point3],
    threshold: f64,
) -> Vec<u32> {
    let hypotheses: Vec<Similarity> = transforms
        .iter()
        .zip(&graph.nodes)
        .map(|(t, g)| Similarity {
            rotation: t.matrix.cast::<Real>(),
            translation: (g + t.translation - t.matrix * g).cast::<Real>(),
            scale: 1.0,
        })
        .collect();
    let prefs = Preferences::of_points(start, deformed, &hypotheses, threshold as Real);
    cluster_jaccard(&prefs, start.len())
}

/// NRR of P onto Q: the deformed P and its segments.
pub fn register_nonrigid_graph(p: &[Point3], q: &[Point3], params: &NrrParams) -> NrrResult {
    let q_tree = Neighbours::build(q);
    let rigid = register_rigid_icp(p, q, &q_tree, &params.icp);
    let start: Vec<Point3> = p.iter().map(|x| rigid.apply(x)).collect();
    let features = consistent_matches(p, q, rigid.scale, params);
    let graph = build_graph(&start, params.nodes, params.influence, params.graph_neighbours);
    let points: Vec<Vector3d<f64>> = start.iter().map(to64).collect();
    let mut transforms = vec![NodeTransform::identity(); graph.nodes.len()];
    let mut feature_weight = params.weight_features;
    for _ in 0..params.iterations {
        let deformed = graph.deform(&start, &transforms);
        let matches = match_closest(&deformed, &q_tree, params.keep_fraction);
        let closest = matches.weight.iter().filter(|&&w| w > 0.0).count().max(1) as f64;
        let mut data: Vec<Datum> = (0..p.len())
            .filter(|&i| matches.weight[i] > 0.0)
            .map(|i| Datum { index: i, target: to64(&q[matches.target[i]]), weight: 1.0 / closest })
            .collect();
        let per_feature = feature_weight / features.len().max(1) as f64;
        data.extend(features.iter().map(|&(i, a)| Datum {
            index: i,
            target: to64(&q[a]),
            weight: per_feature,
        }));
        for _ in 0..params.alternations {
            solve_translations(&graph, &points, &data, &mut transforms, params.weight_reg);
            solve_rotations(&graph, &points, &data, &mut transforms, params.weight_reg);
        }
        feature_weight *= params.feature_decay;
    }
    let deformed = graph.deform(&start, &transforms);
    let labels =
        cluster_node_transforms(&graph, &transforms, &start, &deformed, params.segment_threshold);
    let min_size = ((params.min_segment_fraction * p.len() as Real).ceil() as usize).max(1);
    let (segments, _) = absorb_small_segments(p, &labels, min_size);
    NrrResult { deformed, segments }
}

/// NRR as a method (name `"nrr"`): its own flow and its own segments.
#[derive(Debug, Clone, Default)]
pub struct Nrr {
    /// Its parameters.
    pub params: NrrParams,
}

impl Nrr {
    /// An NRR method with the given parameters.
    pub fn with_params(params: NrrParams) -> Self {
        Self { params }
    }
}

impl Method for Nrr {
    fn name(&self) -> &str {
        "nrr"
    }

    fn predict(&self, input: &PairInput) -> Result<Prediction, MethodError> {
        run_method(self.name(), input, 0, |input, _| {
            let p = &input.p.points;
            let result = register_nonrigid_graph(p, &input.q.points, &self.params);
            let flow: Vec<Vector3> = result.deformed.iter().zip(p).map(|(d, x)| d - x).collect();
            Ok::<_, NrrError>((flow, result.segments))
        })
    }
}
