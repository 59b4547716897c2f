//! Every category of the library, over many seeds: valid and varied objects, parts that stay
//! connected without passing through each other, motions that can be observed (no spinning
//! of a symmetric part), and pairs whose every part is visible at N = 512.
//!
//! Set `GENERATOR_CATEGORY=name` to check one category while writing it.

use articulated::categories::{Category, CATEGORIES};
use articulated::check::LinkShapes;
use articulated::kinematics::link_poses;
use articulated::objects::ArticulatedObject;
use articulated::sampling::SurfaceSampler;
use articulated::seed::{rng_for, Stream};
use generator::config::GeneratorConfig;
use generator::generate::object_pairs;
use generator::protocol::draw_state;
use pairs::math::{Point3, Real};
use pairs::parts::part_sizes;
use parry3d::query::PointQuery;
use parry3d::shape::TriMesh;

mod common;
use common::for_seeds;

/// A child link may float at most this far from its parent (fraction of the object's size).
const GAP_TOLERANCE: Real = 0.01;
/// Links may overlap at most this deep (fraction of the object's size): hinge pins, screws.
const PENETRATION_TOLERANCE: Real = 0.02;
/// A joint moved by a quarter of its range or more must move its link's surface on average
/// by at least this much (fraction of the object's size), or its motion is a symmetry.
const VISIBLE_MOTION: Real = 0.005;

/// The categories under test: all, or the one named by `GENERATOR_CATEGORY`.
fn categories() -> Vec<&'static Category> {
    let only = std::env::var("GENERATOR_CATEGORY").ok();
    let chosen: Vec<_> =
        CATEGORIES.iter().filter(|c| only.as_deref().is_none_or(|o| o == c.name)).collect();
    assert!(!chosen.is_empty(), "no category called {only:?}");
    chosen
}

fn build(category: &Category, seed: u64) -> ArticulatedObject {
    (category.build)(&mut rng_for(seed, 0, Stream::Object))
}

#[test]
fn categories_build_valid_varied_repeatable_objects() {
    for category in categories() {
        let (a, b) = (build(category, 0), build(category, 1));
        a.validate().unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(a.category, category.name);
        assert!(!a.joints.is_empty(), "{} has no joint", category.name);
        assert!(!category.splits.is_empty(), "{} is in no split", category.name);
        assert_ne!(a.links[0].mesh, b.links[0].mesh, "{} proportions do not vary", category.name);
        assert_eq!(a, build(category, 0), "{} is not repeatable", category.name);
    }
}

#[test]
fn parts_stay_connected_and_do_not_pass_through_each_other() {
    for category in categories() {
        for_seeds(12, |seed| {
            let object = build(category, seed);
            object.validate().map_err(|e| e.to_string())?;
            let shapes = LinkShapes::new(&object);
            let size = shapes.size();
            let mut rng = rng_for(seed, 0, Stream::States);
            let rest: Vec<Real> = object.joints.iter().map(|j| j.rest).collect();
            let lows: Vec<Real> = object.joints.iter().map(|j| j.limits.0).collect();
            let highs: Vec<Real> = object.joints.iter().map(|j| j.limits.1).collect();
            let drawn = (0..10).map(|_| draw_state(&object, 0.3, &mut rng));
            for state in [rest, lows, highs].into_iter().chain(drawn) {
                let poses = link_poses(&object, &state);
                for (j, gap) in
                    shapes.joint_gaps(&object, &poses, GAP_TOLERANCE * size).iter().enumerate()
                {
                    if let Some(gap) = gap {
                        let joint = &object.joints[j];
                        return Err(format!(
                            "{} seed {seed}: link {:?} floats {:.4} ({:.1}% of size) from its parent {:?} at {state:?}",
                            category.name,
                            object.links[joint.child].name,
                            gap,
                            100.0 * gap / size,
                            object.links[joint.parent].name,
                        ));
                    }
                }
                if let Some(hit) = shapes.deepest_penetration(&poses, PENETRATION_TOLERANCE * size)
                {
                    return Err(format!(
                        "{} seed {seed}: links {:?} and {:?} overlap {:.4} deep ({:.1}% of size) at {state:?}",
                        category.name,
                        object.links[hit.links.0].name,
                        object.links[hit.links.1].name,
                        hit.depth,
                        100.0 * hit.depth / size,
                    ));
                }
            }
            Ok(())
        });
    }
}

/// Mean distance from a link's surface posed by joint values `a` to its mesh posed by `b`.
fn mean_surface_shift(object: &ArticulatedObject, link: usize, a: &[Real], b: &[Real]) -> Real {
    let (pa, pb) = (link_poses(object, a)[link], link_poses(object, b)[link]);
    let mesh = &object.links[link].mesh;
    let posed: Vec<Point3> = mesh.vertices.iter().map(|v| pb * v).collect();
    let target = TriMesh::new(posed, mesh.triangles.clone()).expect("a valid link mesh");
    let alone = ArticulatedObject::new("probe", object.links[link].clone());
    let samples =
        SurfaceSampler::new(&alone).sample(&alone, 500, &mut rng_for(0, 0, Stream::Pair(0)));
    let total: Real =
        samples.iter().map(|s| target.distance_to_local_point(&(pa * s.rest), true)).sum();
    total / samples.len().max(1) as Real
}

#[test]
fn every_joint_motion_is_visible_not_a_symmetry() {
    for category in categories() {
        for_seeds(4, |seed| {
            let object = build(category, seed);
            let size = LinkShapes::new(&object).size();
            let rest: Vec<Real> = object.joints.iter().map(|j| j.rest).collect();
            for (j, joint) in object.joints.iter().enumerate() {
                let (lo, hi) = joint.limits;
                let far = if hi - joint.rest >= joint.rest - lo { hi } else { lo };
                for quarter in 1..=4 {
                    let mut moved = rest.clone();
                    moved[j] = joint.rest + (far - joint.rest) * quarter as Real / 4.0;
                    let shift = mean_surface_shift(&object, joint.child, &rest, &moved);
                    if shift < VISIBLE_MOTION * size {
                        return Err(format!(
                            "{} seed {seed}: moving joint {j} ({:?}) to {:.3} shifts its surface only {:.5} ({:.2}% of size): a symmetric or hidden motion",
                            category.name, object.links[joint.child].name, moved[j], shift, 100.0 * shift / size
                        ));
                    }
                }
            }
            Ok(())
        });
    }
}

#[test]
fn every_object_gives_its_pairs_with_every_part_visible() {
    for category in categories() {
        for_seeds(6, |seed| {
            let config = GeneratorConfig {
                seed,
                objects: 1,
                categories: vec![category.name.into()],
                ..Default::default()
            };
            let pairs = object_pairs(&config, 0).map_err(|e| e.to_string())?;
            if pairs.len() != 5 {
                return Err(format!("{} seed {seed}: {} pairs", category.name, pairs.len()));
            }
            for generated in &pairs {
                let truth = generated.pair.truth();
                let k = truth.num_parts();
                for sizes in [part_sizes(&truth.part_p, k), part_sizes(&truth.part_q, k)] {
                    if k < 2 || sizes.iter().any(|&s| s < 10) {
                        return Err(format!("{}: part sizes {sizes:?}", generated.pair.id()));
                    }
                }
            }
            Ok(())
        });
    }
}
