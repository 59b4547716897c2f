//! Embedded deformation (ED) fitted to Q with ICP-style correspondences.
//!
//! After Sumner, Schmid & Pauly 2007 ("Embedded deformation for shape manipulation"), the
//! paper's ED row: a deformation graph ([`super::graph`]) of nodes with affine transforms
//! `(A_j, t_j)`; every point moves by the blend of its nearest nodes' transforms. The
//! energy is `w_fit E_fit + w_reg E_reg + w_rot E_rot`, each term a mean over its
//! residuals: `E_rot` pushes each `A_j` towards a rotation (orthogonal unit columns),
//! `E_reg` asks neighbouring nodes to agree on where they put each other, `E_fit` pulls the
//! deformed points onto their closest points of Q. As in non-rigid ICP, the closest points
//! are recomputed after each round of Gauss-Newton steps, and the whole fit starts from
//! trimmed rigid ICP ([`super::rigid`]), whose similarity is applied to P first (so the
//! nodes' affine maps stay near rotations even though P and Q have different scales).
//!
//! Use it for flows of smooth, mostly isometric deformations. Limitations (the paper's):
//! nothing keeps parts rigid, closest points pull the wrong way when the articulation is
//! large, and missing data lets the graph wander.

use nalgebra::Vector3 as Vector3d;
use pairs::math::{Point3, Real, Vector3};
use pairs::{Method, MethodError, PairInput, Prediction};

use super::correspondence::match_closest;
use super::graph::{build_graph, to64, DeformationGraph, NodeTransform};
use super::rigid::{register_rigid_icp, IcpParams};
use super::solve::NormalEquations;
use crate::geometry::{InputError, Neighbours};
use crate::predict::run_method;

/// Parameters of [`register_embedded_deformation`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdParams {
    /// Graph nodes. Default 48.
    pub nodes: usize,
    /// Nodes blended per point. Default 4 (Sumner et al.'s k).
    pub influence: usize,
    /// Neighbours per node in the regulariser. Default 6.
    pub graph_neighbours: usize,
    /// Closest-point rounds. Default 10.
    pub iterations: usize,
    /// Gauss-Newton steps per round. Default 2.
    pub gauss_newton_steps: usize,
    /// Weight of the fit to Q. Default 1.
    pub weight_fit: f64,
    /// Weight of the neighbour-agreement term. Default 0.1.
    pub weight_reg: f64,
    /// Weight of the rotation term. Default 0.1.
    pub weight_rot: f64,
    /// Fraction of closest matches kept each round. Default 0.9.
    pub keep_fraction: Real,
    /// The rigid initialisation.
    pub icp: IcpParams,
}

impl Default for EdParams {
    fn default() -> Self {
        Self {
            nodes: 48,
            influence: 4,
            graph_neighbours: 6,
            iterations: 10,
            gauss_newton_steps: 2,
            weight_fit: 1.0,
            weight_reg: 0.1,
            weight_rot: 0.1,
            keep_fraction: 0.9,
            icp: IcpParams::default(),
        }
    }
}

/// Why embedded deformation failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum EdError {
    /// The pair is unusable (see [`InputError`]).
    #[error(transparent)]
    Input(#[from] InputError),
}

/// Unknown index of entry `(row, col)` of node `j`'s matrix, or of its translation `row`.
fn matrix_var(j: usize, row: usize, col: usize) -> usize {
    12 * j + 3 * col + row
}
fn translation_var(j: usize, row: usize) -> usize {
    12 * j + 9 + row
}

