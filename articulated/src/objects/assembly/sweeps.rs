//! Where a turning segment may go: the edges it can hinge about, and boxes that hold all
//! that turns with it over its whole range, to prefer motions that cannot reach any other
//! segment (the full check of the assembly then only rarely fails).

use pairs::math::{Point3, Real, Vector3};

use super::geometry::{Block, Face, EPS};
use super::segments::Segment;
use super::shape::Shape;

/// Segment `i` and every segment standing on it, directly or not.
pub(super) fn subtree(segments: &[Segment], i: usize) -> impl Iterator<Item = usize> + '_ {
    (i..segments.len()).filter(move |&d| d == i || descends(segments, d, i))
}

/// Whether segment `d` lies in the subtree of segment `i`.
fn descends(segments: &[Segment], mut d: usize, i: usize) -> bool {
    while let Some(p) = segments[d].parent {
        if p == i {
            return true;
        }
        d = p;
    }
    false
}

/// The bounding box of segment `i` and the rooms of all that stands on it.
fn reach(segments: &[Segment], i: usize) -> Block {
    subtree(segments, i)
        .skip(1)
        .map(|d| segments[d].room())
        .fold(segments[i].block, |a, b| a.union(&b))
}

/// A hinge edge of a segment: its outward direction from the footprint's centre (a unit
/// coordinate vector) and whether it lies on an edge of a box parent, so that the segment
/// may fold past a right angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Edge {
    /// Outward direction.
    pub out: Vector3,
    /// Whether it lies on the parent box's edge.
    pub on_parent_edge: bool,
}

/// The footprint edges segment `i` (standing on `face`) can swing about without anything
/// that swings with it passing below its parent's face.
pub(super) fn hinge_edges(segments: &[Segment], i: usize, face: Face) -> Vec<Edge> {
    let segment = &segments[i];
    let reach = reach(segments, i);
    let parent = segment.parent.map(|p| &segments[p]);
    let mut edges = Vec::new();
    for axis in face.plane_axes() {
        for positive in [true, false] {
            let side = Face { axis, positive };
            let edge = segment.block.span(side).1;
            if reach.span(side).1 > edge + EPS {
                continue;
            }
            // Flush with the parent's edge, but for the inset kept from it.
            let on_parent_edge = parent.is_some_and(|p| {
                p.shape == Shape::Box && p.block.span(side).1 - edge < 0.02 * p.block.half()[axis]
            });
            edges.push(Edge { out: side.normal(), on_parent_edge });
        }
    }
    edges
}

/// Boxes holding segment `i` and all on it swinging about `edge` by up to `max` radians:
/// everything stays within the farthest reach from the hinge line, above the parent's face,
/// and past a right angle also below it, beyond the edge.
pub(super) fn hinge_sweep(
    segments: &[Segment],
    i: usize,
    face: Face,
    out: Vector3,
    max: Real,
) -> Vec<Block> {
    let (reach, segment) = (reach(segments, i), &segments[i]);
    let line = segment.contact + out * segment.block.half()[out.iamax()];
    let normal = face.normal();
    let radius = corners(&reach)
        .map(|c| (c - line).dot(&out).hypot((c - line).dot(&normal)))
        .fold(0.0, Real::max);
    // The part of the disc about the hinge line between two heights over the parent's face,
    // on both sides of the edge or only beyond it.
    let band = |beyond_only: bool, (low, high): (Real, Real)| {
        let mut band = reach;
        let across = line + out * if beyond_only { 0.0 } else { -radius };
        let (a, b) = (across + normal * low, line + out * radius + normal * high);
        for k in [out.iamax(), face.axis] {
            band.min[k] = a[k].min(b[k]);
            band.max[k] = a[k].max(b[k]);
        }
        band
    };
    let mut sweep = vec![band(false, (0.0, radius))];
    if max > std::f32::consts::FRAC_PI_2 {
        sweep.push(band(true, (-radius * (max - std::f32::consts::FRAC_PI_2).sin(), 0.0)));
    }
    sweep
}

/// A box holding segment `i` and all on it twisting about the normal of `face` through
/// `pivot`, whatever the angle.
pub(super) fn twist_sweep(segments: &[Segment], i: usize, face: Face, pivot: Point3) -> Block {
    let reach = reach(segments, i);
    let [a, b] = face.plane_axes();
    let radius =
        corners(&reach).map(|c| (c[a] - pivot[a]).hypot(c[b] - pivot[b])).fold(0.0, Real::max);
    let mut sweep = reach;
    for k in [a, b] {
        sweep.min[k] = pivot[k] - radius;
        sweep.max[k] = pivot[k] + radius;
    }
    sweep
}

/// The space claimed by the motions chosen so far: for each moving segment, boxes that
/// hold all that moves with it over its range (with its ancestors at rest).
#[derive(Debug, Clone, Default)]
pub(super) struct Claims(Vec<(usize, Vec<Block>)>);

impl Claims {
    /// Whether `sweep`, of segment `i` and all on it, keeps clear of every segment outside
    /// that subtree (of the rooms where sleeves may stand, but of its parent's box, which the
    /// sweep starts on) and of the claims of segments neither above nor below it.
    pub fn clear(&self, segments: &[Segment], i: usize, sweep: &[Block]) -> bool {
        let parent = segments[i].parent;
        let apart = |b: &Block| sweep.iter().all(|s| !s.overlaps(b));
        let statics =
            segments.iter().enumerate().filter(|&(j, _)| j != i && !descends(segments, j, i));
        let claims =
            self.0.iter().filter(|(j, _)| !descends(segments, *j, i) && !descends(segments, i, *j));
        statics.into_iter().all(|(j, s)| apart(&if Some(j) == parent { s.block } else { s.room() }))
            && claims.flat_map(|(_, boxes)| boxes).all(apart)
    }

    /// Claims `sweep` for segment `i`.
    pub fn claim(&mut self, i: usize, sweep: Vec<Block>) {
        self.0.push((i, sweep));
    }
}

/// A box holding segment `i` and all on it sliding up to `travel` along `normal`.
pub(super) fn slide_sweep(segments: &[Segment], i: usize, normal: Vector3, travel: Real) -> Block {
    let reach = reach(segments, i);
    let moved = normal * travel;
    reach.union(&Block { min: reach.min + moved, max: reach.max + moved })
}

/// The eight corners of a box.
fn corners(block: &Block) -> impl Iterator<Item = Point3> + '_ {
    (0..8).map(move |c| {
        Point3::new(
            if c & 1 == 0 { block.min.x } else { block.max.x },
            if c & 2 == 0 { block.min.y } else { block.max.y },
            if c & 4 == 0 { block.min.z } else { block.max.z },
        )
    })
}
