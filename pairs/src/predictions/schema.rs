//! The `/header` and `/prediction` records, field for field as docs/FORMAT.md describes them,
//! and their conversion to and from [`Prediction`].

use serde::{Deserialize, Serialize};
use serde_bytes::ByteBuf;

use crate::dataset::schema::f32_bytes;
use crate::joint_estimate::JointEstimate;
use crate::joints::JointKind;
use crate::math::{Matrix3, Point3, Real, Vector3};
use crate::method::Prediction;
use crate::transform::Similarity;

/// Topic of the header record.
pub const HEADER_TOPIC: &str = "/header";
/// Topic of the prediction records.
pub const PREDICTION_TOPIC: &str = "/prediction";
/// MCAP message encoding of both channels.
pub const PREDICTION_ENCODING: &str = "cbor";
/// Schema name in the `/header` channel's metadata.
pub const HEADER_SCHEMA: &str = "part_induction.PredictionHeader";
/// Schema name in the `/prediction` channel's metadata.
pub const PREDICTION_SCHEMA: &str = "part_induction.Prediction";
/// The header's `format`.
pub const PREDICTIONS_FORMAT: &str = "part-induction-predictions";
/// Version of the file layout, in the header and in both channels' metadata.
pub const PREDICTIONS_VERSION: u32 = 1;

/// Largest deviation of `RᵀR` from the identity (any entry) accepted as a rotation: loose
/// enough for f32 rotations from any solver, tight enough to catch a matrix that is not one.
const ROTATION_TOLERANCE: Real = 1e-3;

/// The `/header` record: what made the file and for which dataset.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PredictionHeader {
    /// [`PREDICTIONS_FORMAT`].
    pub format: String,
    /// [`PREDICTIONS_VERSION`].
    pub format_version: u32,
    /// The method's name.
    pub method: String,
    /// The method's version, free text; may be empty.
    #[serde(default)]
    pub method_version: String,
    /// Content hash of the dataset: the sha256 of its `pairs.mcap` in its manifest.
    pub dataset: String,
}

impl PredictionHeader {
    /// The header of this format version for `method` at `method_version` on the dataset
    /// whose content hash is `dataset`.
    pub fn new(method: &str, method_version: &str, dataset: &str) -> Self {
        Self {
            format: PREDICTIONS_FORMAT.into(),
            format_version: PREDICTIONS_VERSION,
            method: method.into(),
            method_version: method_version.into(),
            dataset: dataset.into(),
        }
    }
}

/// A segment's motion, `x -> scale * R x + t`, P's to Q's normalised frame.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MotionPredictionRecord {
    /// Rotation matrix, row-major.
    pub rotation: [Real; 9],
    /// Translation, Q's normalised units.
    pub translation: [Real; 3],
    /// Uniform scale (1 when absent).
    #[serde(default = "one")]
    pub scale: Real,
}

fn one() -> Real {
    1.0
}

/// Soft segment probabilities: `columns` per point of P, row-major.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SegmentProbsRecord {
    /// Probabilities per point (C).
    pub columns: u32,
    /// `N_p x C` f32, little-endian.
    pub values: ByteBuf,
}

/// The joint that moves one segment, P's normalised frame.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JointPredictionRecord {
    /// `revolute` or `prismatic` (text, so that an unknown kind fails its pair only).
    pub kind: String,
    /// Unit axis.
    pub axis: [Real; 3],
    /// A point on the axis.
    pub pivot: [Real; 3],
    /// State change from P to Q: radians, or P's normalised units.
    pub value: Real,
}

/// The `/prediction` record of one pair. Every field but `id` may be absent.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct PredictionRecord {
    /// The pair's id.
    pub id: String,
    /// `N_p` u32, little-endian: segment of each point of P.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub segments_p: Option<ByteBuf>,
    /// `N_q` u32, little-endian: segment of each point of Q.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub segments_q: Option<ByteBuf>,
    /// `N_p x 3` f32, little-endian: flow on P, Q's normalised units.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub flow: Option<ByteBuf>,
    /// Motion of each segment.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub motions: Option<Vec<MotionPredictionRecord>>,
    /// `N_p` f32, little-endian, in `[0, 1]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub corr_mask: Option<ByteBuf>,
    /// Soft segment probabilities on P.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub segment_probs: Option<SegmentProbsRecord>,
    /// The joint of each segment, null where it has none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub joints: Option<Vec<Option<JointPredictionRecord>>>,
    /// Why the method failed on this pair.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
}

