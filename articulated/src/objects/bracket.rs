//! Bracket hinges: a knuckle on the moving part turning between two cheek plates that hang
//! from a surface of the static part, the way folding legs, ladder frames and shelves hang.

use pairs::math::{Point3, Real, Vector3};

use super::articulated::Joint;
use super::contact::contact_pads;
use crate::mesh::Mesh;

/// Cheek plate thickness along the hinge axis, metres.
const CHEEK: Real = 0.006;

/// A hinge at `pivot` turning about `axis` by up to `max_angle`, its knuckle of radius `r`
/// spanning `half_span` either side of the pivot along the axis, hung from the surface at
/// `mount` (from the pivot to the surface, normal to the axis).
///
/// Returns the bracket for the static part (two cheeks flanking the knuckle and a cap
/// joining them to the surface), the knuckle for the moving part, and the joint.
pub fn bracket_hinge(
    pivot: Point3,
    axis: Vector3,
    half_span: Real,
    r: Real,
    mount: Vector3,
    max_angle: Real,
) -> (Mesh, Mesh, Joint) {
    // Zero vectors (no category passes one) fall back to a z axis mounted along y.
    let axis = pairs::math::unit_or(&axis, Vector3::z());
    let up = pairs::math::unit_or(&mount, Vector3::y());
    let below = pivot - up * 1.3 * r;
    let mut bracket: Vec<Mesh> = [-1.0, 1.0]
        .iter()
        .map(|&s| {
            let off = axis * s * (half_span + 0.5 * CHEEK);
            Mesh::beam(below + off, pivot + mount + off, 2.6 * r, CHEEK, axis)
        })
        .collect();
    // A cap fills any room between the knuckle and the surface.
    if mount.norm() > 1.01 * r {
        bracket.push(Mesh::beam(pivot + up * r, pivot + mount, 2.6 * r, 2.0 * half_span, axis));
    }
    let (pad_bracket, pad_knuckle) = contact_pads(pivot + axis * half_span, -axis, 0.8 * r);
    bracket.push(pad_bracket);
    let knuckle = Mesh::union([
        Mesh::cylinder(pivot - axis * half_span, pivot + axis * half_span, r, 12),
        pad_knuckle,
    ]);
    (Mesh::union(bracket), knuckle, Joint::hinge(pivot, axis, max_angle))
}
