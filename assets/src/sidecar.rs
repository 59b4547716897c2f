//! The joints sidecar `<name>.joints.json` of an OBJ asset, whose joint records glTF node
//! `extras` share (docs/FORMAT.md, "Joints sidecar").

use std::path::{Path, PathBuf};

use serde::Deserialize;

use super::skeleton::{RawJoint, RawKind, RawMimic};
use super::{text, ImportError};

/// The sidecar file.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Sidecar {
    /// Category for provenance; the asset's file stem when absent.
    #[serde(default)]
    pub category: Option<String>,
    /// Joints, each naming its parent and child part.
    pub joints: Vec<JointSpec>,
}

/// One joint record: the same fields in a sidecar and in a glTF node's `extras.joint`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointSpec {
    /// Joint name, unique in the asset.
    pub name: String,
    /// `revolute`, `continuous`, `prismatic` or `fixed`.
    #[serde(rename = "type")]
    pub kind: String,
    /// Parent part (OBJ group or glTF node name); a glTF node's `extras` may leave it out
    /// for the node's parent in the hierarchy.
    #[serde(default)]
    pub parent: Option<String>,
    /// Child part; a glTF node's `extras` may leave it out for the node itself.
    #[serde(default)]
    pub child: Option<String>,
    /// A point on the axis, asset frame (default the origin).
    #[serde(default)]
    pub origin: Option<[f64; 3]>,
    /// Axis direction, asset frame; required unless `fixed`.
    #[serde(default)]
    pub axis: Option<[f64; 3]>,
    /// Lower limit (radians or asset units); required for revolute and prismatic.
    #[serde(default)]
    pub lower: Option<f64>,
    /// Upper limit.
    #[serde(default)]
    pub upper: Option<f64>,
    /// The joint this one follows.
    #[serde(default)]
    pub mimic: Option<MimicSpec>,
}

/// `mimic`: `value = multiplier * value(joint) + offset`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MimicSpec {
    /// The joint followed.
    pub joint: String,
    /// Factor, default 1.
    #[serde(default = "one")]
    pub multiplier: f64,
    /// Offset, default 0.
    #[serde(default)]
    pub offset: f64,
}

fn one() -> f64 {
    1.0
}

/// Where the sidecar of the asset at `path` is: `<stem>.joints.json` beside it.
pub fn sidecar_path(path: &Path) -> PathBuf {
    let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    path.with_file_name(format!("{stem}.joints.json"))
}

/// Reads and parses a sidecar file.
pub fn read_sidecar(path: &Path) -> Result<Sidecar, ImportError> {
    parse_sidecar(path, &text::read_text(path)?)
}

/// Parses sidecar text (`path` for errors).
pub fn parse_sidecar(path: &Path, text: &str) -> Result<Sidecar, ImportError> {
    serde_json::from_str(text).map_err(|e| ImportError::Parse {
        path: path.into(),
        format: "joints sidecar",
        reason: e.to_string(),
    })
}

impl JointSpec {
    /// The asset joint, with `parent` and `child` filled in where the record leaves them
    /// out (a glTF node's hierarchy parent and the node itself).
    pub fn to_raw(
        &self,
        default_parent: Option<&str>,
        default_child: Option<&str>,
    ) -> Result<RawJoint, ImportError> {
        let kind = RawKind::parse(&self.name, &self.kind)?;
        let end = |given: &Option<String>, default: Option<&str>, field| {
            given
                .clone()
                .or_else(|| default.map(String::from))
                .ok_or_else(|| ImportError::MissingField { joint: self.name.clone(), field })
        };
        let axis = match (kind, self.axis) {
            (RawKind::Fixed, axis) => axis.unwrap_or([1.0, 0.0, 0.0]),
            (_, Some(axis)) => axis,
            (_, None) => {
                return Err(ImportError::MissingField { joint: self.name.clone(), field: "axis" })
            }
        };
        let limits = match (self.lower, self.upper) {
            (Some(lo), Some(hi)) => Some((lo, hi)),
            _ => None,
        };
        Ok(RawJoint {
            name: self.name.clone(),
            kind,
            parent: end(&self.parent, default_parent, "parent")?,
            child: end(&self.child, default_child, "child")?,
            origin: self.origin.unwrap_or_default(),
            axis,
            limits,
            mimic: self.mimic.as_ref().map(|m| RawMimic {
                leader: m.joint.clone(),
                multiplier: m.multiplier,
                offset: m.offset,
            }),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn records_parse_and_unknown_fields_or_types_are_refused() {
        let path = Path::new("t.joints.json");
        let ok = r#"{"joints": [{"name": "j", "type": "revolute", "parent": "a", "child": "b",
            "axis": [0, 0, 1], "lower": 0, "upper": 1}]}"#;
        let raw = parse_sidecar(path, ok).expect("parses").joints[0].to_raw(None, None);
        assert_eq!(raw.expect("joint").limits, Some((0.0, 1.0)));
        let typo = r#"{"joints": [], "jionts": []}"#;
        assert!(matches!(parse_sidecar(path, typo), Err(ImportError::Parse { .. })));
        let ball = r#"{"joints": [{"name": "j", "type": "ball", "parent": "a", "child": "b"}]}"#;
        let spec = parse_sidecar(path, ball).expect("parses");
        let err = spec.joints[0].to_raw(None, None).expect_err("unknown type");
        assert!(matches!(err, ImportError::UnknownJointType { .. }), "{err}");
        assert!(err.to_string().contains("ball"));
    }
}
