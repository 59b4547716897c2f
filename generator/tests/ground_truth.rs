//! The ground truth of generated pairs holds against the meshes it was made from, for every
//! category.

use articulated::categories::CATEGORIES;
use generator::config::GeneratorConfig;
use generator::generate::{build_object, object_pairs};
use pairs::math::Point3;
use pairs::parts::part_sizes;
use parry3d::query::PointQuery;
use parry3d::shape::TriMesh;

mod common;
use common::for_seeds;

fn config_for(category: &str) -> GeneratorConfig {
    GeneratorConfig {
        objects: 2,
        points: 256,
        categories: vec![category.into()],
        seed: 11,
        ..Default::default()
    }
}

/// Checks that every pair of object 0 of `config` maps P onto Q's posed surface, part by
/// part, and that the flow is the motion minus the position.
fn check_motions(config: &GeneratorConfig) -> Result<(), String> {
    let object = build_object(config, 0).map_err(|e| e.to_string())?;
    for generated in object_pairs(config, 0).map_err(|e| e.to_string())? {
        let (input, truth) = (generated.pair.input(), generated.pair.truth());
        let flow = truth.flow.as_deref().ok_or_else(|| format!("{}: no flow", input.id))?;
        let norm_q = input.q.normalisation;
        // Q's posed mesh in Q's normalised frame, one mesh per part.
        for part in 0..truth.num_parts() {
            let (mut vertices, mut indices) = (Vec::new(), Vec::new());
            for (link, l) in object.links.iter().enumerate() {
                if usize::from(generated.parts.of_link[link]) != part {
                    continue;
                }
                let offset = vertices.len() as u32;
                let posed =
                    l.mesh.vertices.iter().map(|v| norm_q.apply(&(generated.poses_q[link] * v)));
                vertices.extend(posed);
                indices.extend(l.mesh.triangles.iter().map(|t| t.map(|i| i + offset)));
            }
            let mesh = TriMesh::new(vertices, indices).map_err(|e| e.to_string())?;
            for (i, p) in input.p.points.iter().enumerate() {
                if usize::from(truth.part_p[i]) != part {
                    continue;
                }
                let moved: Point3 = truth.motions[part].apply(p);
                let d = mesh.distance_to_local_point(&moved, false);
                if d >= 1e-4 {
                    return Err(format!(
                        "{}: point {i} of part {part} lands {d} from Q's surface",
                        input.id
                    ));
                }
                if (moved - p - flow[i]).norm() >= 1e-5 {
                    return Err(format!("{}: flow {i} is not the motion", input.id));
                }
            }
        }
    }
    Ok(())
}

#[test]
fn motions_map_p_onto_q_surface_for_every_category_over_many_seeds() {
    for category in CATEGORIES {
        for_seeds(4, |seed| check_motions(&GeneratorConfig { seed, ..config_for(category.name) }));
    }
}

#[test]
fn parts_agree_between_p_and_q_and_moving_parts_moved() {
    for category in CATEGORIES {
        let config = config_for(category.name);
        for generated in object_pairs(&config, 0).expect("pairs") {
            let truth = generated.pair.truth();
            let k = truth.num_parts();
            assert!(k >= 2, "{}: nothing moves", generated.pair.id());
            for sizes in [part_sizes(&truth.part_p, k), part_sizes(&truth.part_q, k)] {
                assert!(sizes.iter().all(|&s| s >= 10), "{}: {sizes:?}", generated.pair.id());
            }
            // Every moving part has its joint, and its joint value changed.
            for part in 1..k {
                let joint =
                    truth.joints.iter().find(|j| usize::from(j.part) == part).expect("joint");
                assert_ne!(joint.value_p, joint.value_q);
            }
            // Parts are links grouped by motion: two parts never share a motion.
            for a in 0..k {
                for b in a + 1..k {
                    let (ma, mb) = (&truth.motions[a], &truth.motions[b]);
                    let same = (ma.rotation - mb.rotation).amax() < 1e-6
                        && (ma.translation - mb.translation).norm() < 1e-6;
                    assert!(!same, "{}: parts {a} and {b} move together", generated.pair.id());
                }
            }
        }
    }
}

#[test]
fn links_that_did_not_move_are_merged_into_one_part() {
    // Cabinets have a drawer and a door; with rest states common, some pairs keep one closed.
    let config = GeneratorConfig { rest_probability: 0.6, ..config_for("cabinet") };
    let mut merged = 0;
    for object_index in 0..6 {
        for generated in object_pairs(&config, object_index).expect("pairs") {
            let truth = generated.pair.truth();
            let values_equal = truth.joints.len() < 2;
            if values_equal {
                merged += 1;
                assert_eq!(truth.num_parts(), 2);
                // The link that stayed shares the base's part.
                assert!(generated.parts.of_link.iter().filter(|&&p| p == 0).count() >= 2);
            }
        }
    }
    assert!(merged > 0, "no pair kept a joint still; the merge was never exercised");
}

#[test]
fn correspondences_point_to_the_nearest_point_of_the_same_part() {
    let config = config_for("scissors");
    let generated = object_pairs(&config, 1).expect("pairs").remove(0);
    let (input, truth) = (generated.pair.input(), generated.pair.truth());
    for (i, p) in input.p.points.iter().enumerate() {
        assert!(truth.corr_mask[i]);
        let moved = truth.motions[usize::from(truth.part_p[i])].apply(p);
        let j = truth.corr_index[i] as usize;
        assert_eq!(truth.part_q[j], truth.part_p[i]);
        let best = input
            .q
            .points
            .iter()
            .zip(&truth.part_q)
            .filter(|(_, &k)| k == truth.part_p[i])
            .map(|(q, _)| (q - moved).norm())
            .fold(f32::MAX, f32::min);
        assert_eq!((input.q.points[j] - moved).norm(), best);
    }
}
