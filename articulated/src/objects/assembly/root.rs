//! The root primitive of a random assembly: a box, a round prism or a bevelled block of
//! random proportions, whose flat faces children stand on.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::geometry::{Block, Face};
use super::segments::Segment;
use crate::seed::Rng;

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

/// A box, a round prism or a bevelled block of random proportions, centred at the origin.
pub(super) fn root(rng: &mut Rng) -> Segment {
    let mut half = Vector3::from_fn(|_, _| rng.random_range(0.12..0.35));
    let shape = match rng.random_range(0..4) {
        0 | 1 => Shape::Box,
        2 => Shape::Cylinder { axis: rng.random_range(0..3) },
        _ => Shape::Blob { chamfer: half.min() * rng.random_range(0.15..0.35) },
    };
    if let Shape::Cylinder { axis } = shape {
        // A round cross-section: both cross axes share the radius.
        half[(axis + 2) % 3] = half[(axis + 1) % 3];
    }
    Segment::new(None, shape, vec![Block { min: Point3::from(-half), max: Point3::from(half) }])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::seed::{rng_for, Stream};

    #[test]
    fn roots_have_their_analytic_areas_and_fill_their_blocks() {
        for seed in 0..40 {
            let root = root(&mut rng_for(seed, 0, Stream::Object));
            let mesh = root.mesh();
            let error = (mesh.area() - root.area).abs() / root.area;
            assert!(error < 1e-3, "{:?}: {} vs {}", root.shape, mesh.area(), root.area);
            let (lo, hi) = pairs::math::bounds(&mesh.vertices).expect("a root has vertices");
            assert!((lo - root.block.min).norm() < 1e-4 && (hi - root.block.max).norm() < 1e-4);
        }
    }
}
