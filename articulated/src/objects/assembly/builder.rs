//! The random assembly builder: draws segment trees and their motions until one is
//! plausible (every link large enough to be sampled, every motion visible, no two links
//! overlapping), all from the one seeded generator, so the same state gives the same object.

use pairs::math::{Real, Vector3};
use rand::Rng as _;

use super::boxes::flaps;
use super::collision::{collides, OVERLAP};
use super::growth::grow;
use super::links::{assemble, Assembly};
use super::motions::{plan, Motion};
use super::params::AssemblyParams;
use super::visibility::{motions_visible, SHIFT};
use crate::objects::ArticulatedObject;
use crate::seed::Rng;

/// Category name of every assembly.
const CATEGORY: &str = "assembly";
/// Draws of the motions before falling back to a box with two flaps.
const DRAFTS: usize = 4;

/// A random assembly of primitives with 2 to 6 (per `params`) moving segments.
///
/// The number of moving segments and how many of them slide are drawn first and kept, so
/// that translations and rotations come in the ratio asked for, while trees are drawn until
/// one takes those motions plausibly. Motions that `params.max_attempts` trees do not take
/// (six sliders, say) are drawn again; after `DRAFTS` such draws, which the defaults make
/// very rare, it returns a box with two hinged flaps.
pub fn random_assembly(rng: &mut Rng, params: &AssemblyParams) -> ArticulatedObject {
    let most = (*params.segments.end()).max(3);
    for _ in 0..DRAFTS {
        let moving = rng.random_range(params.moving.clone()).clamp(1, most - 1);
        let sliders =
            (0..moving).filter(|_| rng.random_bool(params.translation_probability)).count();
        // Many moving segments need many segments, for enough of them to be large enough.
        let fewest = (*params.segments.start()).clamp(moving + 3, most);
        for _ in 0..params.max_attempts {
            let count = rng.random_range(fewest..=most);
            let segments = grow(rng, count, (sliders, moving), params);
            let Some(motions) = plan(rng, &segments, (sliders, moving - sliders), params) else {
                continue;
            };
            let assembly = assemble(CATEGORY, &segments, &motions);
            if plausible(&assembly, params) {
                return assembly.object;
            }
        }
    }
    fallback(rng, params).object
}

/// Whether every link holds `min_area_fraction` of the area, every motion shows and no
/// two links overlap.
fn plausible(assembly: &Assembly, params: &AssemblyParams) -> bool {
    let object = &assembly.object;
    let areas: Vec<Real> = object.links.iter().map(|l| l.mesh.area()).collect();
    let total: Real = areas.iter().sum();
    if areas.iter().any(|&a| a < params.min_area_fraction * total) {
        return false;
    }
    let Some(bounds) = assembly.blocks.iter().flatten().copied().reduce(|a, b| a.union(&b)) else {
        return false;
    };
    let size = (bounds.max - bounds.min).norm();
    motions_visible(object, &assembly.blocks, SHIFT * size)
        && !collides(object, &assembly.blocks, OVERLAP * size)
}

/// A box with a hinged flap on each of two opposite faces.
fn fallback(rng: &mut Rng, params: &AssemblyParams) -> Assembly {
    let segments = flaps(rng);
    let max = rng.random_range(params.hinge_degrees.clone()).to_radians();
    let flap = Some(Motion::Hinge { out: Vector3::y(), max });
    assemble(CATEGORY, &segments, &[None, flap, flap])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::objects::Link;
    use crate::seed::{rng_for, Stream};
    use pairs::math::Point3;
    use pairs::JointKind;
    use parry3d::query::PointQuery;
    use parry3d::shape::ConvexPolyhedron;

    fn assemblies(count: u64) -> impl Iterator<Item = ArticulatedObject> {
        let params = AssemblyParams::default();
        (0..count).map(move |seed| random_assembly(&mut rng_for(seed, 0, Stream::Object), &params))
    }

    #[test]
    fn moving_parts_are_as_many_as_the_params_ask() {
        let params = AssemblyParams::default();
        let mut seen = [0; 7];
        for object in assemblies(150) {
            object.validate().unwrap_or_else(|e| panic!("{e}"));
            let moving = object.joints.len();
            assert!(params.moving.contains(&moving), "{moving} moving segments");
            seen[moving] += 1;
        }
        assert!(seen[2..=6].iter().all(|&n| n > 0), "{seen:?}");
    }

    #[test]
    fn translations_to_rotations_is_about_one_to_three() {
        let (mut slides, mut turns) = (0, 0);
        for object in assemblies(300) {
            for joint in &object.joints {
                match joint.kind {
                    JointKind::Prismatic => slides += 1,
                    JointKind::Revolute => turns += 1,
                }
            }
        }
        let share = slides as f64 / (slides + turns) as f64;
        assert!((share - 0.25).abs() < 0.04, "{slides} slides, {turns} turns");
    }

    /// Distance from `p` to the nearest convex piece of `link` (0 on its surface).
    fn distance(link: &Link, p: &Point3) -> Real {
        link.mesh
            .convex_pieces()
            .filter_map(ConvexPolyhedron::from_convex_hull)
            .map(|piece| piece.distance_to_local_point(p, true))
            .fold(Real::MAX, Real::min)
    }

    #[test]
    fn every_pivot_lies_on_the_contact_of_parent_and_child() {
        for object in assemblies(60) {
            for joint in &object.joints {
                let on_parent = distance(&object.links[joint.parent], &joint.pivot);
                let on_child = distance(&object.links[joint.child], &joint.pivot);
                assert!(on_parent < 1e-4 && on_child < 1e-4, "{joint:?}: {on_parent} {on_child}");
            }
        }
    }

    #[test]
    fn the_fallback_is_plausible() {
        let params = AssemblyParams::default();
        for seed in 0..20 {
            let assembly = fallback(&mut rng_for(seed, 0, Stream::Object), &params);
            assert!(plausible(&assembly, &params), "seed {seed}");
        }
    }
}
