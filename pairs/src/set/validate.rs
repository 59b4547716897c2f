//! The checks a set passes when built: shapes and ids, motions that are similarities of one
//! scale, view 0 at the identity, flows that agree with the motions.

use crate::error::SetError;
use crate::math::Real;
use crate::parts::{PartId, MAX_PARTS};
use crate::scan::Scan;
use crate::set::types::{SetInput, SetMode, SetProvenance, SetTruth, ViewKind};
use crate::transform::Similarity;

/// Tolerance on view 0's own motions, which must be the identity.
const IDENTITY_TOLERANCE: Real = 1e-5;
/// Tolerance on a rotation matrix's deviation from orthonormality (the pair record's).
const ROTATION_TOLERANCE: Real = 1e-3;
/// How far the motions of set parts grouped into one part of a pair may differ between its
/// two views (rotation and translation differences, summed; normalised units).
const GROUP_TOLERANCE: Real = 1e-3;
/// Tolerance on a stored flow against the motion it should equal, normalised units (the
/// pair record's).
const FLOW_TOLERANCE: Real = 1e-4;

/// The shapes and ids of a set: everything [`Set::pair`] indexes, so that it cannot panic.
pub(super) fn validate(
    input: &SetInput,
    truth: &SetTruth,
    provenance: &SetProvenance,
    scans: &[Option<Scan>],
) -> Result<(), SetError> {
    let set = input.id.as_str();
    let bad = |field: &'static str, index: usize, reason: String| SetError::Invalid {
        set: set.into(),
        field,
        index,
        reason,
    };
    let views = input.views.len();
    if views < 2 {
        return Err(bad("views", 0, format!("{views} views (a set has at least 2)")));
    }
    let kinds: Vec<ViewKind> = input.views.iter().map(|v| v.kind).collect();
    if SetMode::of(&kinds).is_none() {
        let reason = "views must be all full, all scanned, or view 0 full and the others \
                      scanned"
            .to_string();
        return Err(bad("views", 0, reason));
    }
    let per_view = [
        ("parts", truth.parts.len()),
        ("motions", truth.motions.len()),
        ("flows", truth.flows.len()),
        ("presence", truth.presence.len()),
        ("pair_parts", truth.pair_parts.len()),
        ("provenance.views", provenance.views.len()),
        ("scans", scans.len()),
    ];
    for (field, found) in per_view {
        if found != views {
            return Err(bad(field, 0, format!("{found} entries for {views} views")));
        }
    }
    let parts = truth.num_parts();
    if parts == 0 || parts > MAX_PARTS {
        return Err(bad("motions", 0, format!("{parts} parts (1 to {MAX_PARTS})")));
    }
    let n0 = input.views[0].cloud.len();
    for (k, view) in input.views.iter().enumerate() {
        let n = view.cloud.len();
        if n == 0 {
            return Err(bad("views", k, "empty cloud".into()));
        }
        if truth.parts[k].len() != n {
            return Err(bad("parts", k, format!("{} ids for {n} points", truth.parts[k].len())));
        }
        if let Some(i) = truth.parts[k].iter().position(|&s| usize::from(s) >= parts) {
            return Err(bad("parts", k, format!("point {i} holds part {}", truth.parts[k][i])));
        }
        if truth.motions[k].len() != parts {
            return Err(bad("motions", k, format!("{} motions", truth.motions[k].len())));
        }
        if truth.flows[k].len() != n0 {
            return Err(bad("flows", k, format!("{} vectors", truth.flows[k].len())));
        }
        if (view.kind == ViewKind::Scan) != scans[k].is_some() {
            return Err(bad("scans", k, "a scanned view has a camera, a full view none".into()));
        }
        let (presence, groups) = (&truth.presence[k], &truth.pair_parts[k]);
        if presence.len() != views || groups.len() != views {
            return Err(bad("presence", k, format!("rows for {views} views expected")));
        }
        for j in 0..views {
            if presence[j].len() != n || (j == k && !presence[j].iter().all(|&p| p)) {
                let reason = format!("row {j}: {n} flags expected (all 1 for its own view)");
                return Err(bad("presence", k, reason));
            }
            pair_groups(&groups[j], parts, j == k).map_err(|r| bad("pair_parts", k, r))?;
        }
    }
    for (k, motions) in truth.motions.iter().enumerate() {
        let scale = motions[0].scale;
        let broken = motions.iter().position(|m| {
            !m.is_finite() || m.rotation_defect() > ROTATION_TOLERANCE || m.scale != scale
        });
        if let Some(s) = broken {
            let reason = format!("part {s}: not finite, not a rotation, or another scale");
            return Err(bad("motions", k, reason));
        }
        if scale.is_nan() || scale <= 0.0 {
            return Err(bad("motions", k, format!("scale {scale} is not positive")));
        }
    }
    // Set parts grouped into one part of a pair must move alike between its two views.
    for i in 0..views {
        for j in (0..views).filter(|&j| j != i) {
            let groups = &truth.pair_parts[i][j];
            let between = |s: usize| truth.motions[j][s].compose(&truth.motions[i][s].inverse());
            for (s, &g) in groups.iter().enumerate() {
                let first = groups.iter().position(|&x| x == g).unwrap_or(s);
                let (a, b) = (between(s), between(first));
                let apart =
                    (a.rotation - b.rotation).norm() + (a.translation - b.translation).norm();
                if apart.is_nan() || apart > GROUP_TOLERANCE {
                    let reason = format!(
                        "row {j}: set parts {first} and {s} form one part but move apart by {apart}"
                    );
                    return Err(bad("pair_parts", i, reason));
                }
            }
        }
    }
    let identity = Similarity::identity();
    let off = |m: &Similarity| {
        (m.rotation - identity.rotation).norm() + m.translation.norm() + (m.scale - 1.0).abs()
    };
    if let Some(s) = truth.motions[0].iter().position(|m| off(m) > IDENTITY_TOLERANCE) {
        return Err(bad("motions", 0, format!("view 0's motion of part {s} is not the identity")));
    }
    let view0 = &input.views[0].cloud.points;
    for (k, (flow, motions)) in truth.flows.iter().zip(&truth.motions).enumerate() {
        for (i, ((x, f), &s)) in view0.iter().zip(flow).zip(&truth.parts[0]).enumerate() {
            let err = (motions[usize::from(s)].apply(x) - x - f).norm();
            // A NaN flow fails too: it is not within the tolerance.
            if err.is_nan() || err > FLOW_TOLERANCE * (1.0 + x.coords.norm()) {
                let reason =
                    format!("view {k}'s flow of point {i} differs from the motion by {err}");
                return Err(bad("flows", k, reason));
            }
        }
    }
    for (index, joint) in truth.joints.iter().enumerate() {
        let (part, parent) = (usize::from(joint.part), usize::from(joint.parent));
        if part >= parts || parent >= parts || part == parent {
            let reason = format!("joins parts {part} and {parent} of {parts}");
            return Err(bad("joints", index, reason));
        }
        let lengths = [joint.axis.len(), joint.pivot.len(), joint.value.len()];
        if lengths.iter().any(|&l| l != views) {
            return Err(bad("joints", index, format!("per-view lengths {lengths:?}, not {views}")));
        }
        let finite = joint.value.iter().all(|v| v.is_finite())
            && joint.pivot.iter().all(|p| p.coords.iter().all(|c| c.is_finite()))
            && joint.axis.iter().all(|a| (a.norm() - 1.0).abs() <= 1e-3);
        if !finite {
            let reason = "values and pivots must be finite and axes unit".to_string();
            return Err(bad("joints", index, reason));
        }
    }
    Ok(())
}

/// A row of `pair_parts`: one id per set part, numbered by first appearance from 0 (the
/// identity on a view's own row).
fn pair_groups(groups: &[PartId], parts: usize, own: bool) -> Result<(), String> {
    if groups.len() != parts {
        return Err(format!("{} ids for {parts} parts", groups.len()));
    }
    let mut next = 0usize;
    for (s, &g) in groups.iter().enumerate() {
        let g = usize::from(g);
        if g > next || (own && g != s) {
            return Err(format!("part {s} in pair part {g}: not numbered by first appearance"));
        }
        next = next.max(g + 1);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pair_groups_number_by_first_appearance() {
        assert!(pair_groups(&[0, 1, 0, 2], 4, false).is_ok());
        assert!(pair_groups(&[0, 2, 1], 3, false).is_err());
        assert!(pair_groups(&[0, 0], 2, true).is_err());
        assert!(pair_groups(&[0], 2, false).is_err());
    }
}
