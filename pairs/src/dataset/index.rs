//! `index.csv`: one row per pair, for quick filtering with polars or pandas.

use serde::{Deserialize, Serialize};

use crate::joints::JointKind;
use crate::pair::Pair;
use crate::set::Set;
use crate::transform::rotation_error_deg;

/// One row of `index.csv`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct IndexRow {
    /// Pair id.
    pub id: String,
    /// `SF2F`, `SF2P` or `SP2P`.
    pub kind: String,
    /// Object category.
    pub category: String,
    /// Object index within the dataset.
    pub object_id: u32,
    /// Index of P's articulation state.
    pub articulation_p: u32,
    /// Index of Q's articulation state.
    pub articulation_q: u32,
    /// Points in P.
    pub n_p: usize,
    /// Points in Q.
    pub n_q: usize,
    /// Number of parts, base included.
    pub num_parts: usize,
    /// Joint kinds of the moving parts, `;`-separated, in part order.
    pub joint_types: String,
    /// Largest change of a revolute joint between the states, degrees (0 if none).
    pub max_joint_rotation_deg: f32,
    /// Largest change of a prismatic joint between the states, P's normalised units (0 if none).
    pub max_joint_translation: f32,
    /// Largest rotation of a part relative to the base part (part 0), degrees.
    pub max_relative_rotation_deg: f32,
}

impl IndexRow {
    /// The row describing a pair.
    pub fn of(pair: &Pair) -> Self {
        let (input, truth, prov) = (pair.input(), pair.truth(), pair.provenance());
        let change = |kind: JointKind| {
            truth
                .joints
                .iter()
                .filter(|j| j.kind == kind)
                .map(|j| (j.value_q - j.value_p).abs())
                .fold(0.0f32, f32::max)
        };
        Self {
            id: input.id.clone(),
            kind: input.kind.as_str().into(),
            category: prov.category.clone(),
            object_id: prov.object_id,
            articulation_p: prov.articulation_p,
            articulation_q: prov.articulation_q,
            n_p: input.p.len(),
            n_q: input.q.len(),
            num_parts: truth.num_parts(),
            joint_types: truth.joints.iter().map(|j| j.kind.as_str()).collect::<Vec<_>>().join(";"),
            max_joint_rotation_deg: change(JointKind::Revolute).to_degrees(),
            max_joint_translation: change(JointKind::Prismatic) / input.p.normalisation.scale,
            max_relative_rotation_deg: truth
                .motions
                .iter()
                .map(|m| rotation_error_deg(&truth.motions[0].rotation, &m.rotation))
                .fold(0.0f32, f32::max),
        }
    }
}

/// One row of a set dataset's `index.csv`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SetIndexRow {
    /// Set id.
    pub id: String,
    /// `full`, `scan` or `mixed`.
    pub mode: String,
    /// Number of views K.
    pub views: usize,
    /// Object category.
    pub category: String,
    /// Object index within the dataset.
    pub object_id: u32,
    /// Index of the set among the object's sets.
    pub set_index: u32,
    /// Each view's articulation state, `;`-separated.
    pub articulations: String,
    /// Each view's number of points, `;`-separated.
    pub points: String,
    /// Number of set parts, base included.
    pub num_parts: usize,
    /// Joint kinds between set parts, `;`-separated, in joint order.
    pub joint_types: String,
}

impl SetIndexRow {
    /// The row describing a set.
    pub fn of(set: &Set) -> Self {
        let (input, truth, prov) = (set.input(), set.truth(), set.provenance());
        let join = |items: Vec<String>| items.join(";");
        Self {
            id: input.id.clone(),
            mode: set.mode().as_str().into(),
            views: set.len(),
            category: prov.category.clone(),
            object_id: prov.object_id,
            set_index: prov.set_index,
            articulations: join(prov.views.iter().map(|v| v.articulation.to_string()).collect()),
            points: join(input.views.iter().map(|v| v.cloud.len().to_string()).collect()),
            num_parts: truth.num_parts(),
            joint_types: join(truth.joints.iter().map(|j| j.kind.as_str().to_string()).collect()),
        }
    }
}
