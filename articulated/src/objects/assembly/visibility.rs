//! Whether a motion shows: the mean distance from a link's surface at rest to the moved link,
//! as the category tests measure it (there from random samples, here from a grid of samples
//! on every face of the link's boxes).

use pairs::math::{Isometry3, Point3, Real, Vector3};
use pairs::JointKind;

use super::geometry::Block;
use crate::kinematics::joint_motion;
use crate::objects::ArticulatedObject;

/// Smallest mean surface shift of a joint moved by a quarter of its range, as a fraction of
/// the object's size: the category tests ask for 0.005 and their estimate from 500 random
/// samples comes out as low as 0.8 times this one.
pub(super) const SHIFT: Real = 0.0065;
/// Samples along each side of a box face.
const SAMPLES: usize = 3;

/// Whether every joint moved from rest by a quarter of its larger side moves its link's
/// surface on average by at least `min_shift`, and a twist (a turn both ways) by all of it
/// too: slides and hinges only show more as they go on, but a twist could come round
/// towards a symmetry.
pub(super) fn motions_visible(
    object: &ArticulatedObject,
    blocks: &[Vec<Block>],
    min_shift: Real,
) -> bool {
    object.joints.iter().all(|joint| {
        let (lo, hi) = joint.limits;
        let far = if hi - joint.rest >= joint.rest - lo { hi } else { lo };
        let twist = joint.kind == JointKind::Revolute && lo < joint.rest;
        let fractions: &[Real] = if twist { &[0.25, 1.0] } else { &[0.25] };
        fractions.iter().all(|fraction| {
            let value = joint.rest + (far - joint.rest) * fraction;
            shift(&blocks[joint.child], &joint_motion(joint, value)) >= min_shift
        })
    })
}

/// How far `motion` moves the surface of `blocks` on average: the mean distance from their
/// surface at rest to their moved surface (the sides of a box sliding along themselves do
/// not count).
pub(super) fn shift(blocks: &[Block], motion: &Isometry3) -> Real {
    // The distance from a point to the moved surface is that from the point moved back.
    let back = motion.inverse();
    let (mut sum, mut area) = (0.0, 0.0);
    let cells = (SAMPLES * SAMPLES) as Real;
    let at = |i: usize| (2 * i + 1) as Real / (2 * SAMPLES) as Real;
    for block in blocks {
        let d = block.max - block.min;
        for axis in 0..3 {
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            let face = d[u] * d[v];
            for side in [block.min[axis], block.max[axis]] {
                for k in 0..SAMPLES * SAMPLES {
                    let mut p = block.min;
                    p[axis] = side;
                    p[u] += d[u] * at(k / SAMPLES);
                    p[v] += d[v] * at(k % SAMPLES);
                    let q = back * p;
                    let near =
                        blocks.iter().map(|b| surface_distance(b, &q)).fold(Real::MAX, Real::min);
                    sum += near * face / cells;
                }
                area += face;
            }
        }
    }
    if area > 0.0 {
        sum / area
    } else {
        0.0
    }
}

/// Distance from `p` to the surface of an axis-aligned box.
fn surface_distance(block: &Block, p: &Point3) -> Real {
    let outside = (block.min - p).sup(&(p - block.max)).sup(&Vector3::zeros()).norm();
    if outside > 0.0 {
        outside
    } else {
        (0..3).map(|k| (p[k] - block.min[k]).min(block.max[k] - p[k])).fold(Real::MAX, Real::min)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use pairs::math::Translation3;
    use pairs::transform::rotation_about;

    fn bar() -> Block {
        Block { min: Point3::new(-0.4, -0.1, -0.05), max: Point3::new(0.4, 0.1, 0.05) }
    }

    #[test]
    fn a_half_turn_of_a_box_about_its_centre_does_not_show() {
        let half_turn = rotation_about(&Point3::origin(), &Vector3::z(), std::f32::consts::PI);
        assert!(shift(&[bar()], &half_turn) < 1e-5);
        let off_centre = rotation_about(&Point3::new(0.2, 0.0, 0.0), &Vector3::z(), 0.5);
        assert!(shift(&[bar()], &off_centre) > 0.02);
    }

    #[test]
    fn a_slide_shows_only_on_the_faces_across_it() {
        // Sliding along x by 0.05 shows on the two 0.2 x 0.1 end faces (0.04 of 0.26 area),
        // by the slide less whatever lies nearer another face; the sides do not show it.
        let slide = Isometry3::from(Translation3::new(0.05, 0.0, 0.0));
        let shown = shift(&[bar()], &slide);
        assert!(shown > 0.2 * 0.05 * 0.04 / 0.26 && shown <= 0.05 * 0.04 / 0.26 + 1e-6, "{shown}");
    }
}
