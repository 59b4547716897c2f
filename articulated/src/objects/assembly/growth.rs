//! Growing the segment tree: boxes sprout on free faces of existing segments, never on a
//! face towards an ancestor (whose normal is opposite to one an ancestor grew along), which
//! keeps every subtree in the half-space outside the face it stands on; and never where
//! they would run into another segment's room.

use std::ops::Range;

use pairs::math::Real;
use rand::Rng as _;

use super::boxes::{place, slider_on};
use super::geometry::Face;
use super::params::AssemblyParams;
use super::root::root;
use super::segments::Segment;
use crate::seed::Rng;

/// How far a box set flush with an edge of its parent's face stays inside it, as a fraction
/// of the face's half extent.
const FLUSH_INSET: Real = 0.01;

/// Grows a tree of up to `count` segments for `moving` moving segments, `sliders` of them
/// sliders: a root primitive, then boxes on free faces.
pub(super) fn grow(
    rng: &mut Rng,
    count: usize,
    (sliders, moving): (usize, usize),
    params: &AssemblyParams,
) -> Vec<Segment> {
    // Many moving segments each need a good share of the area: wider boxes then.
    let least = (0.4 + 0.075 * moving.saturating_sub(2) as Real).min(0.7);
    let mut segments = vec![root(rng)];
    let mut placed = 0;
    for _ in 0..6 * count {
        if segments.len() >= count {
            break;
        }
        // Sliders grow at random steps, all of them before the tree is full.
        let wanted = sliders - placed;
        let slider = wanted > 0 && (count - segments.len() <= wanted || rng.random_bool(0.5));
        match sprout(rng, &segments, slider, least, params) {
            Ok(segment) => {
                placed += usize::from(slider);
                let (parent, face) = (segment.parent.unwrap_or(0), segment.face);
                segments[parent].used |= face.map_or(0, Face::bit);
                segments.push(segment);
            }
            // A slider that does not fit the widest face leaves it to others.
            Err(Some((parent, face))) if slider => segments[parent].used |= face.bit(),
            Err(_) => {}
        }
    }
    segments
}

/// One new segment on a free face of an existing one, or the face tried where it would run
/// into another segment (`None` where no face is free or a slider would not show). A
/// slider goes on the widest free face; other boxes cover at least `least` of their face
/// along each side.
fn sprout(
    rng: &mut Rng,
    segments: &[Segment],
    slider: bool,
    least: Real,
    params: &AssemblyParams,
) -> Result<Segment, Option<(usize, Face)>> {
    let (parent, face) =
        if slider { widest_face(segments) } else { any_face(rng, segments) }.ok_or(None)?;
    let cover = if slider { 0.7..0.95 } else { least..0.9 };
    let (footprint, offset) = spot(rng, segments[parent].face_half(face), cover);
    let segment = if slider {
        slider_on(rng, segments, (parent, face), (footprint, offset), params).ok_or(None)?
    } else {
        let height = (footprint[0] + footprint[1]) * rng.random_range(0.5..1.5);
        place(segments, parent, face, offset, &[(footprint, height)])
    };
    let room = segment.room();
    if segments.iter().enumerate().all(|(i, s)| i == parent || !s.room().overlaps(&room)) {
        Ok(segment)
    } else {
        Err(Some((parent, face)))
    }
}

/// A footprint inside a face with half extents `room`: its half extents, a fraction drawn
/// from `cover` of the face's, and its centre's offset from the face's centre.
fn spot(rng: &mut Rng, room: [Real; 2], cover: Range<Real>) -> ([Real; 2], [Real; 2]) {
    let mut footprint = [0.0; 2];
    let mut offset = [0.0; 2];
    for i in 0..2 {
        footprint[i] = room[i] * rng.random_range(cover.clone());
        let slack = room[i] - footprint[i];
        // Often flush with an edge of the face, as lids and flaps are; not quite, as convex
        // distance queries fail on side faces of two links that lie in one plane.
        let flush = slack - (FLUSH_INSET * room[i]).min(0.5 * slack);
        offset[i] = if rng.random_bool(0.3) {
            if rng.random_bool(0.5) {
                flush
            } else {
                -flush
            }
        } else {
            rng.random_range(-slack..=slack)
        };
    }
    (footprint, offset)
}

