//! What PARIS, DigitalTwinArt and ArtGS read as ground truth, in a layout's world frame:
//! `trans.json` (`trans_info.{type, axis.o, axis.d, rotate|translate.{l, r}}`, degrees or
//! world units, start = `l`, end = `r`; PARIS `systems/utils.py:354-388`, DigitalTwinArt
//! `utils/articulation_utils.py:72-97`, ArtGS `utils/metrics.py:268-293`) and the state
//! meshes as triangle PLY files (`<state>{,_static,_dynamic,_dynamic_<i>}_rotate.ply`).

use std::fmt::Write as _;
use std::path::Path;

use pairs::math::{Isometry3, Matrix3, Point3, Real, Rotation3, UnitQuaternion, Vector3};
use pairs::renders::{ObjectTruth, RenderJoint, TrueJoint, WorldFrame};
use pairs::{JointKind, PartId};
use serde::Serialize;
use serde_json::{json, Value};

use super::write_bytes;
use crate::job::{bounds, posed_mesh};
use crate::{JointStates, RenderError, RenderJob};
use scanner::camera::Camera;

/// The layout's world frame centred on the object's bounding box over every state and
/// scaled so that its largest half extent is 1 (PARIS's `preprocess.py:245-252` when
/// `z_up`). The frame's fields hold `Real` values, so [`WorldFrame::point`] is exact.
pub fn normalised_frame(job: &RenderJob, z_up: bool) -> WorldFrame {
    let (lo, hi) = bounds(&job.scenes);
    let half = (hi - lo).max() * 0.5;
    let centre: [Real; 3] = nalgebra::center(&lo, &hi).coords.into();
    WorldFrame { scale: f64::from(1.0 / half.max(1e-9)), centre: centre.map(f64::from), z_up }
}

/// A camera-to-world matrix in `frame`, with OpenGL camera axes (x right, y up, looking
/// along -z): our OpenCV camera's y and z columns negated.
pub fn camera_to_world(frame: &WorldFrame, camera: &Camera) -> [[f64; 4]; 4] {
    let r = frame.axes()
        * camera.pose.rotation.to_rotation_matrix().matrix()
        * Matrix3::from_diagonal(&Vector3::new(1.0, -1.0, -1.0));
    let t = frame.point(&camera.centre());
    std::array::from_fn(|i| match i {
        3 => [0.0, 0.0, 0.0, 1.0],
        _ => [r[(i, 0)], r[(i, 1)], r[(i, 2)], t[i]].map(f64::from),
    })
}

/// `frame.json` of the PARIS and ArtGS layouts: the frame's scale and centre as the `Real`
/// values they are.
#[derive(Debug, Serialize)]
pub struct FrameFile {
    scale: Real,
    centre: [Real; 3],
    z_up: bool,
}

impl FrameFile {
    /// The file of `frame`.
    pub fn of(frame: &WorldFrame) -> Self {
        Self {
            scale: frame.scale as Real,
            centre: frame.centre.map(|c| c as Real),
            z_up: frame.z_up,
        }
    }
}

/// The ground truth of one object in a layout's world: its moving joints (axis in the
/// start state, change from start to end in radians or world units).
pub fn object_truth(job: &RenderJob, frame: &WorldFrame, folder: &str) -> ObjectTruth {
    let (lo, hi) = bounds(&job.scenes);
    let joints = part_joints(job)
        .iter()
        .map(|j| {
            let (pivot, axis, [start, end]) = in_world(frame, j);
            let state = end - start;
            TrueJoint {
                name: j.name.clone(),
                part: j.part,
                joint: RenderJoint {
                    kind: j.kind,
                    axis: [axis.x, axis.y, axis.z].map(f64::from),
                    pivot: [pivot.x, pivot.y, pivot.z].map(f64::from),
                    state: f64::from(state),
                },
            }
        })
        .collect();
    ObjectTruth {
        folder: folder.into(),
        object_id: job.object.object_id,
        category: job.object.object.category.clone(),
        world: *frame,
        diagonal: f64::from((hi - lo).norm() * frame.scale as Real),
        joints,
    }
}

/// The moving joints whose child starts a part, one per moving part, in part order, each as
/// its part's motion from state 0 to state 1 relative to the static part: the joint itself
/// for a part on the static part; for a part on a moving part (whose motion carries its
/// parent's), that motion as a screw (`pairs::screw`): a revolute joint about the screw's
/// axis by its angle when it turns (its slide along the axis left out), else a prismatic
/// joint along its translation, from value 0 to the angle or distance.
pub fn part_joints(job: &RenderJob) -> Vec<JointStates> {
    let mut joints: Vec<JointStates> = job
        .joints()
        .into_iter()
        .filter(|j| j.moves && job.part_of_link.iter().position(|&p| p == j.part) == Some(j.child))
        .map(|mut j| {
            if job.part_of_link[j.parent] != 0 && job.states.len() >= 2 {
                let motion = job.part_motion(j.part, 0, 1);
                let screw = pairs::screw::Screw::of(&pairs::Similarity::from_isometry(&motion));
                let (kind, value) = if screw.angle > 1e-4 {
                    (JointKind::Revolute, screw.angle)
                } else {
                    (JointKind::Prismatic, screw.slide)
                };
                j.kind = kind;
                j.value = vec![0.0, value];
                j.axis = vec![screw.axis.into(); 2];
                j.pivot = vec![screw.pivot.coords.into(); 2];
            }
            j
        })
        .collect();
    joints.sort_by_key(|j| j.part);
    joints
}

