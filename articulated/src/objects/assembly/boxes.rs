//! New segments: plain boxes and sliders standing on a face of their parent, and the
//! fallback assembly's flaps.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::geometry::{unit, Block, Face};
use super::params::AssemblyParams;
use super::segments::Segment;
use super::shape::Shape;
use super::visibility::{shift, SHIFT};
use crate::seed::Rng;

/// How deep a segment sinks into its parent, as a fraction of its footprint's smaller half
/// extent.
const SINK: Real = 0.02;

/// How much more than needed a slider's travel must show when it sprouts, as the tree
/// grows bigger after.
const SLIDER_MARGIN: Real = 1.2;

/// A segment of stacked boxes on `face` of segment `parent`, centred at `offset` from the
/// face's centre (along the face's plane axes); each tier is a footprint's half extents and
/// a height.
pub(super) fn place(
    segments: &[Segment],
    parent: usize,
    face: Face,
    offset: [Real; 2],
    tiers: &[([Real; 2], Real)],
) -> Segment {
    let host = &segments[parent];
    let [a, b] = face.plane_axes();
    let contact = host.face_centre(face) + unit(a) * offset[0] + unit(b) * offset[1];
    let mut base = 0.0;
    let pieces = tiers
        .iter()
        .map(|&(half, height)| {
            let spread = unit(a) * half[0] + unit(b) * half[1];
            let start = contact + face.normal() * base;
            base += height;
            Block::spanning(start - spread, start + spread + face.normal() * height)
        })
        .collect();
    let footprint = tiers[0].0;
    let mut segment = Segment::new(Some(parent), Shape::Box, pieces);
    segment.face = Some(face);
    segment.contact = contact;
    segment.footprint = footprint;
    segment.sink = SINK * footprint[0].min(footprint[1]);
    // A sleeve fits under a head; a plain box keeps a thin margin around it.
    segment.wall = match tiers.get(1) {
        Some((head, _)) => 0.6 * (head[0] - footprint[0]).min(head[1] - footprint[1]),
        None => 0.12 * footprint[0].min(footprint[1]),
    };
    segment.closed = host.closed | Face { positive: !face.positive, ..face }.bit();
    segment
}

/// The simplest assembly: a box with a flap on each of two opposite faces. Each flap
/// stays on its own side of the box whatever its hinge does, so nothing can collide.
pub(super) fn flaps(rng: &mut Rng) -> Vec<Segment> {
    let half = Vector3::from_fn(|_, _| rng.random_range(0.15..0.3));
    let block = Block { min: Point3::from(-half), max: Point3::from(half) };
    let mut segments = vec![Segment::new(None, Shape::Box, vec![block])];
    for positive in [true, false] {
        let footprint = [0.8 * half.y, 0.8 * half.z];
        let height = 0.5 * (footprint[0] + footprint[1]);
        let flap =
            place(&segments, 0, Face { axis: 0, positive }, [0.0; 2], &[(footprint, height)]);
        segments.push(flap);
    }
    segments
}

/// A slider on `face` of segment `parent` with a head of half extents `footprint` at
/// `offset` (see `place`): a shaft under the head, with room for a sleeve around the shaft
/// and below the head, and nothing on its sides. `None` where a quarter of its travel would
/// not move its surface visibly against the tree so far (only faces across the travel
/// show it, by at most a quarter of the travel: a quick bound before the mean).
pub(super) fn slider_on(
    rng: &mut Rng,
    segments: &[Segment],
    (parent, face): (usize, Face),
    (footprint, offset): ([Real; 2], [Real; 2]),
    params: &AssemblyParams,
) -> Option<Segment> {
    let shaft = footprint.map(|f| f * rng.random_range(0.45..0.6));
    let length = (shaft[0] + shaft[1]) * rng.random_range(1.0..1.8);
    let head = (footprint[0] + footprint[1]) * rng.random_range(0.15..0.35);
    let mut segment = place(segments, parent, face, offset, &[(shaft, length), (footprint, head)]);
    segment.slider = true;
    segment.travel = length * rng.random_range(params.travel_fraction.clone());
    let bounds = segments.iter().map(Segment::room).fold(segment.room(), |a, b| a.union(&b));
    let needed = SLIDER_MARGIN * SHIFT * (bounds.max - bounds.min).norm();
    let [a, b] = face.plane_axes();
    let across: Real =
        segment.pieces.iter().map(|p| 2.0 * (p.max - p.min)[a] * (p.max - p.min)[b]).sum();
    if 0.25 * segment.travel * across < needed * segment.area
        || shift(&segment.pieces, &segment.slide(0.25)) < needed
    {
        return None;
    }
    segment.closed |= [a, b].into_iter().fold(0, |bits, axis| {
        bits | Face { axis, positive: true }.bit() | Face { axis, positive: false }.bit()
    });
    Some(segment)
}
