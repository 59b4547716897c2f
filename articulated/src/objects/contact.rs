//! Contact pads: thin discs where a hinge's two links meet, so that they visibly touch at
//! every angle of the joint.

use pairs::math::{Point3, Real, Vector3};

use crate::mesh::Mesh;

/// Coaxial contact pads for a hinge: two thin discs of `radius` meeting on the plane through
/// `pivot` normal to `axis`, the parent's on the -`axis` side and the child's on the +`axis`
/// side; each goes inside its own link's hinge part, where the two links touch.
///
/// Turning about the axis keeps the pads in contact, and the checks' convex distance query
/// (GJK) between thin, centrally symmetric pieces stays within their thickness of the truth,
/// where between thick flush faces it can be off by half their thickness.
pub fn contact_pads(pivot: Point3, axis: Vector3, radius: Real) -> (Mesh, Mesh) {
    // A zero axis (no joint builds one) stacks the pads along z.
    let step = pairs::math::unit_or(&axis, Vector3::z()) * pad_thickness(radius);
    (
        Mesh::cylinder(pivot - step, pivot, radius, 12),
        Mesh::cylinder(pivot, pivot + step, radius, 12),
    )
}

/// Thickness of a contact pad `size` across: thin enough that the checks' distance query
/// errs by less than a fraction of a millimetre, thick enough to keep a proper hull.
pub fn pad_thickness(size: Real) -> Real {
    (0.02 * size).max(2e-4)
}