impl PredictionRecord {
    /// The record of `prediction` for pair `id`.
    pub fn from_prediction(id: &str, prediction: &Prediction) -> Self {
        let u32_bytes =
            |v: &[u32]| ByteBuf::from(v.iter().flat_map(|s| s.to_le_bytes()).collect::<Vec<_>>());
        let segments_q = &prediction.segments_q;
        Self {
            id: id.into(),
            segments_p: Some(u32_bytes(&prediction.segments_p)),
            segments_q: (!segments_q.is_empty()).then(|| u32_bytes(segments_q)),
            flow: prediction
                .flow
                .as_ref()
                .map(|f| ByteBuf::from(f32_bytes(f.iter().flat_map(|v| v.iter().copied())))),
            motions: (!prediction.motions.is_empty())
                .then(|| prediction.motions.iter().map(motion_record).collect()),
            corr_mask: prediction
                .corr_mask
                .as_ref()
                .map(|m| ByteBuf::from(f32_bytes(m.iter().copied()))),
            segment_probs: prediction.segment_probs.as_ref().map(|rows| SegmentProbsRecord {
                columns: rows.first().map_or(0, Vec::len) as u32,
                values: ByteBuf::from(f32_bytes(rows.iter().flatten().copied())),
            }),
            joints: prediction
                .joints
                .as_ref()
                .map(|joints| joints.iter().map(|j| j.as_ref().map(joint_record)).collect()),
            error: None,
        }
    }

    /// The record of a pair the method failed on.
    pub fn failure(id: &str, reason: &str) -> Self {
        Self { id: id.into(), error: Some(reason.into()), ..Self::default() }
    }

    /// The prediction this record holds, or why it holds none: the method's own `error`, or
    /// the first field that does not decode (lengths against the pair's point counts are the
    /// scorer's check, which knows the pair).
    pub fn into_prediction(self) -> Result<Prediction, String> {
        if let Some(error) = self.error {
            return Err(format!("the method failed: {error}"));
        }
        let segments_p = self.segments_p.ok_or("no segments_p")?;
        let segments_p: Vec<u32> =
            words("segments_p", &segments_p)?.map(u32::from_le_bytes).collect();
        let segments_q = match &self.segments_q {
            Some(bytes) => words("segments_q", bytes)?.map(u32::from_le_bytes).collect(),
            None => Vec::new(),
        };
        let flow = self.flow.map(|bytes| vectors("flow", &bytes)).transpose()?;
        let motions: Vec<Similarity> = self
            .motions
            .unwrap_or_default()
            .iter()
            .enumerate()
            .map(|(s, m)| similarity(s, m))
            .collect::<Result<_, _>>()?;
        let corr_mask = self.corr_mask.map(|bytes| floats("corr_mask", &bytes)).transpose()?;
        if let Some(i) = corr_mask.iter().flatten().position(|v| !(0.0..=1.0).contains(v)) {
            return Err(format!("corr_mask[{i}] is not in [0, 1]"));
        }
        let segment_probs = self.segment_probs.map(probabilities).transpose()?;
        let flat = segment_probs.iter().flatten().flatten();
        if let Some(i) = flat.clone().position(|v| !v.is_finite()) {
            return Err(format!("segment_probs value {i} is not finite"));
        }
        if let Some(rows) = segment_probs.as_ref().filter(|r| r.len() != segments_p.len()) {
            return Err(format!(
                "segment_probs has {} rows but segments_p {} entries",
                rows.len(),
                segments_p.len()
            ));
        }
        let joints = self
            .joints
            .map(|joints| {
                joints
                    .into_iter()
                    .enumerate()
                    .map(|(s, j)| j.map(|j| joint_estimate(s, j)).transpose())
                    .collect::<Result<Vec<_>, _>>()
            })
            .transpose()?;
        // Motions and joints, when given, have one entry per segment id (S = one more than
        // the largest id of P and Q).
        let count = segments_p.iter().chain(&segments_q).max().map_or(0, |&s| s as usize + 1);
        let lengths = [("motions", motions.len()), ("joints", joints.as_ref().map_or(0, Vec::len))];
        if let Some((field, len)) = lengths.into_iter().find(|&(_, n)| n != 0 && n != count) {
            return Err(format!(
                "{field} has {len} entries, expected {count} (one per segment id 0..={})",
                count.saturating_sub(1)
            ));
        }
        Ok(Prediction { flow, segments_p, segments_q, motions, corr_mask, segment_probs, joints })
    }
}

