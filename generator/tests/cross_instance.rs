//! Cross-instance pairs (XF2F, XF2P): P and Q observe two different objects of one
//! category, parts are matched by role (the same named links), and the record has no flow.

use articulated::categories::{Split, CATEGORIES};
use articulated::objects::ArticulatedObject;
use generator::config::GeneratorConfig;
use generator::generate::{build_object, generate_dataset, object_pairs, GenerateError};
use generator::label::same_structure;
use generator::shard::merge_shards;
use pairs::dataset::{Dataset, Shard, PAIRS_FILE};
use pairs::math::{Isometry3, Point3};
use pairs::{JointKind, PairKind};
use parry3d::query::PointQuery;
use parry3d::shape::TriMesh;

fn config_for(kind: PairKind, category: &str) -> GeneratorConfig {
    GeneratorConfig {
        kind,
        objects: 1,
        points: 256,
        categories: vec![category.into()],
        seed: 7,
        ..GeneratorConfig::of_kind(kind)
    }
}

/// The posed meshes of the links of `part`, in a cloud's normalised frame.
fn part_mesh(
    object: &ArticulatedObject,
    of_link: &[u8],
    poses: &[Isometry3],
    normalise: impl Fn(&Point3) -> Point3,
    part: u8,
) -> TriMesh {
    let (mut vertices, mut indices) = (Vec::new(), Vec::new());
    for (link, l) in object.links.iter().enumerate().filter(|(i, _)| of_link[*i] == part) {
        let offset = vertices.len() as u32;
        vertices.extend(l.mesh.vertices.iter().map(|v| normalise(&(poses[link] * v))));
        indices.extend(l.mesh.triangles.iter().map(|t| t.map(|i| i + offset)));
    }
    TriMesh::new(vertices, indices).expect("a part has triangles")
}

#[test]
fn every_category_pairs_two_different_objects_part_for_part() {
    let mut paired = 0;
    for category in CATEGORIES {
        let config = config_for(PairKind::Xf2f, category.name);
        let generated = match object_pairs(&config, 0) {
            Ok(generated) => generated,
            // A category whose instances differ in their links (user-built assemblies) is
            // left out, and says so.
            Err(GenerateError::NoPartner { category: c, .. }) => {
                assert_eq!(c, category.name);
                continue;
            }
            Err(e) => panic!("{}: {e}", category.name),
        };
        paired += 1;
        let object_p = build_object(&config, 0).expect("P's object");
        for g in &generated {
            let (input, truth, provenance) = (g.pair.input(), g.pair.truth(), g.pair.provenance());
            let id = &input.id;
            assert_eq!(input.kind, PairKind::Xf2f);
            let seed_q = provenance.seed_q.expect("Q's seed in the provenance");
            assert_ne!(seed_q, provenance.seed, "{id}: one seed for both objects");
            let object_q =
                build_object(&GeneratorConfig { seed: seed_q, ..config.clone() }, 0).expect("Q's");
            // Same roles, different shapes.
            assert!(same_structure(&object_p, &object_q), "{id}: links or joints differ");
            let differs = object_p
                .links
                .iter()
                .zip(&object_q.links)
                .any(|(a, b)| a.mesh.vertices != b.mesh.vertices);
            assert!(differs, "{id}: the two objects have the same geometry");
            // No flow and no correspondences between two shapes.
            assert!(truth.flow.is_none(), "{id}: a flow");
            assert!(truth.corr_mask.iter().all(|&m| !m), "{id}: a correspondence");
            // Part k of P lies on P's object's links of part k, and part k of Q on the same
            // named links of Q's object: matched parts have the same role.
            for part in 0..truth.num_parts() as u8 {
                let sides = [
                    (&object_p, &g.poses_p, &input.p, &truth.part_p, "P"),
                    (&object_q, &g.poses_q, &input.q, &truth.part_q, "Q"),
                ];
                for (object, poses, cloud, labels, side) in sides {
                    let norm = cloud.normalisation;
                    let mesh = part_mesh(object, &g.parts.of_link, poses, |x| norm.apply(x), part);
                    for (i, x) in
                        cloud.points.iter().enumerate().filter(|(i, _)| labels[*i] == part)
                    {
                        let d = mesh.distance_to_local_point(x, false);
                        assert!(d < 1e-4, "{id}: {side} point {i} is {d} off its part {part}");
                    }
                }
            }
            // A hinge's motion takes P's hinge onto Q's hinge.
            for joint in truth.joints.iter().filter(|j| j.kind == JointKind::Revolute) {
                let motion = &truth.motions[usize::from(joint.part)];
                let pivot = motion.apply(&joint.pivot_p);
                let axis = motion.rotation * joint.axis_p;
                assert!(
                    (pivot - joint.pivot_q).norm() < 1e-3,
                    "{id}: pivot {pivot} vs {}",
                    joint.pivot_q
                );
                assert!(
                    (axis - joint.axis_q).norm() < 1e-3,
                    "{id}: axis {axis} vs {}",
                    joint.axis_q
                );
            }
        }
    }
    assert!(paired + 1 >= CATEGORIES.len(), "only {paired} categories could be paired");
}

#[test]
fn a_scanned_cross_instance_set_is_deterministic_and_counts_what_it_left_out() {
    let config = GeneratorConfig {
        kind: PairKind::Xf2p,
        objects: 6,
        pairs_per_object: 2,
        points: 128,
        split: Split::Train,
        categories: vec!["laptop".into(), "assembly".into(), "cabinet".into()],
        seed: 3,
        ..GeneratorConfig::of_kind(PairKind::Xf2p)
    };
    let (a, b) = (tempfile::tempdir().expect("tempdir"), tempfile::tempdir().expect("tempdir"));
    let manifest = generate_dataset(&config, a.path(), false, None, |_| {}).expect("generate");
    generate_dataset(&config, b.path(), false, None, |_| {}).expect("generate again");
    let read = |d: &std::path::Path| std::fs::read(d.join(PAIRS_FILE)).expect("read");
    assert!(read(a.path()) == read(b.path()), "two runs differ");
    // Assemblies draw their links at random: they find no instance to match.
    assert_eq!(manifest.origin.left_out.get("assembly"), Some(&2));
    // Shards count their own left-out objects, and merging adds them up: the merged set is
    // the single run, manifest included.
    let shards: Vec<std::path::PathBuf> = [1, 0]
        .into_iter()
        .map(|index| {
            let dir = a.path().join(format!("shard-{index}"));
            let shard = Some(Shard { index, count: 2 });
            generate_dataset(&config, &dir, false, shard, |_| {}).expect("a shard");
            dir
        })
        .collect();
    let merged = a.path().join("merged");
    let merged_manifest = merge_shards(&shards, &merged, false, |_| {}).expect("merge");
    assert_eq!(merged_manifest.origin.left_out, manifest.origin.left_out);
    assert!(read(&merged) == read(a.path()), "merged shards differ from the single run");
    let pairs: Vec<_> = Dataset::open(a.path())
        .expect("open")
        .pairs()
        .expect("pairs")
        .collect::<Result<_, _>>()
        .expect("valid pairs");
    assert_eq!(pairs.len(), 8);
    for pair in &pairs {
        assert_eq!(pair.input().kind, PairKind::Xf2p);
        assert!(pair.scans().q.is_some() && pair.scans().p.is_none(), "{}", pair.id());
        assert!(pair.truth().flow.is_none());
        assert!(pair.provenance().seed_q.is_some());
    }
}
