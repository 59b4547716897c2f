//! Invariant checks of a pair record, run on construction and on every read.

use crate::error::PairError;
use crate::ground_truth::GroundTruth;
use crate::input::{PairInput, Provenance};
use crate::math::{Matrix3, Point3, Real};
use crate::parts::{PartId, MAX_PARTS};
use crate::scan::Scans;

/// Tolerance on stored flow against the motion it should equal, normalised units.
const FLOW_TOLERANCE: Real = 1e-4;
/// Tolerance on a rotation matrix's deviation from orthonormality.
const ROTATION_TOLERANCE: Real = 1e-3;

/// Checks every invariant of a pair; the first violation is returned.
pub(crate) fn pair(input: &PairInput, truth: &GroundTruth) -> Result<(), PairError> {
    let id = &input.id;
    let (n_p, n_q) = (input.p.len(), input.q.len());
    nonempty(id, "p.points", n_p)?;
    nonempty(id, "q.points", n_q)?;
    points(id, "p.points", &input.p.points)?;
    points(id, "q.points", &input.q.points)?;
    normalisation(id, "p", &input.p.normalisation)?;
    normalisation(id, "q", &input.q.normalisation)?;
    length(id, "part_p", n_p, truth.part_p.len())?;
    length(id, "part_q", n_q, truth.part_q.len())?;
    match (&truth.flow, input.kind.cross_instance()) {
        (Some(flow), false) => length(id, "flow", n_p, flow.len())?,
        (None, true) => {}
        (Some(_), true) => {
            let reason =
                format!("a {} pair has no flow (two different shapes)", input.kind.as_str());
            return Err(inconsistent(id, "flow", 0, reason));
        }
        (None, false) => {
            let reason = format!("a {} pair needs its flow", input.kind.as_str());
            return Err(inconsistent(id, "flow", 0, reason));
        }
    }
    length(id, "corr_mask", n_p, truth.corr_mask.len())?;
    length(id, "corr_index", n_p, truth.corr_index.len())?;
    let parts = truth.num_parts();
    if parts == 0 || parts > MAX_PARTS {
        return Err(inconsistent(id, "motions", 0, format!("{parts} parts (1 to {MAX_PARTS})")));
    }
    part_ids(id, "part_p", &truth.part_p, parts)?;
    part_ids(id, "part_q", &truth.part_q, parts)?;
    motions(id, truth)?;
    flow(id, input, truth)?;
    correspondences(id, truth, n_q)?;
    joints(id, truth)
}

fn nonempty(id: &str, field: &'static str, n: usize) -> Result<(), PairError> {
    (n > 0).then_some(()).ok_or_else(|| inconsistent(id, field, 0, "empty cloud".into()))
}

fn length(id: &str, field: &'static str, expected: usize, found: usize) -> Result<(), PairError> {
    if expected == found {
        Ok(())
    } else {
        Err(PairError::Length { pair: id.into(), field, expected, found })
    }
}

fn finite(id: &str, field: &'static str, index: usize, values: &[Real]) -> Result<(), PairError> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(PairError::NonFinite { pair: id.into(), field, index })
    }
}

fn inconsistent(id: &str, field: &'static str, index: usize, reason: String) -> PairError {
    PairError::Inconsistent { pair: id.into(), field, index, reason }
}

fn points(id: &str, field: &'static str, pts: &[Point3]) -> Result<(), PairError> {
    pts.iter().enumerate().try_for_each(|(i, p)| finite(id, field, i, p.coords.as_slice()))
}

fn normalisation(
    id: &str,
    field: &'static str,
    n: &crate::cloud::Normalisation,
) -> Result<(), PairError> {
    finite(id, field, 0, n.centre.as_slice())?;
    finite(id, field, 0, &[n.scale])?;
    if n.scale > 0.0 {
        Ok(())
    } else {
        Err(inconsistent(id, field, 0, format!("normalisation scale {} is not positive", n.scale)))
    }
}

fn part_ids(id: &str, field: &'static str, ids: &[PartId], parts: usize) -> Result<(), PairError> {
    match ids.iter().position(|&k| usize::from(k) >= parts) {
        None => Ok(()),
        Some(index) => Err(PairError::PartOutOfRange {
            pair: id.into(),
            field,
            index,
            id: usize::from(ids[index]),
            parts,
        }),
    }
}

fn motions(id: &str, truth: &GroundTruth) -> Result<(), PairError> {
    let scale = truth.motions[0].scale;
    for (k, m) in truth.motions.iter().enumerate() {
        if !m.is_finite() {
            return Err(PairError::NonFinite { pair: id.into(), field: "motions", index: k });
        }
        if m.rotation_defect() > ROTATION_TOLERANCE {
            return Err(inconsistent(id, "motions", k, "rotation is not a rotation matrix".into()));
        }
        if m.scale <= 0.0 || m.scale != scale {
            return Err(inconsistent(id, "scale", k, "scale must be positive and shared".into()));
        }
    }
    Ok(())
}