/// A joint's pivot and axis in state 0 and its values in states 0 and 1, in the world:
/// radians, or world units for a prismatic joint.
fn in_world(frame: &WorldFrame, joint: &JointStates) -> (Point3, Vector3, [Real; 2]) {
    let pivot = frame.point(&Point3::from(joint.pivot[0]));
    let axis = frame.direction(&Vector3::from(joint.axis[0]));
    let unit = match joint.kind {
        JointKind::Revolute => 1.0,
        JointKind::Prismatic => frame.scale as Real,
    };
    (pivot, axis, [joint.value[0] * unit, joint.value[1] * unit])
}

/// One `trans_info` entry: the joint's axis in state 0 and its values in states 0 and 1
/// (degrees or world units).
pub fn trans_entry(frame: &WorldFrame, joint: &JointStates) -> Value {
    let (o, d, [l, r]) = in_world(frame, joint);
    let (name, l, r) = match joint.kind {
        JointKind::Revolute => ("rotate", l.to_degrees(), r.to_degrees()),
        JointKind::Prismatic => ("translate", l, r),
    };
    json!({
        "type": name,
        "axis": {"o": [o.x, o.y, o.z], "d": [d.x, d.y, d.z]},
        name: {"l": l, "r": r},
    })
}

/// `trans.json`: one entry as an object when one part moves, a list in part order when
/// several do (DigitalTwinArt's multi-part form, `articulation_utils.py:72-97`).
pub fn trans_json(frame: &WorldFrame, joints: &[JointStates]) -> Value {
    let entries: Vec<Value> = joints.iter().map(|j| trans_entry(frame, j)).collect();
    match entries.as_slice() {
        [one] => json!({ "trans_info": one }),
        _ => json!({ "trans_info": entries }),
    }
}

/// The rigid motion of a `trans_info` entry from start to end: a rotation by `r - l`
/// degrees about `d` through `o` (right-handed), or a shift by `(r - l) d`.
pub fn entry_motion(info: &Value) -> Option<Isometry3> {
    let v3 = |v: &Value| -> Option<Vector3> {
        let a = v.as_array()?;
        let c = |i: usize| a.get(i).and_then(Value::as_f64).map(|x| x as Real);
        Some(Vector3::new(c(0)?, c(1)?, c(2)?))
    };
    let o = v3(info.get("axis")?.get("o")?)?;
    let d = pairs::math::try_unit(&v3(info.get("axis")?.get("d")?)?)?;
    let kind = info.get("type")?.as_str()?;
    let block = info.get(kind)?;
    let delta = (block.get("r")?.as_f64()? - block.get("l")?.as_f64()?) as Real;
    match kind {
        "rotate" => {
            let rot = UnitQuaternion::from_rotation_matrix(&Rotation3::new(d * delta.to_radians()));
            Some(Isometry3::from_parts((o - rot * o).into(), rot))
        }
        "translate" => Some(Isometry3::from_parts((d * delta).into(), UnitQuaternion::identity())),
        _ => None,
    }
}

/// Writes `<dir>/<state>/<state>{,_static,_dynamic[_<i>]}_rotate.ply` for each state
/// named in `states` (state `s` of the job), in the world frame.
pub fn write_meshes(
    job: &RenderJob,
    frame: &WorldFrame,
    dir: &Path,
    states: &[(usize, &str)],
) -> Result<(), RenderError> {
    let moving = job.parts - 1;
    for &(s, name) in states {
        let mut files: Vec<(String, Option<Vec<PartId>>)> = vec![
            (format!("{name}_rotate.ply"), None),
            (format!("{name}_static_rotate.ply"), Some(vec![0])),
        ];
        for i in 0..moving {
            let file = match moving {
                1 => format!("{name}_dynamic_rotate.ply"),
                _ => format!("{name}_dynamic_{i}_rotate.ply"),
            };
            files.push((file, Some(vec![(i + 1) as PartId])));
        }
        for (file, parts) in files {
            let (vertices, triangles) = posed_mesh(job, s, parts.as_deref());
            let vertices: Vec<Point3> = vertices.iter().map(|v| frame.point(v)).collect();
            write_bytes(&dir.join(name).join(file), ply_text(&vertices, &triangles).as_bytes())?;
        }
    }
    Ok(())
}

/// An ASCII triangle PLY (what pytorch3d's `load_ply` reads).
pub fn ply_text(vertices: &[Point3], triangles: &[[u32; 3]]) -> String {
    let mut out = String::with_capacity(vertices.len() * 40 + triangles.len() * 20 + 200);
    let _ = write!(
        out,
        "ply\nformat ascii 1.0\ncomment part_induction generator\nelement vertex {}\n\
         property float x\nproperty float y\nproperty float z\nelement face {}\n\
         property list uchar int vertex_indices\nend_header\n",
        vertices.len(),
        triangles.len()
    );
    for v in vertices {
        let _ = writeln!(out, "{} {} {}", v.x, v.y, v.z);
    }
    for t in triangles {
        let _ = writeln!(out, "3 {} {} {}", t[0], t[1], t[2]);
    }
    out
}
