//! Convex prisms from 2D outlines: blades, jaws, lenses, panels with rounded corners, and
//! the plain boxes that frames and bodies are laid out with.
//!
//! An outline is a list of points in a plane (u, v); a prism sweeps it across a depth range
//! d, and a placement maps (u, v, d) into the object frame, so that one outline serves any
//! plane a category needs.

use pairs::math::{Point3, Real};

use crate::mesh::Mesh;

/// The convex hull of `outline` swept over depths `d0..d1`, each point placed by `place`.
pub fn prism(
    outline: &[[Real; 2]],
    (d0, d1): (Real, Real),
    place: impl Fn(Real, Real, Real) -> Point3,
) -> Mesh {
    let points: Vec<Point3> = [d0, d1]
        .iter()
        .flat_map(|&d| outline.iter().map(move |&[u, v]| (u, v, d)))
        .map(|(u, v, d)| place(u, v, d))
        .collect();
    Mesh::hull(&points)
}

/// A rectangle of half sizes `half_u` x `half_v` centred at the origin with its corners
/// rounded by `radius` (clamped to fit), each corner drawn with `segments` steps.
pub fn rounded_rect(half_u: Real, half_v: Real, radius: Real, segments: u32) -> Vec<[Real; 2]> {
    let r = radius.clamp(0.0, half_u.min(half_v));
    let corners = [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)];
    corners
        .iter()
        .enumerate()
        .flat_map(|(k, &(su, sv))| {
            let start = k as Real * std::f32::consts::FRAC_PI_2;
            (0..=segments).map(move |i| {
                let a = start + std::f32::consts::FRAC_PI_2 * i as Real / segments.max(1) as Real;
                [su * (half_u - r) + r * a.cos(), sv * (half_v - r) + r * a.sin()]
            })
        })
        .collect()
}

/// A superellipse |u/a|^p + |v/b|^p = 1 with `segments` points: an ellipse for p = 2, a
/// rectangle with ever sharper corners as p grows; convex for p >= 1.
pub fn superellipse(half_u: Real, half_v: Real, exponent: Real, segments: u32) -> Vec<[Real; 2]> {
    (0..segments)
        .map(|i| {
            let a = std::f32::consts::TAU * i as Real / segments as Real;
            let (c, s) = (a.cos(), a.sin());
            let bend = |x: Real| x.signum() * x.abs().powf(2.0 / exponent);
            [half_u * bend(c), half_v * bend(s)]
        })
        .collect()
}

/// The axis-aligned box spanning two opposite corners given in any order, for parts laid
/// out by their corner points.
pub fn block(a: Point3, b: Point3) -> Mesh {
    Mesh::cuboid(a.inf(&b), a.sup(&b))
}