fn flow(id: &str, input: &PairInput, truth: &GroundTruth) -> Result<(), PairError> {
    let Some(flow) = &truth.flow else { return Ok(()) };
    for (i, (p, f)) in input.p.points.iter().zip(flow).enumerate() {
        finite(id, "flow", i, f.as_slice())?;
        let moved = truth.motions[usize::from(truth.part_p[i])].apply(p);
        let err = (moved - p - f).norm();
        if err > FLOW_TOLERANCE * (1.0 + p.coords.norm()) {
            return Err(inconsistent(id, "flow", i, format!("differs from the motion by {err}")));
        }
    }
    Ok(())
}

fn correspondences(id: &str, truth: &GroundTruth, n_q: usize) -> Result<(), PairError> {
    for (i, (&mask, &index)) in truth.corr_mask.iter().zip(&truth.corr_index).enumerate() {
        match (mask, usize::try_from(index)) {
            (false, _) if index == -1 => {}
            (false, _) => {
                return Err(inconsistent(id, "corr_index", i, format!("{index} where mask is 0")))
            }
            (true, Ok(j)) if j < n_q => {
                if truth.part_q[j] != truth.part_p[i] {
                    let reason = format!("Q point {j} is of another part");
                    return Err(inconsistent(id, "corr_index", i, reason));
                }
            }
            (true, _) => {
                let reason = format!("{index} is not an index of Q ({n_q} points)");
                return Err(inconsistent(id, "corr_index", i, reason));
            }
        }
    }
    Ok(())
}

fn joints(id: &str, truth: &GroundTruth) -> Result<(), PairError> {
    for (j, joint) in truth.joints.iter().enumerate() {
        let values = [joint.value_p, joint.value_q];
        for v in [joint.axis_p.as_slice(), joint.axis_q.as_slice(), &values] {
            finite(id, "joints", j, v)?;
        }
        finite(id, "joints", j, joint.pivot_p.coords.as_slice())?;
        finite(id, "joints", j, joint.pivot_q.coords.as_slice())?;
        let part = usize::from(joint.part);
        if part == 0 || part >= truth.num_parts() {
            let reason = format!("moves part {part}, not a moving part of this pair");
            return Err(inconsistent(id, "joints", j, reason));
        }
        for axis in [&joint.axis_p, &joint.axis_q] {
            if (axis.norm() - 1.0).abs() > 1e-3 {
                return Err(inconsistent(id, "joints", j, "axis is not unit length".into()));
            }
        }
    }
    Ok(())
}

/// Checks the camera records of a pair's scanned sides.
pub(crate) fn scans(id: &str, scans: &Scans) -> Result<(), PairError> {
    for (field, scan) in [("scan_p", &scans.p), ("scan_q", &scans.q)] {
        let Some(scan) = scan else { continue };
        let k = &scan.intrinsics;
        finite(id, field, 0, &[k.fx, k.fy, k.cx, k.cy, scan.depth_scale])?;
        finite(id, field, 0, scan.rotation.as_slice())?;
        finite(id, field, 0, scan.translation.as_slice())?;
        if k.width == 0 || k.height == 0 || k.fx <= 0.0 || k.fy <= 0.0 || scan.depth_scale <= 0.0 {
            let reason = "image size, focal lengths and depth scale must be positive".into();
            return Err(inconsistent(id, field, 0, reason));
        }
        let defect = (scan.rotation.transpose() * scan.rotation - Matrix3::identity()).norm();
        if defect > ROTATION_TOLERANCE || scan.rotation.determinant() <= 0.0 {
            let reason = "extrinsic rotation is not a rotation matrix".into();
            return Err(inconsistent(id, field, 0, reason));
        }
    }
    Ok(())
}

/// The provenance's joint values are finite and its global poses are rigid.
pub(crate) fn provenance(id: &str, provenance: &Provenance) -> Result<(), PairError> {
    for (field, values) in [
        ("provenance.joints_p", &provenance.joints_p),
        ("provenance.joints_q", &provenance.joints_q),
    ] {
        for (index, (_, &value)) in values.iter().enumerate() {
            finite(id, field, index, &[value])?;
        }
    }
    for (field, pose) in
        [("provenance.pose_p", &provenance.pose_p), ("provenance.pose_q", &provenance.pose_q)]
    {
        let Some(pose) = pose else { continue };
        finite(id, field, 0, &pose.rotation)?;
        finite(id, field, 0, &pose.translation)?;
        let rotation = Matrix3::from_row_slice(&pose.rotation);
        let defect = (rotation.transpose() * rotation - Matrix3::identity()).norm();
        if defect > ROTATION_TOLERANCE || rotation.determinant() <= 0.0 {
            return Err(inconsistent(id, field, 0, "rotation is not a rotation matrix".into()));
        }
    }
    Ok(())
}
