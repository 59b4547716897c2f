//! Ground truth of the joints that move the parts of a pair.

use serde::{Deserialize, Serialize};

use crate::math::{Point3, Real, Vector3};
use crate::parts::PartId;

/// How a joint moves its child.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum JointKind {
    /// Rotation about an axis through a pivot; values in radians.
    Revolute,
    /// Translation along an axis; values in object units.
    Prismatic,
}

impl JointKind {
    /// Lower-case name, as written in files.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Revolute => "revolute",
            Self::Prismatic => "prismatic",
        }
    }
}

/// The joint that moves one part of a pair, seen in both clouds.
#[derive(Debug, Clone, PartialEq)]
pub struct JointTruth {
    /// The part this joint moves (relative to its parent part).
    pub part: PartId,
    /// Revolute or prismatic.
    pub kind: JointKind,
    /// Unit axis direction, P's normalised frame.
    pub axis_p: Vector3,
    /// A point on the axis, P's normalised frame (normalised units).
    pub pivot_p: Point3,
    /// Unit axis direction, Q's normalised frame.
    pub axis_q: Vector3,
    /// A point on the axis, Q's normalised frame (normalised units).
    pub pivot_q: Point3,
    /// Joint value in P's state (radians or object units, see [`JointKind`]).
    pub value_p: Real,
    /// Joint value in Q's state (radians or object units, see [`JointKind`]).
    pub value_q: Real,
}
