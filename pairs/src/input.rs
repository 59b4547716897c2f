//! A pair as a method sees it ([`PairInput`]: its kind and two clouds), the poses of its
//! sides and where it came from ([`Provenance`]).

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::cloud::Cloud;
use crate::math::{Isometry3, Real};

/// Which observations a pair holds (DESIGN.md, "Shared definitions").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum PairKind {
    /// Full shape to full shape.
    #[serde(rename = "SF2F")]
    Sf2f,
    /// Full shape to a virtual scan.
    #[serde(rename = "SF2P")]
    Sf2p,
    /// Virtual scan to virtual scan.
    #[serde(rename = "SP2P")]
    Sp2p,
    /// Cross-instance: the full shape of one object to the full shape of another object of
    /// the same category. Parts correspond by role; there is no flow.
    #[serde(rename = "XF2F")]
    Xf2f,
    /// Cross-instance: the full shape of one object to a virtual scan of another object of
    /// the same category. Parts correspond by role; there is no flow.
    #[serde(rename = "XF2P")]
    Xf2p,
}

impl PairKind {
    /// Upper-case name, as written in files.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Sf2f => "SF2F",
            Self::Sf2p => "SF2P",
            Self::Sp2p => "SP2P",
            Self::Xf2f => "XF2F",
            Self::Xf2p => "XF2P",
        }
    }

    /// Every kind, in the order the boards list them.
    pub const ALL: [PairKind; 5] = [Self::Sf2f, Self::Sf2p, Self::Sp2p, Self::Xf2f, Self::Xf2p];

    /// Whether P and Q are two different objects of one category (no flow, no point
    /// correspondences; parts correspond by their role in the category).
    pub fn cross_instance(self) -> bool {
        matches!(self, Self::Xf2f | Self::Xf2p)
    }

    /// Whether P is a virtual scan.
    pub fn scanned_p(self) -> bool {
        matches!(self, Self::Sp2p)
    }

    /// Whether Q is a virtual scan.
    pub fn scanned_q(self) -> bool {
        matches!(self, Self::Sf2p | Self::Sp2p | Self::Xf2p)
    }
}

impl std::str::FromStr for PairKind {
    type Err = String;

    /// Parses a kind's name, in either case (`sf2p`, `XF2F`).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL.into_iter().find(|k| k.as_str().eq_ignore_ascii_case(s)).ok_or_else(|| {
            let names: Vec<_> = Self::ALL.iter().map(|k| k.as_str().to_lowercase()).collect();
            format!("unknown pair kind {s:?}; expected one of {}", names.join(", "))
        })
    }
}

/// Where a pair came from, so that any pair can be regenerated, and the object re-posed
/// into both of its states elsewhere (a simulator, from the object's exported URDF).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Provenance {
    /// Object category (e.g. `laptop`).
    pub category: String,
    /// Index of the object within its dataset.
    pub object_id: u32,
    /// Index of P's articulation state among the object's states.
    pub articulation_p: u32,
    /// Index of Q's articulation state among the object's states.
    pub articulation_q: u32,
    /// Seed of the dataset the pair belongs to.
    pub seed: u64,
    /// For a cross-instance pair (XF2F, XF2P), the seed that built Q's object: it is object
    /// `object_id` of the same dataset config with this seed (P's object is built with
    /// `seed`), and `articulation_q` indexes its states. Absent when P and Q are one object.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed_q: Option<u64>,
    /// Version of the generator that made it.
    pub generator_version: String,
    /// Every joint of the object by name (the exported URDF's joint names), unchanged ones
    /// too, with its value in P's state: radians or object units. Empty in schema-1 files.
    #[serde(default)]
    pub joints_p: BTreeMap<String, Real>,
    /// Every joint's value in Q's state, as [`Self::joints_p`].
    #[serde(default)]
    pub joints_q: BTreeMap<String, Real>,
    /// P's global pose: the object's rest frame (its URDF base frame) into P's object frame,
    /// the frame `p.centre` and `p.scale` normalise. Absent in schema-1 files.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pose_p: Option<Pose>,
    /// Q's global pose, as [`Self::pose_p`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pose_q: Option<Pose>,
}

/// A rigid transform `x -> R x + t`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Pose {
    /// Rotation matrix R, row-major.
    pub rotation: [Real; 9],
    /// Translation t.
    pub translation: [Real; 3],
}

impl Pose {
    /// The pose of an isometry.
    pub fn of(isometry: &Isometry3) -> Self {
        let r = isometry.rotation.to_rotation_matrix().into_inner();
        Self {
            rotation: [r.m11, r.m12, r.m13, r.m21, r.m22, r.m23, r.m31, r.m32, r.m33],
            translation: isometry.translation.vector.into(),
        }
    }
}

/// A pair as a method sees it: the two clouds, without any ground truth.
#[derive(Debug, Clone, PartialEq)]
pub struct PairInput {
    /// Unique id within the dataset.
    pub id: String,
    /// Kind of observations.
    pub kind: PairKind,
    /// The source cloud, P's normalised frame.
    pub p: Cloud,
    /// The target cloud, Q's normalised frame.
    pub q: Cloud,
}