/// Normal equations of the ED energy at `transforms`, for `points` (P after the rigid
/// initialisation) with targets `targets` and weights `weights`.
fn energy_equations(
    graph: &DeformationGraph,
    transforms: &[NodeTransform],
    points: &[Vector3d<f64>],
    targets: &[Vector3d<f64>],
    weights: &[Real],
    params: &EdParams,
) -> NormalEquations {
    let mut eq = NormalEquations::new(12 * graph.nodes.len());
    let kept = weights.iter().filter(|&&w| w > 0.0).count().max(1) as f64;
    for ((x, y), (blend, &w)) in points.iter().zip(targets).zip(graph.weights.iter().zip(weights)) {
        if w <= 0.0 {
            continue;
        }
        let moved = blend.iter().fold(Vector3d::zeros(), |acc, &(j, b)| {
            acc + transforms[j].apply(&graph.nodes[j], x) * b
        });
        for r in 0..3 {
            let mut row = Vec::with_capacity(4 * blend.len());
            for &(j, b) in blend {
                let d = x - graph.nodes[j];
                row.extend((0..3).map(|c| (matrix_var(j, r, c), b * d[c])));
                row.push((translation_var(j, r), b));
            }
            eq.add(&row, moved[r] - y[r], params.weight_fit * f64::from(w) / kept);
        }
    }
    let edges = graph.edges.len().max(1) as f64;
    for &(j, k) in &graph.edges {
        let e = graph.nodes[k] - graph.nodes[j];
        let residual = transforms[j].apply(&graph.nodes[j], &graph.nodes[k])
            - graph.nodes[k]
            - transforms[k].translation;
        for r in 0..3 {
            let mut row: Vec<(usize, f64)> = (0..3).map(|c| (matrix_var(j, r, c), e[c])).collect();
            row.push((translation_var(j, r), 1.0));
            row.push((translation_var(k, r), -1.0));
            eq.add(&row, residual[r], params.weight_reg / edges);
        }
    }
    let nodes = graph.nodes.len().max(1) as f64;
    for (j, t) in transforms.iter().enumerate() {
        let a = &t.matrix;
        for c1 in 0..3 {
            for c2 in c1..3 {
                let value = a.column(c1).dot(&a.column(c2)) - if c1 == c2 { 1.0 } else { 0.0 };
                let mut row = Vec::with_capacity(6);
                for r in 0..3 {
                    row.push((matrix_var(j, r, c1), a[(r, c2)]));
                    row.push((matrix_var(j, r, c2), a[(r, c1)]));
                }
                eq.add(&row, value, params.weight_rot / nodes);
            }
        }
    }
    eq
}

/// P deformed onto Q by embedded deformation (after the rigid ICP initialisation).
pub fn register_embedded_deformation(p: &[Point3], q: &[Point3], params: &EdParams) -> Vec<Point3> {
    let q_tree = Neighbours::build(q);
    let rigid = register_rigid_icp(p, q, &q_tree, &params.icp);
    let start: Vec<Point3> = p.iter().map(|x| rigid.apply(x)).collect();
    let graph = build_graph(&start, params.nodes, params.influence, params.graph_neighbours);
    let points: Vec<Vector3d<f64>> = start.iter().map(to64).collect();
    let mut transforms = vec![NodeTransform::identity(); graph.nodes.len()];
    for _ in 0..params.iterations {
        let deformed = graph.deform(&start, &transforms);
        let matches = match_closest(&deformed, &q_tree, params.keep_fraction);
        let targets: Vec<Vector3d<f64>> = matches.target.iter().map(|&j| to64(&q[j])).collect();
        for _ in 0..params.gauss_newton_steps {
            let eq =
                energy_equations(&graph, &transforms, &points, &targets, &matches.weight, params);
            let Some(step) = eq.step(1e-9) else { break };
            for (j, t) in transforms.iter_mut().enumerate() {
                for r in 0..3 {
                    for c in 0..3 {
                        t.matrix[(r, c)] += step[matrix_var(j, r, c)];
                    }
                    t.translation[r] += step[translation_var(j, r)];
                }
            }
        }
    }
    graph.deform(&start, &transforms)
}

/// Embedded deformation as a flow method (name `"ed"`): one segment.
#[derive(Debug, Clone, Default)]
pub struct EmbeddedDeformation {
    /// Its parameters.
    pub params: EdParams,
}

impl EmbeddedDeformation {
    /// An ED flow method with the given parameters.
    pub fn with_params(params: EdParams) -> Self {
        Self { params }
    }
}

impl Method for EmbeddedDeformation {
    fn name(&self) -> &str {
        "ed"
    }

    fn predict(&self, input: &PairInput) -> Result<Prediction, MethodError> {
        run_method(self.name(), input, 0, |input, _| {
            let p = &input.p.points;
            let deformed = register_embedded_deformation(p, &input.q.points, &self.params);
            let flow: Vec<Vector3> = deformed.iter().zip(p).map(|(d, x)| d - x).collect();
            Ok::<_, EdError>((flow, vec![0; p.len()]))
        })
    }
}
