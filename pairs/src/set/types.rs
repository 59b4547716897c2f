//! What a set holds: its views (kind and cloud), its ground truth (motions, flows, joints,
//! the parts of every pair of views) and its provenance.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::cloud::Cloud;
use crate::joints::JointKind;
use crate::math::{Point3, Real, Vector3};
use crate::pair::Pose;
use crate::parts::PartId;
use crate::transform::Similarity;

/// How one view of a set was observed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ViewKind {
    /// A full shape: area-weighted surface samples.
    Full,
    /// A virtual scan from one camera.
    Scan,
}

impl ViewKind {
    /// Lower-case name, as written in files.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Full => "full",
            Self::Scan => "scan",
        }
    }
}

/// What the views of a set are: every one full, every one scanned, or view 0 full and the
/// others scanned (the SF2P setting with K views).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum SetMode {
    /// Every view a full shape.
    #[default]
    Full,
    /// Every view a virtual scan.
    Scan,
    /// View 0 a full shape, the others virtual scans.
    Mixed,
}

impl SetMode {
    /// Every mode, in the order docs list them.
    pub const ALL: [SetMode; 3] = [Self::Full, Self::Scan, Self::Mixed];

    /// Lower-case name, as written in files.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Full => "full",
            Self::Scan => "scan",
            Self::Mixed => "mixed",
        }
    }

    /// How view `k` is observed.
    pub fn view(self, k: usize) -> ViewKind {
        match self {
            Self::Full => ViewKind::Full,
            Self::Scan => ViewKind::Scan,
            Self::Mixed if k == 0 => ViewKind::Full,
            Self::Mixed => ViewKind::Scan,
        }
    }

    /// The mode of a sequence of view kinds, if it is one of the three.
    pub fn of(kinds: &[ViewKind]) -> Option<Self> {
        Self::ALL.into_iter().find(|m| kinds.iter().enumerate().all(|(k, &v)| m.view(k) == v))
    }
}

impl std::str::FromStr for SetMode {
    type Err = String;

    /// Parses a mode's name, in either case.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|m| m.as_str().eq_ignore_ascii_case(s))
            .ok_or_else(|| format!("unknown set mode {s:?}; expected one of full, scan, mixed"))
    }
}

/// One observation of a set as a method sees it.
#[derive(Debug, Clone, PartialEq)]
pub struct View {
    /// Full shape or scan.
    pub kind: ViewKind,
    /// The cloud, in its own normalised frame.
    pub cloud: Cloud,
}

/// A set as a method sees it: its K views, without any ground truth.
#[derive(Debug, Clone, PartialEq)]
pub struct SetInput {
    /// Unique id within the dataset.
    pub id: String,
    /// The K observations, view 0 first.
    pub views: Vec<View>,
}

/// The joint between two set parts, seen in every view.
#[derive(Debug, Clone, PartialEq)]
pub struct SetJoint {
    /// The joint's name (the exported URDF's).
    pub name: String,
    /// The set part it moves.
    pub part: PartId,
    /// The set part it moves it against.
    pub parent: PartId,
    /// Revolute or prismatic.
    pub kind: JointKind,
    /// Per view: unit axis direction, the view's normalised frame.
    pub axis: Vec<Vector3>,
    /// Per view: a point on the axis, the view's normalised frame.
    pub pivot: Vec<Point3>,
    /// Per view: the joint's value (radians or object units, see [`JointKind`]).
    pub value: Vec<Real>,
}

/// Everything a method must recover for one set.
#[derive(Debug, Clone, PartialEq)]
pub struct SetTruth {
    /// Per view, per point: its set part. Part 0 holds the root link; part k in one view is
    /// part k in every view.
    pub parts: Vec<Vec<PartId>>,
    /// `motions[k][s]` maps set part s from view 0's normalised frame to view k's; the
    /// parts of one view share one scale, and view 0's motions are the identity.
    pub motions: Vec<Vec<Similarity>>,
    /// `flows[k]`: per point of view 0, `motions[k][parts[0][i]](x_i) - x_i` (all zero for
    /// k = 0), view k's normalised units.
    pub flows: Vec<Vec<Vector3>>,
    /// `presence[i][j]`: per point of view i, whether the point moved to view j's state is
    /// present in view j (always for a full view j; for a scan, visible from its camera and
    /// not lost); `presence[i][i]` is all true.
    pub presence: Vec<Vec<Vec<bool>>>,
    /// `pair_parts[i][j][s]`: the part of the pair (i, j) that set part s belongs to (set
    /// parts that did not move relative to each other between the two states are one part
    /// of the pair, numbered by first appearance); `pair_parts[i][i]` is `0..parts`.
    pub pair_parts: Vec<Vec<Vec<PartId>>>,
    /// The joints between set parts, in the object's joint order.
    pub joints: Vec<SetJoint>,
}

impl SetTruth {
    /// Number of set parts.
    pub fn num_parts(&self) -> usize {
        self.motions.first().map_or(0, Vec::len)
    }
}

/// Where one view came from.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct ViewProvenance {
    /// Index of the view's articulation state among the object's states.
    pub articulation: u32,
    /// Every joint of the object by name, with its value in the view's state.
    pub joints: BTreeMap<String, Real>,
    /// The view's global pose: the object's rest frame into the view's object frame.
    pub pose: Option<Pose>,
}

/// Where a set came from, so that it can be regenerated.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct SetProvenance {
    /// Object category.
    pub category: String,
    /// Index of the object within its dataset.
    pub object_id: u32,
    /// Index of the set among the object's sets.
    pub set_index: u32,
    /// Seed of the dataset the set belongs to.
    pub seed: u64,
    /// Version of the generator that made it.
    pub generator_version: String,
    /// Per view.
    pub views: Vec<ViewProvenance>,
}
