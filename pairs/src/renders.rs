//! Renders for image-based methods (`generator render`; docs/FORMAT.md, "Renders"): the
//! ground truth every layout writes at its root (`ground_truth.json`), and the joints-only
//! prediction files a method writes for a render (`joints.json`), both in the layout's
//! world frame and units. Scored by [`crate::metrics::render_joints`].

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::joints::JointKind;
use crate::math::{Matrix3, Point3, Real, Vector3};

/// The render record at a render folder's root.
pub const RENDER_FILE: &str = "render.json";
/// The ground truth at a render folder's root.
pub const GROUND_TRUTH_FILE: &str = "ground_truth.json";
/// The `format` of a joints-only prediction file.
pub const JOINTS_FORMAT: &str = "part-induction-joints";
/// Its version.
pub const JOINTS_VERSION: u32 = 1;
/// Most joints an object or a prediction may list (matching tries every assignment).
pub const MAX_JOINTS: usize = 8;

/// The map from the generator's object frame (Y up, object units) to a layout's world:
/// `x' = scale * C * (x - centre)`, `C` the Y-up to Z-up rotation when `z_up`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WorldFrame {
    /// World units per object unit.
    pub scale: f64,
    /// Subtracted first, object frame.
    pub centre: [f64; 3],
    /// Whether the world is Z-up (`C = [[1,0,0],[0,0,-1],[0,1,0]]`).
    pub z_up: bool,
}

impl WorldFrame {
    /// Our object frame, unchanged.
    pub fn identity() -> Self {
        Self { scale: 1.0, centre: [0.0; 3], z_up: false }
    }

    /// The rotation `C`.
    pub fn axes(&self) -> Matrix3 {
        if self.z_up {
            Matrix3::new(1.0, 0.0, 0.0, 0.0, 0.0, -1.0, 0.0, 1.0, 0.0)
        } else {
            Matrix3::identity()
        }
    }

    /// A point of the object frame in the world, in [`Real`] arithmetic (the frame's
    /// fields hold `Real` values widened, so this is the renderer's own arithmetic).
    pub fn point(&self, p: &Point3) -> Point3 {
        let centre = Point3::from(self.centre.map(|c| c as Real));
        Point3::from(self.axes() * (p - centre) * self.scale as Real)
    }

    /// A direction of the object frame in the world.
    pub fn direction(&self, d: &Vector3) -> Vector3 {
        self.axes() * d
    }
}

/// One joint: its type, axis direction, a point of its axis, and its state change from
/// the start state (0) to the end state (1): radians for a revolute joint (right-handed
/// about `axis`), world units along `axis` for a prismatic one.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RenderJoint {
    /// Revolute or prismatic.
    #[serde(rename = "type")]
    pub kind: JointKind,
    /// Axis direction, world frame (need not be unit).
    pub axis: [f64; 3],
    /// A point of the axis, world frame.
    pub pivot: [f64; 3],
    /// Change from start to end: radians or world units.
    pub state: f64,
}

impl RenderJoint {
    /// Why the joint cannot be scored, if it cannot: a non-finite number or a zero axis.
    pub fn problem(&self) -> Option<String> {
        let all = self.axis.iter().chain(&self.pivot).chain(std::iter::once(&self.state));
        if all.clone().any(|x| !x.is_finite()) {
            return Some("a number is not finite".into());
        }
        if self.axis.iter().all(|&x| x == 0.0) {
            return Some("the axis is zero".into());
        }
        None
    }
}

/// A true joint of a rendered object: one per moving part, in part order.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TrueJoint {
    /// The joint's name in the object.
    pub name: String,
    /// The part it moves (1, 2, ...; part 0 is static).
    pub part: u8,
    /// Type, axis (state 0), pivot and change, world frame.
    #[serde(flatten)]
    pub joint: RenderJoint,
}

/// The ground truth of one rendered object.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectTruth {
    /// Its folder in the layout, relative to the render's root (the key of predictions).
    pub folder: String,
    /// Object index in the render's selection.
    pub object_id: u32,
    /// Category (or the asset's name).
    pub category: String,
    /// Our object frame to the layout's world.
    pub world: WorldFrame,
    /// Diagonal of the object's bounding box over both states, world units.
    pub diagonal: f64,
    /// The moving joints.
    pub joints: Vec<TrueJoint>,
}

/// `ground_truth.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RenderTruth {
    /// The layout (`native`, `paris`, `dta`, `artgs`).
    pub layout: String,
    /// The generator's render seed.
    pub seed: u64,
    /// Every object.
    pub objects: Vec<ObjectTruth>,
}

/// A joints-only prediction file (`joints.json`): per object folder, the joints the
/// method found, in the layout's world frame.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointPredictions {
    /// [`JOINTS_FORMAT`].
    pub format: String,
    /// [`JOINTS_VERSION`].
    pub version: u32,
    /// The method's name.
    pub method: String,
    /// Object folder → its joints (an object left out has every joint missed).
    pub objects: BTreeMap<String, Vec<RenderJoint>>,
}

