//! The `/pair` message: a CBOR map whose large arrays are little-endian byte strings
//! (docs/FORMAT.md documents every field).

use serde::{Deserialize, Serialize};
use serde_bytes::ByteBuf;

use crate::cloud::{Cloud, Normalisation};
use crate::error::PairError;
use crate::ground_truth::GroundTruth;
use crate::joints::{JointKind, JointTruth};
use crate::math::{Matrix3, Point3, Real, Vector3};
use crate::pair::{Pair, PairInput, PairKind, Provenance};
use crate::parts::PartId;
use crate::scan::{Intrinsics, Scan, ScanImages, Scans};
use crate::transform::Similarity;

/// Topic of the pair records.
pub const PAIR_TOPIC: &str = "/pair";
/// MCAP message encoding of the pair records.
pub const PAIR_ENCODING: &str = "cbor";
/// Schema name recorded in the `/pair` channel's metadata under `schema`.
pub const PAIR_SCHEMA: &str = "part_induction.Pair";
/// Version of the record layout written, in the channel metadata and in every record.
/// Version 2 added the full joint configurations and global poses to `provenance`.
pub const SCHEMA_VERSION: u32 = 2;
/// Oldest record layout still read (its provenance has no configurations or poses).
pub const OLDEST_SCHEMA_VERSION: u32 = 1;

/// One cloud: points as `N x 3` little-endian f32, and its normalisation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CloudRecord {
    /// `N x 3` f32, little-endian, row-major (x, y, z per point).
    pub points: ByteBuf,
    /// Bounding-box centre in the object frame.
    pub centre: [Real; 3],
    /// Bounding-box diagonal in object units.
    pub scale: Real,
}

/// One part motion: `x -> scale * R x + t`, with the pair's shared scale.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MotionRecord {
    /// Rotation matrix, row-major.
    pub rotation: [Real; 9],
    /// Translation, Q's normalised units.
    pub translation: [Real; 3],
}

/// One joint of the ground truth.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JointRecord {
    /// The part it moves.
    pub part: PartId,
    /// `revolute` or `prismatic`.
    pub kind: JointKind,
    /// Unit axis, P's normalised frame.
    pub axis_p: [Real; 3],
    /// Point on the axis, P's normalised frame.
    pub pivot_p: [Real; 3],
    /// Unit axis, Q's normalised frame.
    pub axis_q: [Real; 3],
    /// Point on the axis, Q's normalised frame.
    pub pivot_q: [Real; 3],
    /// Joint value in P's state (radians or object units).
    pub value_p: Real,
    /// Joint value in Q's state (radians or object units).
    pub value_q: Real,
}

/// The `/pair` message, field for field as docs/FORMAT.md describes it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PairRecord {
    /// Layout version, [`SCHEMA_VERSION`].
    pub schema_version: u32,
    /// Unique pair id.
    pub id: String,
    /// `SF2F`, `SF2P`, `SP2P`, `XF2F` or `XF2P`.
    pub kind: PairKind,
    /// The source cloud.
    pub p: CloudRecord,
    /// The target cloud.
    pub q: CloudRecord,
    /// Number of parts K.
    pub num_parts: u32,
    /// Part id per point of P, u8.
    pub part_p: ByteBuf,
    /// Part id per point of Q, u8.
    pub part_q: ByteBuf,
    /// Scale shared by all part motions.
    pub scale: Real,
    /// K part motions.
    pub motions: Vec<MotionRecord>,
    /// `N_p x 3` f32 flow, little-endian; absent in a cross-instance pair (XF2F, XF2P).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub flow: Option<ByteBuf>,
    /// Per point of P, u8 0 or 1.
    pub corr_mask: ByteBuf,
    /// Per point of P, i32 little-endian, -1 where the mask is 0.
    pub corr_index: ByteBuf,
    /// Joints of the moving parts.
    pub joints: Vec<JointRecord>,
    /// Where the pair came from.
    pub provenance: Provenance,
    /// P's camera, for a scanned P (SP2P); absent otherwise.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scan_p: Option<ScanRecord>,
    /// Q's camera, for a scanned Q (SF2P, SP2P); absent otherwise.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scan_q: Option<ScanRecord>,
}

