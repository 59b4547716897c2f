//! The shape of a segment within its bounding box: a box, a 12-sided prism or a bevelled
//! block (only the root is other than a box), with its area, flat faces and corners.

use pairs::math::{Point3, Real, Vector3};

use super::geometry::{Block, Face};

/// tan 15 degrees: a 12-gon's half side over its inradius.
const TAN_15: Real = 0.267_949_2;

/// The shape of a segment within its bounding box; only the root is other than a box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Shape {
    /// Boxes filling their blocks.
    Box,
    /// A 12-sided prism along `axis` whose flat sides face the block's faces.
    Cylinder {
        /// Coordinate axis of the prism.
        axis: usize,
    },
    /// A box with every edge bevelled by `chamfer`.
    Blob {
        /// How far each face is inset from its block's edges.
        chamfer: Real,
    },
}

impl Shape {
    /// Surface area of a prism or bevelled block filling `block` (`None` for boxes, which
    /// count their own pieces).
    pub fn area(self, block: &Block) -> Option<Real> {
        let h = block.half();
        match self {
            Shape::Box => None,
            Shape::Cylinder { axis } => {
                let (r, length) = (h[(axis + 1) % 3], 2.0 * h[axis]);
                Some(24.0 * TAN_15 * r * (r + length))
            }
            // Six inset faces, twelve bevels c * sqrt 2 wide, eight corner triangles.
            Shape::Blob { chamfer: c } => {
                let inset = h.add_scalar(-c);
                let faces = 8.0 * (inset.x * inset.y + inset.y * inset.z + inset.z * inset.x);
                let bevels = 8.0 * std::f32::consts::SQRT_2 * c * inset.sum();
                Some(faces + bevels + 4.0 * (3.0 as Real).sqrt() * c * c)
            }
        }
    }

    /// Half extents, along `face.plane_axes()`, of the flat rectangle centred on `face` of
    /// the shape filling `block`.
    pub fn face_half(self, block: &Block, face: Face) -> [Real; 2] {
        let half = block.half();
        let [a, b] = face.plane_axes();
        match self {
            Shape::Box => [half[a], half[b]],
            Shape::Blob { chamfer } => [half[a] - chamfer, half[b] - chamfer],
            // A square inside the cap's inscribed circle.
            Shape::Cylinder { axis } if axis == face.axis => [0.7 * half[a], 0.7 * half[b]],
            // One flat side of the prism: its full length, its width across.
            Shape::Cylinder { axis } => {
                let across = |k: usize| if k == axis { half[k] } else { half[k] * TAN_15 };
                [across(a), across(b)]
            }
        }
    }

    /// The corners of a prism or bevelled block filling `block`, whose hull is the shape
    /// (`None` for boxes).
    pub fn corners(self, block: &Block) -> Option<Vec<Point3>> {
        let (centre, half) = (block.centre(), block.half());
        match self {
            Shape::Box => None,
            Shape::Cylinder { axis } => {
                // Corners at 15 + 30k degrees put flat sides across both cross axes.
                let [a, b] = Face { axis, positive: true }.plane_axes();
                let radius = half[a] / (15.0 as Real).to_radians().cos();
                let corner = |i: usize| {
                    let angle = (15.0 + 30.0 * (i % 12) as Real).to_radians();
                    let mut p = centre;
                    p[axis] += if i < 12 { -half[axis] } else { half[axis] };
                    p[a] += radius * angle.cos();
                    p[b] += radius * angle.sin();
                    p
                };
                Some((0..24).map(corner).collect())
            }
            Shape::Blob { chamfer } => {
                // Each corner is cut by a triangle: one point per axis, inset along the others.
                let corner = |i: usize| {
                    let (corner, full) = (i / 3, i % 3);
                    centre
                        + Vector3::from_fn(|k, _| {
                            let sign = if corner >> k & 1 == 0 { -1.0 } else { 1.0 };
                            sign * if k == full { half[k] } else { half[k] - chamfer }
                        })
                };
                Some((0..24).map(corner).collect())
            }
        }
    }
}
