//! Which segments move and how: hinges along an edge of the contact rectangle, twists about
//! the contact normal, and slides along the contact normal out of a sleeve.

use pairs::math::{Point3, Real, Vector3};
use pairs::transform::rotation_about;
use rand::seq::SliceRandom;
use rand::Rng as _;

use super::geometry::{unit, Block, Face};
use super::params::AssemblyParams;
use super::segments::Segment;
use super::sweeps::{hinge_edges, hinge_sweep, slide_sweep, subtree, twist_sweep, Claims, Edge};
use super::visibility::{shift, SHIFT};
use crate::seed::Rng;

/// How a moving segment moves relative to its parent.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Motion {
    /// Swings away from its parent about the edge of its footprint on the `out` side, by up
    /// to `max` radians.
    Hinge {
        /// Unit coordinate vector from the footprint's centre towards the hinge edge.
        out: Vector3,
        /// Largest opening, radians.
        max: Real,
    },
    /// Turns about the contact normal through `pivot`, a point of the footprint off its
    /// centre, so that no turn is a symmetry of the box.
    Twist {
        /// A point of the contact rectangle on the axis.
        pivot: Point3,
        /// Lowest and highest angle, radians.
        limits: (Real, Real),
    },
    /// Slides along the contact normal out of its sleeve, by up to `travel`.
    Slide {
        /// Longest travel.
        travel: Real,
    },
}

/// Motions for the tree's `slides` sliders (the segments grown to slide) and for `turns`
/// more of its segments, such that every link (a moving segment with what is welded to it)
/// holds at least `min_area_fraction` of the area; `None` where the tree cannot take them
/// or a slide would not show.
pub(super) fn plan(
    rng: &mut Rng,
    segments: &[Segment],
    (slides, turns): (usize, usize),
    params: &AssemblyParams,
) -> Option<Vec<Option<Motion>>> {
    let mut moving: Vec<bool> = segments.iter().map(|s| s.slider).collect();
    if moving.iter().filter(|&&m| m).count() != slides || !links_large(segments, &moving, params) {
        return None;
    }
    let mut order: Vec<usize> = (1..segments.len()).filter(|&i| !moving[i]).collect();
    order.shuffle(rng);
    let mut chosen = 0;
    for i in order {
        if chosen == turns {
            break;
        }
        moving[i] = true;
        if links_large(segments, &moving, params) {
            chosen += 1;
        } else {
            moving[i] = false;
        }
    }
    if chosen < turns {
        return None;
    }
    // Rooms hold the sleeves, so their bounds are at least the object's.
    let bounds = segments.iter().map(Segment::room).reduce(|a, b| a.union(&b))?;
    let min_shift = SHIFT * (bounds.max - bounds.min).norm();
    let mut motions = vec![None; segments.len()];
    let mut claims = Claims::default();
    for (i, segment) in segments.iter().enumerate().filter(|&(i, _)| moving[i]) {
        let face = segment.face?;
        let motion = if segment.slider {
            slide(segments, i, min_shift)?
        } else {
            turn(rng, segments, i, params, (min_shift, &claims))?
        };
        claims.claim(i, sweep(segments, i, face, motion));
        motions[i] = Some(motion);
    }
    Some(motions)
}

/// Boxes holding segment `i` (on `face`) and all on it over the range of `motion`.
fn sweep(segments: &[Segment], i: usize, face: Face, motion: Motion) -> Vec<Block> {
    match motion {
        Motion::Hinge { out, max } => hinge_sweep(segments, i, face, out, max),
        Motion::Twist { pivot, .. } => vec![twist_sweep(segments, i, face, pivot)],
        Motion::Slide { travel } => vec![slide_sweep(segments, i, face.normal(), travel)],
    }
}