/// The camera of one scanned side (conventions in `crate::scan`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ScanRecord {
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Intrinsics `[fx, fy, cx, cy]`, pixels.
    pub intrinsics: [Real; 4],
    /// Camera-to-object rotation, row-major.
    pub rotation: [Real; 9],
    /// Camera-to-object translation (the camera centre), object units.
    pub translation: [Real; 3],
    /// Object units per unit of the depth PNG.
    pub depth_scale: Real,
    /// Depth PNG path, relative to the dataset folder.
    pub depth: String,
    /// Part-label PNG path, relative to the dataset folder.
    pub labels: String,
    /// Colour PNG path, relative to the dataset folder.
    pub colour: String,
}

impl PairRecord {
    /// The record of a pair.
    pub fn from_pair(pair: &Pair) -> Self {
        let (input, truth) = (pair.input(), pair.truth());
        Self {
            schema_version: SCHEMA_VERSION,
            id: input.id.clone(),
            kind: input.kind,
            p: cloud_record(&input.p),
            q: cloud_record(&input.q),
            num_parts: truth.num_parts() as u32,
            part_p: ByteBuf::from(truth.part_p.clone()),
            part_q: ByteBuf::from(truth.part_q.clone()),
            scale: truth.motions.first().map_or(1.0, |m| m.scale),
            motions: truth.motions.iter().map(motion_record).collect(),
            flow: truth
                .flow
                .as_ref()
                .map(|flow| ByteBuf::from(f32_bytes(flow.iter().flat_map(|v| v.iter().copied())))),
            corr_mask: ByteBuf::from(
                truth.corr_mask.iter().map(|&m| u8::from(m)).collect::<Vec<_>>(),
            ),
            corr_index: ByteBuf::from(
                truth.corr_index.iter().flat_map(|i| i.to_le_bytes()).collect::<Vec<_>>(),
            ),
            joints: truth.joints.iter().map(joint_record).collect(),
            provenance: pair.provenance().clone(),
            scan_p: pair.scans().p.as_ref().map(scan_record),
            scan_q: pair.scans().q.as_ref().map(scan_record),
        }
    }

    /// Decodes the byte arrays and validates the pair.
    pub fn into_pair(self) -> Result<Pair, PairError> {
        let id = self.id;
        if !(OLDEST_SCHEMA_VERSION..=SCHEMA_VERSION).contains(&self.schema_version) {
            let reason = format!(
                "version {} (this reader knows {OLDEST_SCHEMA_VERSION} to {SCHEMA_VERSION})",
                self.schema_version
            );
            return Err(PairError::Inconsistent {
                pair: id,
                field: "schema_version",
                index: 0,
                reason,
            });
        }
        let p = cloud(&id, "p.points", self.p)?;
        let q = cloud(&id, "q.points", self.q)?;
        let flow = self.flow.as_ref().map(|f| vectors(&id, "flow", f)).transpose()?;
        let corr_mask = self
            .corr_mask
            .iter()
            .enumerate()
            .map(|(i, &m)| match m {
                0 | 1 => Ok(m == 1),
                _ => Err(PairError::Inconsistent {
                    pair: id.clone(),
                    field: "corr_mask",
                    index: i,
                    reason: format!("value {m} (must be 0 or 1)"),
                }),
            })
            .collect::<Result<Vec<_>, _>>()?;
        let corr_index = words(&id, "corr_index", &self.corr_index)?
            .into_iter()
            .map(i32::from_le_bytes)
            .collect();
        if self.motions.len() != self.num_parts as usize {
            return Err(PairError::Length {
                pair: id,
                field: "motions",
                expected: self.num_parts as usize,
                found: self.motions.len(),
            });
        }
        let scale = self.scale;
        let truth = GroundTruth {
            part_p: self.part_p.into_vec(),
            part_q: self.part_q.into_vec(),
            motions: self
                .motions
                .iter()
                .map(|m| Similarity {
                    rotation: Matrix3::from_row_slice(&m.rotation),
                    translation: Vector3::from(m.translation),
                    scale,
                })
                .collect(),
            flow,
            corr_mask,
            corr_index,
            joints: self.joints.iter().map(joint_truth).collect(),
        };
        let scans = Scans { p: self.scan_p.map(scan), q: self.scan_q.map(scan) };
        Pair::new(PairInput { id, kind: self.kind, p, q }, truth, self.provenance)?
            .with_scans(scans)
    }
}

/// Encodes a pair as the CBOR bytes of a `/pair` message.
pub fn encode_pair(pair: &Pair) -> Vec<u8> {
    let mut out = Vec::new();
    ciborium::into_writer(&PairRecord::from_pair(pair), &mut out)
        .expect("writing CBOR into a Vec cannot fail");
    out
}