/// The record at the root of every render folder (`render.json`), whatever its layout:
/// what wrote it and with which settings, and its object folders. `C` is the render
/// settings (the renderer's `RenderConfig`; `serde_json::Value` for a reader that does not
/// know them), written in their own field order.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RenderRecord<C> {
    /// Version of the render folder format (the renderer's `RENDER_FORMAT_VERSION`).
    pub format_version: u32,
    /// The generator that wrote it.
    pub generator_version: String,
    /// The layout's name (`native`, `paris`, `dta`, `artgs`).
    pub layout: String,
    /// The seed the states and materials were drawn from.
    pub seed: u64,
    /// The render settings.
    pub config: C,
    /// The object folders, relative to the render folder, in object order.
    pub objects: Vec<String>,
}

/// Reads a render folder's `render.json`.
pub fn read_record<C: serde::de::DeserializeOwned>(
    dir: &Path,
) -> Result<RenderRecord<C>, RenderFileError> {
    let path = dir.join(RENDER_FILE);
    parse_json(&read_text(&path)?, &path)
}

/// Why a render's ground truth or a joints file cannot be used.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RenderFileError {
    /// The file cannot be read.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The file is not the documented JSON.
    #[error("{path}: {reason}")]
    Format {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        reason: String,
    },
    /// A joint cannot be scored.
    #[error("{path}: object {object}, joint {index}: {reason}")]
    Joint {
        /// The file.
        path: PathBuf,
        /// The object folder.
        object: String,
        /// The joint's index in the object's list.
        index: usize,
        /// What is wrong.
        reason: String,
    },
}

fn read_text(path: &Path) -> Result<String, RenderFileError> {
    std::fs::read_to_string(path)
        .map_err(|source| RenderFileError::Io { path: path.into(), source })
}

fn parse_json<T: serde::de::DeserializeOwned>(
    text: &str,
    path: &Path,
) -> Result<T, RenderFileError> {
    serde_json::from_str(text)
        .map_err(|e| RenderFileError::Format { path: path.into(), reason: e.to_string() })
}

/// Whether `dir` holds a render (a `ground_truth.json` at its root).
pub fn is_render(dir: &Path) -> bool {
    dir.join(GROUND_TRUTH_FILE).is_file()
}

/// Reads a render's ground truth.
pub fn read_truth(dir: &Path) -> Result<RenderTruth, RenderFileError> {
    let path = dir.join(GROUND_TRUTH_FILE);
    parse_truth(&read_text(&path)?, &path)
}

/// [`read_truth`] on the text of `path`.
pub fn parse_truth(text: &str, path: &Path) -> Result<RenderTruth, RenderFileError> {
    let path = path.to_path_buf();
    let truth: RenderTruth = parse_json(text, &path)?;
    for object in &truth.objects {
        if object.joints.len() > MAX_JOINTS {
            return Err(RenderFileError::Format {
                path,
                reason: format!("object {} has more than {MAX_JOINTS} joints", object.folder),
            });
        }
        for (index, j) in object.joints.iter().enumerate() {
            if let Some(reason) = j.joint.problem() {
                let (path, object) = (path.clone(), object.folder.clone());
                return Err(RenderFileError::Joint { path, object, index, reason });
            }
        }
    }
    Ok(truth)
}

/// Reads a joints-only prediction file and checks it against `truth`: the format and
/// version, every object folder known, every joint finite with a non-zero axis, at most
/// [`MAX_JOINTS`] per object.
pub fn read_predictions(
    path: &Path,
    truth: &RenderTruth,
) -> Result<JointPredictions, RenderFileError> {
    parse_predictions(&read_text(path)?, path, truth)
}

/// [`read_predictions`] on the text of `path`.
pub fn parse_predictions(
    text: &str,
    path: &Path,
    truth: &RenderTruth,
) -> Result<JointPredictions, RenderFileError> {
    let file: JointPredictions = parse_json(text, path)?;
    let bad = |reason: String| RenderFileError::Format { path: path.into(), reason };
    if file.format != JOINTS_FORMAT || file.version != JOINTS_VERSION {
        return Err(bad(format!(
            "format {:?} version {} is not {JOINTS_FORMAT:?} version {JOINTS_VERSION}",
            file.format, file.version
        )));
    }
    if file.method.trim().is_empty() {
        return Err(bad("the method name is empty".into()));
    }
    for (object, joints) in &file.objects {
        if !truth.objects.iter().any(|o| &o.folder == object) {
            return Err(bad(format!("object {object:?} is not in the render")));
        }
        if joints.len() > MAX_JOINTS {
            return Err(bad(format!("object {object} lists more than {MAX_JOINTS} joints")));
        }
        for (index, joint) in joints.iter().enumerate() {
            if let Some(reason) = joint.problem() {
                let (path, object) = (path.into(), object.clone());
                return Err(RenderFileError::Joint { path, object, index, reason });
            }
        }
    }
    Ok(file)
}