fn motion_record(m: &Similarity) -> MotionPredictionRecord {
    let r = &m.rotation;
    MotionPredictionRecord {
        rotation: [r.m11, r.m12, r.m13, r.m21, r.m22, r.m23, r.m31, r.m32, r.m33],
        translation: m.translation.into(),
        scale: m.scale,
    }
}

fn joint_record(j: &JointEstimate) -> JointPredictionRecord {
    JointPredictionRecord {
        kind: j.kind.as_str().into(),
        axis: j.axis.into(),
        pivot: j.pivot.coords.into(),
        value: j.value,
    }
}

/// The motion of segment `s`, checked to be a similarity with a proper rotation.
fn similarity(s: usize, m: &MotionPredictionRecord) -> Result<Similarity, String> {
    let rotation = Matrix3::from_row_slice(&m.rotation);
    let values = m.rotation.iter().chain(&m.translation).chain([&m.scale]);
    if !values.into_iter().all(|v| v.is_finite()) {
        return Err(format!("motions[{s}] is not finite"));
    }
    let deviation = (rotation.transpose() * rotation - Matrix3::identity()).amax();
    if deviation > ROTATION_TOLERANCE || rotation.determinant() <= 0.0 {
        return Err(format!(
            "motions[{s}].rotation is not a rotation (|RᵀR - I| = {deviation:.2e}, det {:.3})",
            rotation.determinant()
        ));
    }
    if m.scale <= 0.0 {
        return Err(format!("motions[{s}].scale is {} (must be > 0)", m.scale));
    }
    Ok(Similarity { rotation, translation: Vector3::from(m.translation), scale: m.scale })
}

fn joint_estimate(s: usize, j: JointPredictionRecord) -> Result<JointEstimate, String> {
    let kind = match j.kind.as_str() {
        "revolute" => JointKind::Revolute,
        "prismatic" => JointKind::Prismatic,
        other => {
            return Err(format!("joints[{s}].kind is {other:?} (revolute or prismatic)"));
        }
    };
    let values = j.axis.iter().chain(&j.pivot).chain([&j.value]);
    if !values.into_iter().all(|v| v.is_finite()) {
        return Err(format!("joints[{s}] is not finite"));
    }
    let axis = Vector3::from(j.axis);
    let axis = axis.try_normalize(1e-6).ok_or(format!("joints[{s}].axis is zero"))?;
    Ok(JointEstimate { kind, axis, pivot: Point3::from(j.pivot), value: j.value })
}

fn probabilities(record: SegmentProbsRecord) -> Result<Vec<Vec<Real>>, String> {
    let values = floats("segment_probs.values", &record.values)?;
    let columns = record.columns as usize;
    if columns == 0 {
        return if values.is_empty() {
            Ok(Vec::new())
        } else {
            Err("segment_probs has 0 columns but values".into())
        };
    }
    if values.len() % columns != 0 {
        return Err(format!(
            "segment_probs.values has {} floats, not a multiple of {columns} columns",
            values.len()
        ));
    }
    Ok(values.chunks_exact(columns).map(<[Real]>::to_vec).collect())
}

/// The 4-byte words of a byte string, or which field's length is off.
fn words<'a>(field: &str, bytes: &'a [u8]) -> Result<impl Iterator<Item = [u8; 4]> + 'a, String> {
    let (chunks, rest) = bytes.as_chunks::<4>();
    if rest.is_empty() {
        Ok(chunks.iter().copied())
    } else {
        Err(format!("{field} has {} bytes, not a whole number of 4-byte values", bytes.len()))
    }
}

fn floats(field: &str, bytes: &[u8]) -> Result<Vec<Real>, String> {
    Ok(words(field, bytes)?.map(f32::from_le_bytes).collect())
}

fn vectors(field: &str, bytes: &[u8]) -> Result<Vec<Vector3>, String> {
    let values = floats(field, bytes)?;
    let (triples, rest) = values.as_chunks::<3>();
    if !rest.is_empty() {
        return Err(format!("{field} has {} floats, not a multiple of 3", values.len()));
    }
    Ok(triples.iter().map(|t| Vector3::from(*t)).collect())
}