/// Decodes the CBOR bytes of a `/pair` message into a record (not yet validated).
pub fn decode_record(bytes: &[u8]) -> Result<PairRecord, String> {
    ciborium::from_reader(bytes).map_err(|e| e.to_string())
}

/// Little-endian bytes of a sequence of f32.
pub(crate) fn f32_bytes(values: impl Iterator<Item = Real>) -> Vec<u8> {
    values.flat_map(|v| v.to_le_bytes()).collect()
}

pub(crate) fn cloud_record(c: &Cloud) -> CloudRecord {
    CloudRecord {
        points: ByteBuf::from(f32_bytes(c.points.iter().flat_map(|p| p.coords.iter().copied()))),
        centre: c.normalisation.centre.into(),
        scale: c.normalisation.scale,
    }
}

fn row_major(r: &Matrix3) -> [Real; 9] {
    [r.m11, r.m12, r.m13, r.m21, r.m22, r.m23, r.m31, r.m32, r.m33]
}

pub(crate) fn motion_record(m: &Similarity) -> MotionRecord {
    MotionRecord { rotation: row_major(&m.rotation), translation: m.translation.into() }
}

pub(crate) fn scan_record(s: &Scan) -> ScanRecord {
    let k = &s.intrinsics;
    ScanRecord {
        width: k.width,
        height: k.height,
        intrinsics: [k.fx, k.fy, k.cx, k.cy],
        rotation: row_major(&s.rotation),
        translation: s.translation.into(),
        depth_scale: s.depth_scale,
        depth: s.images.depth.clone(),
        labels: s.images.labels.clone(),
        colour: s.images.colour.clone(),
    }
}

pub(crate) fn scan(r: ScanRecord) -> Scan {
    let [fx, fy, cx, cy] = r.intrinsics;
    Scan {
        intrinsics: Intrinsics { width: r.width, height: r.height, fx, fy, cx, cy },
        rotation: Matrix3::from_row_slice(&r.rotation),
        translation: Vector3::from(r.translation),
        depth_scale: r.depth_scale,
        images: ScanImages { depth: r.depth, labels: r.labels, colour: r.colour },
    }
}

fn joint_record(j: &JointTruth) -> JointRecord {
    JointRecord {
        part: j.part,
        kind: j.kind,
        axis_p: j.axis_p.into(),
        pivot_p: j.pivot_p.coords.into(),
        axis_q: j.axis_q.into(),
        pivot_q: j.pivot_q.coords.into(),
        value_p: j.value_p,
        value_q: j.value_q,
    }
}

fn joint_truth(j: &JointRecord) -> JointTruth {
    JointTruth {
        part: j.part,
        kind: j.kind,
        axis_p: Vector3::from(j.axis_p),
        pivot_p: Point3::from(j.pivot_p),
        axis_q: Vector3::from(j.axis_q),
        pivot_q: Point3::from(j.pivot_q),
        value_p: j.value_p,
        value_q: j.value_q,
    }
}

pub(crate) fn cloud(id: &str, field: &'static str, rec: CloudRecord) -> Result<Cloud, PairError> {
    let points = vectors(id, field, &rec.points)?.into_iter().map(Point3::from).collect();
    let normalisation = Normalisation { centre: Vector3::from(rec.centre), scale: rec.scale };
    Ok(Cloud { points, normalisation })
}

/// Splits a byte string into 4-byte words, or names the field whose length is off.
pub(crate) fn words(
    id: &str,
    field: &'static str,
    bytes: &[u8],
) -> Result<Vec<[u8; 4]>, PairError> {
    let (chunks, rest) = bytes.as_chunks::<4>();
    if rest.is_empty() {
        Ok(chunks.to_vec())
    } else {
        Err(PairError::Inconsistent {
            pair: id.into(),
            field,
            index: chunks.len(),
            reason: format!("byte length {} is not a multiple of 4", bytes.len()),
        })
    }
}

pub(crate) fn vectors(
    id: &str,
    field: &'static str,
    bytes: &[u8],
) -> Result<Vec<Vector3>, PairError> {
    let values: Vec<Real> = words(id, field, bytes)?.into_iter().map(f32::from_le_bytes).collect();
    let (triples, rest) = values.as_chunks::<3>();
    if !rest.is_empty() {
        return Err(PairError::Inconsistent {
            pair: id.into(),
            field,
            index: triples.len(),
            reason: format!("{} floats is not a multiple of 3", values.len()),
        });
    }
    Ok(triples.iter().map(|t| Vector3::from(*t)).collect())
}
