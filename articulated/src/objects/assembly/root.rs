//! The root primitive of a random assembly: a box, a round prism or a bevelled block of
//! random proportions, whose flat faces children stand on.

use pairs::math::{Point3, Vector3};
use rand::Rng as _;

use super::geometry::Block;
use super::segments::Segment;
use super::shape::Shape;
use crate::seed::Rng;

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
