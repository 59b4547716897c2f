//! The `/set` message: one set of K views as a CBOR map whose large arrays are
//! little-endian byte strings, like the `/pair` message (docs/FORMAT.md, "Set datasets").

use serde::{Deserialize, Serialize};
use serde_bytes::ByteBuf;

use super::schema::{
    cloud, cloud_record, f32_bytes, motion_record, scan, scan_record, vectors, CloudRecord,
    MotionRecord, ScanRecord,
};
use crate::error::{PairError, SetError};
use crate::joints::JointKind;
use crate::math::{Matrix3, Point3, Real, Vector3};
use crate::parts::PartId;
use crate::set::{Set, SetInput, SetJoint, SetProvenance, SetTruth, View, ViewKind};
use crate::transform::Similarity;

/// Topic of the set records.
pub const SET_TOPIC: &str = "/set";
/// Schema name recorded in the `/set` channel's metadata under `schema`.
pub const SET_SCHEMA: &str = "part_induction.Set";
/// Version of the set record layout written, in the channel metadata and in every record.
pub const SET_SCHEMA_VERSION: u32 = 1;

/// One view of a set.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ViewRecord {
    /// `full` or `scan`.
    pub kind: ViewKind,
    /// The view's cloud (`N_k x 3` f32) and its normalisation.
    pub cloud: CloudRecord,
    /// Set part per point, u8.
    pub parts: ByteBuf,
    /// Scale shared by the view's part motions (view 0's diagonal over this view's).
    pub scale: Real,
    /// Per set part: its motion from view 0's normalised frame to this view's.
    pub motions: Vec<MotionRecord>,
    /// `N_0 x 3` f32: view 0's points moved into this view's state, minus view 0's points;
    /// absent on view 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub flow: Option<ByteBuf>,
    /// `K x N_k` u8, row j: whether each point moved into view j's state is present in
    /// view j (row k, the view's own, is all 1).
    pub presence: ByteBuf,
    /// `K x P` u8, row j: the part of the pair (this view, view j) each set part belongs to
    /// (row k is `0..P`).
    pub pair_parts: ByteBuf,
    /// The camera of a scanned view; absent for a full view.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scan: Option<ScanRecord>,
}

/// One joint between two set parts, seen in every view.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SetJointRecord {
    /// The joint's name.
    pub name: String,
    /// The set part it moves.
    pub part: PartId,
    /// The set part it moves against.
    pub parent: PartId,
    /// `revolute` or `prismatic`.
    pub kind: JointKind,
    /// Per view: unit axis, the view's normalised frame.
    pub axis: Vec<[Real; 3]>,
    /// Per view: a point on the axis, the view's normalised frame.
    pub pivot: Vec<[Real; 3]>,
    /// Per view: the joint value (radians or object units).
    pub value: Vec<Real>,
}

/// The `/set` message, field for field as docs/FORMAT.md describes it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SetRecord {
    /// Layout version, [`SET_SCHEMA_VERSION`].
    pub schema_version: u32,
    /// Unique set id.
    pub id: String,
    /// Number of set parts P.
    pub num_parts: u32,
    /// The K views.
    pub views: Vec<ViewRecord>,
    /// The joints between set parts.
    pub joints: Vec<SetJointRecord>,
    /// Where the set came from.
    pub provenance: SetProvenance,
}

impl SetRecord {
    /// The record of a set.
    pub fn from_set(set: &Set) -> Self {
        let (input, truth) = (set.input(), set.truth());
        let flags = |rows: &[Vec<bool>]| {
            ByteBuf::from(rows.iter().flatten().map(|&b| u8::from(b)).collect::<Vec<_>>())
        };
        let views = input
            .views
            .iter()
            .enumerate()
            .map(|(k, view)| ViewRecord {
                kind: view.kind,
                cloud: cloud_record(&view.cloud),
                parts: ByteBuf::from(truth.parts[k].clone()),
                scale: truth.motions[k].first().map_or(1.0, |m| m.scale),
                motions: truth.motions[k].iter().map(motion_record).collect(),
                flow: (k > 0).then(|| {
                    ByteBuf::from(f32_bytes(truth.flows[k].iter().flat_map(|v| v.iter().copied())))
                }),
                presence: flags(&truth.presence[k]),
                pair_parts: ByteBuf::from(truth.pair_parts[k].concat()),
                scan: set.scans()[k].as_ref().map(scan_record),
            })
            .collect();
        Self {
            schema_version: SET_SCHEMA_VERSION,
            id: input.id.clone(),
            num_parts: truth.num_parts() as u32,
            views,
            joints: truth
                .joints
                .iter()
                .map(|j| SetJointRecord {
                    name: j.name.clone(),
                    part: j.part,
                    parent: j.parent,
                    kind: j.kind,
                    axis: j.axis.iter().map(|&a| a.into()).collect(),
                    pivot: j.pivot.iter().map(|p| p.coords.into()).collect(),
                    value: j.value.clone(),
                })
                .collect(),
            provenance: set.provenance().clone(),
        }
    }

