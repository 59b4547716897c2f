//! Checks of a method's input and output, shared by every baseline: the degenerate inputs
//! that no algorithm can work with are refused here with one typed error, and every
//! prediction is checked for NaN before it is returned.

use pairs::math::{Point3, Vector3};
use pairs::{PairInput, Prediction};

/// Smallest cloud a baseline accepts: three points define a rigid motion.
pub const MIN_POINTS: usize = 3;

/// An input no baseline can work with, or an output that would carry NaN.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum InputError {
    /// A cloud has fewer than three points. Cause: an empty or nearly empty scan. Fix: skip
    /// the pair or sample more points.
    #[error("cloud {cloud} has {points} points; at least {MIN_POINTS} are needed")]
    TooFewPoints {
        /// `"P"` or `"Q"`.
        cloud: &'static str,
        /// Points it has.
        points: usize,
    },
    /// A coordinate or flow vector is NaN or infinite. Cause: a broken loader or flow
    /// source. Fix: clean the input; baselines never guess values.
    #[error("{what} entry {index} is not finite")]
    NotFinite {
        /// `"P"`, `"Q"` or `"flow"`.
        what: &'static str,
        /// First bad entry.
        index: usize,
    },
    /// The flow does not hold one vector per point of P. Cause: a flow computed on another
    /// sampling of P. Fix: recompute the flow on this pair.
    #[error("flow has {flow} vectors but P has {points} points")]
    FlowLength {
        /// Vectors in the flow.
        flow: usize,
        /// Points of P.
        points: usize,
    },
    /// The algorithm produced a non-finite value. Cause: a numerical breakdown on an
    /// extreme input. Fix: report the pair; it is a bug.
    #[error("the prediction's {what} is not finite")]
    NonFiniteOutput {
        /// Which field.
        what: &'static str,
    },
}

fn check_points(cloud: &'static str, points: &[Point3]) -> Result<(), InputError> {
    if points.len() < MIN_POINTS {
        return Err(InputError::TooFewPoints { cloud, points: points.len() });
    }
    match points.iter().position(|p| !p.coords.iter().all(|c| c.is_finite())) {
        Some(index) => Err(InputError::NotFinite { what: cloud, index }),
        None => Ok(()),
    }
}

/// Checks that P and Q each hold at least three finite points.
pub fn check_pair(input: &PairInput) -> Result<(), InputError> {
    check_points("P", &input.p.points)?;
    check_points("Q", &input.q.points)
}

/// Checks the pair, and that `flow` holds one finite vector per point of P.
pub fn check_flow(input: &PairInput, flow: &[Vector3]) -> Result<(), InputError> {
    check_pair(input)?;
    if flow.len() != input.p.len() {
        return Err(InputError::FlowLength { flow: flow.len(), points: input.p.len() });
    }
    match flow.iter().position(|f| !f.iter().all(|c| c.is_finite())) {
        Some(index) => Err(InputError::NotFinite { what: "flow", index }),
        None => Ok(()),
    }
}

/// Returns the prediction if its flow and motions are finite, an error otherwise.
pub fn check_prediction(prediction: Prediction) -> Result<Prediction, InputError> {
    let flow_ok = prediction
        .flow
        .as_ref()
        .is_none_or(|flow| flow.iter().all(|f| f.iter().all(|c| c.is_finite())));
    if !flow_ok {
        return Err(InputError::NonFiniteOutput { what: "flow" });
    }
    if !prediction.motions.iter().all(|m| m.is_finite()) {
        return Err(InputError::NonFiniteOutput { what: "motions" });
    }
    Ok(prediction)
}

#[cfg(test)]
mod tests {
    use super::*;
    use pairs::synthetic::hinge_pair;

    #[test]
    fn bad_inputs_are_named() {
        let pair = hinge_pair("t", 3, 0.5);
        let mut input = pair.input().clone();
        let flow = pair.truth().flow.clone().expect("a flow");
        assert_eq!(check_flow(&input, &flow), Ok(()));
        assert!(matches!(check_flow(&input, &flow[1..]), Err(InputError::FlowLength { .. })));
        let mut nan_flow = flow.clone();
        nan_flow[4].x = f32::NAN;
        assert_eq!(
            check_flow(&input, &nan_flow),
            Err(InputError::NotFinite { what: "flow", index: 4 })
        );
        input.q.points[2].y = f32::INFINITY;
        assert_eq!(check_pair(&input), Err(InputError::NotFinite { what: "Q", index: 2 }));
        input.p.points.truncate(2);
        assert_eq!(check_pair(&input), Err(InputError::TooFewPoints { cloud: "P", points: 2 }));
    }
}
