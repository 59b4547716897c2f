//! Hollow tubes, built from flat staves since a hollow is not convex: the outer sleeve of a
//! telescopic column, or a collar turning about a post.

use pairs::math::{Isometry3, Point3, Real, UnitQuaternion, Vector3};

use crate::mesh::Mesh;

/// A tube from `a` to `b` of `staves` flat staves `wall` thick, whose bore is the regular
/// polygon around a circle of radius `bore`: a cylinder of radius `bore` on the same axis
/// slides and turns inside it touching the staves, without passing through them.
pub fn tube(a: Point3, b: Point3, bore: Real, wall: Real, staves: u32) -> Mesh {
    let axis = b - a;
    let step = std::f32::consts::TAU / staves as Real;
    // Staves meet at their outer corners, so the tube shows no gaps.
    let half_chord = (bore + wall) * (0.5 * step).tan();
    let half = Vector3::new(0.5 * wall, 0.5 * axis.norm(), half_chord);
    let local = Mesh::union((0..staves).map(|k| {
        let turn = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), k as Real * step);
        let centre = turn * Vector3::x() * (bore + 0.5 * wall);
        Mesh::oriented_cuboid(&Isometry3::from_parts(centre.into(), turn), half)
    }));
    // Tubes built along -y turn half a turn about x, where `rotation_between` has no answer.
    let rotation = UnitQuaternion::rotation_between(&Vector3::y(), &axis).unwrap_or_else(|| {
        UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f32::consts::PI)
    });
    let centre = nalgebra::center(&a, &b);
    local.transformed(&Isometry3::from_parts(centre.coords.into(), rotation))
}