/// A random free face: of a segment drawn by area (bigger segments carry more children),
/// then one of its free faces.
fn any_face(rng: &mut Rng, segments: &[Segment]) -> Option<(usize, Face)> {
    let weight = |s: &Segment| if s.free_faces().next().is_some() { s.area } else { 0.0 };
    let total: Real = segments.iter().map(weight).sum();
    if total <= 0.0 {
        return None;
    }
    let mut pick = rng.random_range(0.0..total);
    let parent = segments.iter().position(|s| {
        pick -= weight(s);
        pick < 0.0
    })?;
    let faces: Vec<Face> = segments[parent].free_faces().collect();
    Some((parent, faces[rng.random_range(0..faces.len())]))
}

/// The free face with the most room for children: where a slider's travel shows best.
fn widest_face(segments: &[Segment]) -> Option<(usize, Face)> {
    let room = |&(i, f): &(usize, Face)| segments[i].face_half(f).iter().product::<Real>();
    segments
        .iter()
        .enumerate()
        .flat_map(|(i, s)| s.free_faces().map(move |f| (i, f)))
        .max_by(|a, b| room(a).total_cmp(&room(b)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::seed::{rng_for, Stream};

    /// Trees of 9 segments for 6 moving ones, 0 to 2 of them sliders, and their sliders.
    fn trees() -> impl Iterator<Item = (usize, Vec<Segment>)> {
        let params = AssemblyParams::default();
        (0..200).map(move |seed| {
            let rng = &mut rng_for(seed, 0, Stream::Object);
            let sliders = (seed % 3) as usize;
            (sliders, grow(rng, 9, (sliders, 6), &params))
        })
    }

    #[test]
    fn segments_stand_on_their_parents_and_keep_apart() {
        for (_, segments) in trees() {
            for (i, s) in segments.iter().enumerate().skip(1) {
                let (Some(p), Some(face)) = (s.parent, s.face) else { panic!("no parent") };
                let parent = &segments[p];
                // The footprint lies in the parent's face: base on its plane, inside its rect.
                assert!((s.block.span(face).0 - parent.block.span(face).1).abs() < 1e-5);
                let (centre, room) = (parent.face_centre(face), parent.face_half(face));
                for (k, axis) in face.plane_axes().into_iter().enumerate() {
                    let off = (s.contact[axis] - centre[axis]).abs() + s.footprint[k];
                    assert!(off <= room[k] + 1e-5, "segment {i} overhangs its parent's face");
                }
                let others = segments.iter().enumerate().filter(|&(j, o)| {
                    j != i && j != p && o.parent != Some(i) && o.room().overlaps(&s.room())
                });
                assert_eq!(others.count(), 0, "segment {i} runs into another");
            }
        }
    }

    #[test]
    fn every_subtree_stays_outside_the_face_it_stands_on() {
        for (_, segments) in trees() {
            for (i, s) in segments.iter().enumerate().skip(1) {
                let Some(face) = s.face else { panic!("no face") };
                let plane = s.block.span(face).0;
                for d in super::super::sweeps::subtree(&segments, i) {
                    assert!(segments[d].block.span(face).0 >= plane - 1e-5, "{d} under {i}");
                }
            }
        }
    }

    #[test]
    fn trees_mostly_have_the_sliders_asked_for() {
        let (mut fitted, mut asked) = (0, 0);
        for (sliders, segments) in trees().filter(|(sliders, _)| *sliders > 0) {
            let grown = segments.iter().filter(|s| s.slider).count();
            assert!(grown <= sliders);
            asked += 1;
            fitted += usize::from(grown == sliders);
        }
        assert!(fitted * 3 > asked * 2, "{fitted} of {asked}");
    }
}