    /// Decodes the byte arrays and validates the set.
    pub fn into_set(self) -> Result<Set, SetError> {
        let id = self.id;
        let bad = |field: &'static str, index: usize, reason: String| SetError::Invalid {
            set: id.clone(),
            field,
            index,
            reason,
        };
        if self.schema_version != SET_SCHEMA_VERSION {
            let reason =
                format!("version {} (this reader knows {SET_SCHEMA_VERSION})", self.schema_version);
            return Err(bad("schema_version", 0, reason));
        }
        let (k, parts) = (self.views.len(), self.num_parts as usize);
        let mut input = SetInput { id: id.clone(), views: Vec::with_capacity(k) };
        let mut truth = SetTruth {
            parts: Vec::new(),
            motions: Vec::new(),
            flows: Vec::new(),
            presence: Vec::new(),
            pair_parts: Vec::new(),
            joints: Vec::new(),
        };
        let mut scans = Vec::with_capacity(k);
        for (v, view) in self.views.into_iter().enumerate() {
            let as_set = |e: PairError| bad("views", v, e.to_string());
            let cloud = cloud(&id, "cloud.points", view.cloud).map_err(as_set)?;
            let n = cloud.len();
            let flow = match (v, &view.flow) {
                (0, None) => vec![Vector3::zeros(); n],
                (_, Some(bytes)) if v > 0 => vectors(&id, "flow", bytes).map_err(as_set)?,
                _ => {
                    return Err(bad("views", v, "view 0 has no flow, every other view one".into()))
                }
            };
            let presence = rows(&view.presence, n, k).map_err(|r| bad("presence", v, r))?;
            let presence = presence
                .iter()
                .map(|row| match row.iter().find(|&&b| b > 1) {
                    None => Ok(row.iter().map(|&b| b == 1).collect()),
                    Some(b) => Err(bad("presence", v, format!("value {b} (must be 0 or 1)"))),
                })
                .collect::<Result<Vec<Vec<bool>>, _>>()?;
            let pair_parts =
                rows(&view.pair_parts, parts, k).map_err(|r| bad("pair_parts", v, r))?;
            let motions = view
                .motions
                .iter()
                .map(|m| Similarity {
                    rotation: Matrix3::from_row_slice(&m.rotation),
                    translation: Vector3::from(m.translation),
                    scale: view.scale,
                })
                .collect();
            input.views.push(View { kind: view.kind, cloud });
            truth.parts.push(view.parts.into_vec());
            truth.motions.push(motions);
            truth.flows.push(flow);
            truth.presence.push(presence);
            truth.pair_parts.push(pair_parts);
            scans.push(view.scan.map(scan));
        }
        truth.joints = self
            .joints
            .into_iter()
            .map(|j| SetJoint {
                name: j.name,
                part: j.part,
                parent: j.parent,
                kind: j.kind,
                axis: j.axis.into_iter().map(Vector3::from).collect(),
                pivot: j.pivot.into_iter().map(Point3::from).collect(),
                value: j.value,
            })
            .collect();
        Set::new(input, truth, self.provenance, scans)
    }
}

/// Splits `K x width` bytes into K rows, or says why it cannot.
fn rows(bytes: &[u8], width: usize, k: usize) -> Result<Vec<Vec<u8>>, String> {
    if bytes.len() != width * k {
        return Err(format!("{} bytes, expected {k} rows of {width}", bytes.len()));
    }
    Ok(bytes.chunks(width.max(1)).take(k).map(<[u8]>::to_vec).collect())
}

/// Encodes a set as the CBOR bytes of a `/set` message.
pub fn encode_set(set: &Set) -> Vec<u8> {
    let mut out = Vec::new();
    ciborium::into_writer(&SetRecord::from_set(set), &mut out)
        .expect("writing CBOR into a Vec cannot fail");
    out
}

/// Decodes the CBOR bytes of a `/set` message into a record (not yet validated).
pub fn decode_set_record(bytes: &[u8]) -> Result<SetRecord, String> {
    ciborium::from_reader(bytes).map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synthetic;

    #[test]
    fn a_set_survives_its_record() {
        let set = synthetic::hinge_set("h", 4, &[0.0, 0.3, 0.3, 1.0]);
        let back =
            decode_set_record(&encode_set(&set)).expect("decodes").into_set().expect("valid");
        assert_eq!(back, set);
    }

    #[test]
    fn broken_records_name_the_field() {
        let set = synthetic::hinge_set("h", 3, &[0.0, 0.3, 1.0]);
        let record = SetRecord::from_set(&set);
        let mut r = record.clone();
        r.views[1].presence.pop();
        assert!(r.into_set().unwrap_err().to_string().contains("presence"));
        let mut r = record.clone();
        r.views[0].flow = Some(ByteBuf::new());
        assert!(r.into_set().unwrap_err().to_string().contains("flow"));
        let mut r = record.clone();
        r.views[2].cloud.points.push(0);
        assert!(r.into_set().unwrap_err().to_string().contains("cloud.points"));
        let mut r = record;
        r.num_parts = 3;
        assert!(r.into_set().unwrap_err().to_string().contains("pair_parts"));
        assert!(decode_set_record(b"\xff\x00").is_err());
    }
}
