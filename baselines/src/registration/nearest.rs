//! Nearest-neighbour flow: every point of P moves to its closest point of Q.
//!
//! The simplest flow baseline: exact where P and Q already overlap, wrong wherever parts
//! moved further than the sampling density, and never smooth. Use it as the floor every
//! flow method must beat.

use pairs::math::{Point3, Vector3};
use pairs::{Method, MethodError, PairInput, Prediction};

use crate::geometry::{InputError, Neighbours};
use crate::predict::run_method;

/// Why the nearest-neighbour flow failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum NearestError {
    /// The pair is unusable (see [`InputError`]).
    #[error(transparent)]
    Input(#[from] InputError),
}

/// The flow taking every point of `p` to its nearest point of `q` (zero if `q` is empty).
pub fn flow_nearest(p: &[Point3], q: &[Point3]) -> Vec<Vector3> {
    let tree = Neighbours::build(q);
    p.iter().map(|x| tree.nearest(x).map_or(Vector3::zeros(), |(j, _)| q[j] - x)).collect()
}

/// The nearest-neighbour flow method (name `"nn"`): one segment.
#[derive(Debug, Clone, Copy, Default)]
pub struct NearestFlow;

impl Method for NearestFlow {
    fn name(&self) -> &str {
        "nn"
    }

    fn predict(&self, input: &PairInput) -> Result<Prediction, MethodError> {
        run_method(self.name(), input, 0, |input, _| {
            let flow = flow_nearest(&input.p.points, &input.q.points);
            Ok::<_, NearestError>((flow, vec![0; input.p.len()]))
        })
    }
}