/// Whether every link holds at least `min_area_fraction` of the total area when the
/// segments marked `moving` start links and the others are welded to their parents' links
/// (a slider's sleeve to its parent's).
fn links_large(segments: &[Segment], moving: &[bool], params: &AssemblyParams) -> bool {
    let mut link_of = vec![0; segments.len()];
    let mut areas = vec![0.0; segments.len()];
    for (i, segment) in segments.iter().enumerate() {
        let parent = segment.parent.map_or(0, |p| link_of[p]);
        link_of[i] = if moving[i] { i } else { parent };
        areas[link_of[i]] += segment.area;
        areas[parent] += segment.sleeve_walls().iter().map(Block::area).sum::<Real>();
    }
    let total: Real = areas.iter().sum();
    (0..segments.len())
        .filter(|&i| i == 0 || moving[i])
        .all(|i| areas[i] >= params.min_area_fraction * total)
}

/// A slide out of a sleeve as long as a slider's shaft (its head rests on the sleeve's rim),
/// if a quarter of its travel moves the surface of the slider and everything on it by
/// `min_shift` on average.
fn slide(segments: &[Segment], i: usize, min_shift: Real) -> Option<Motion> {
    let shows = shift(&pieces(segments, i), &segments[i].slide(0.25)) >= min_shift;
    shows.then_some(Motion::Slide { travel: segments[i].travel })
}

/// The boxes of segment `i` and all on it.
fn pieces(segments: &[Segment], i: usize) -> Vec<Block> {
    subtree(segments, i).flat_map(|s| segments[s].pieces.iter().copied()).collect()
}

/// With `twist_probability` a twist (see `swivel`), if a quarter of it shows by
/// `min_shift` and its sweep is clear of other segments and `claims`; else a hinge on an
/// edge that nothing of the segment's subtree reaches past, one whose swing is clear if
/// there is; else a twist all the same.
fn turn(
    rng: &mut Rng,
    segments: &[Segment],
    i: usize,
    params: &AssemblyParams,
    (min_shift, claims): (Real, &Claims),
) -> Option<Motion> {
    let face = segments[i].face?;
    let twist = rng.random_bool(params.twist_probability);
    let (pivot, limits) = swivel(rng, &segments[i], face, params);
    if twist && claims.clear(segments, i, &[twist_sweep(segments, i, face, pivot)]) {
        let far = if limits.1 >= -limits.0 { limits.1 } else { limits.0 };
        let quarter = rotation_about(&pivot, &face.normal(), 0.25 * far);
        if shift(&pieces(segments, i), &quarter) >= min_shift {
            return Some(Motion::Twist { pivot, limits });
        }
    }
    let range = |edge: &Edge| {
        if edge.on_parent_edge {
            params.edge_hinge_degrees.clone()
        } else {
            params.hinge_degrees.clone()
        }
    };
    let edges = hinge_edges(segments, i, face);
    let free: Vec<Edge> = edges
        .iter()
        .copied()
        .filter(|e| {
            let widest = range(e).end().to_radians();
            claims.clear(segments, i, &hinge_sweep(segments, i, face, e.out, widest))
        })
        .collect();
    let choice = if free.is_empty() { edges } else { free };
    if choice.is_empty() {
        return Some(Motion::Twist { pivot, limits });
    }
    let edge = choice[rng.random_range(0..choice.len())];
    Some(Motion::Hinge { out: edge.out, max: rng.random_range(range(&edge)).to_radians() })
}

/// A twist's pivot and limits for a segment on `face`: the pivot a point of its footprint
/// off its centre along its longer side, so that no turn is a symmetry of the box.
fn swivel(
    rng: &mut Rng,
    segment: &Segment,
    face: Face,
    params: &AssemblyParams,
) -> (Point3, (Real, Real)) {
    let long = usize::from(segment.footprint[1] > segment.footprint[0]);
    let side = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
    let offset = side * segment.footprint[long] * rng.random_range(0.3..0.6);
    let pivot = segment.contact + unit(face.plane_axes()[long]) * offset;
    let lo = -rng.random_range(params.twist_degrees.clone()).to_radians();
    let hi = rng.random_range(params.twist_degrees.clone()).to_radians();
    (pivot, (lo, hi))
}
