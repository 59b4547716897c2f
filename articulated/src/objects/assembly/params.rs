//! The knobs of the random assembly builder.

use std::ops::RangeInclusive;

use pairs::math::Real;

/// What a random assembly may look like and how its segments may move.
///
/// The default follows the paper's category-free training data (Yi et al. 2018, section
/// "Training Dataset"): shapes of several segments of which 2 to 6 move, translations and
/// rotations in the ratio 1 : 3.
#[derive(Debug, Clone, PartialEq)]
pub struct AssemblyParams {
    /// Number of segments (the root primitive included); default 4..=9.
    pub segments: RangeInclusive<usize>,
    /// Number of moving segments, each becoming one link; default 2..=6 (as in the paper).
    pub moving: RangeInclusive<usize>,
    /// Probability that a moving segment slides (prismatic) rather than turns; default 0.25
    /// (translations : rotations = 1 : 3, as in the paper).
    pub translation_probability: f64,
    /// Probability that a turning segment tries to twist about its contact normal rather
    /// than swing on a hinge along an edge of its contact (a twist must show and have room
    /// to turn); default 0.4.
    pub twist_probability: f64,
    /// Range of a hinge's opening angle, degrees; default 60..=90.
    pub hinge_degrees: RangeInclusive<Real>,
    /// Range of a hinge's opening angle where the hinge lies on an edge of its parent box,
    /// so that the segment can fold past the parent's face, degrees; default 60..=120.
    pub edge_hinge_degrees: RangeInclusive<Real>,
    /// Range of each of a twist's two limits (one each way), degrees; default 70..=90.
    pub twist_degrees: RangeInclusive<Real>,
    /// A sliding segment's travel as a fraction of the length inserted in its sleeve;
    /// default 0.5..=0.6.
    pub travel_fraction: RangeInclusive<Real>,
    /// Smallest share of the total surface area that every link (root included) must have,
    /// so that each part gets enough of N = 512 area-weighted samples (about 26 on average,
    /// where the paper drops parts under 10); default 0.05.
    pub min_area_fraction: Real,
    /// Trees drawn for one draw of the motions before those are drawn again; default 50.
    pub max_attempts: usize,
}

impl Default for AssemblyParams {
    fn default() -> Self {
        Self {
            segments: 4..=9,
            moving: 2..=6,
            translation_probability: 0.25,
            twist_probability: 0.4,
            hinge_degrees: 60.0..=90.0,
            edge_hinge_degrees: 60.0..=120.0,
            twist_degrees: 70.0..=90.0,
            travel_fraction: 0.5..=0.6,
            min_area_fraction: 0.05,
            max_attempts: 50,
        }
    }
}
