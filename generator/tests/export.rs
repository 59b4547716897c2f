//! Objects exported as PartNet-Mobility folders (`generator export-objects`, issue 20) read
//! back through the URDF importer (`generator --assets`) into the same objects, giving the
//! same pairs for the same seed, for every category; and pairs record every joint's value by
//! name and both global poses, enough to rebuild each part's motion from the object alone.

use articulated::categories::CATEGORIES;
use articulated::kinematics::link_poses;
use articulated::objects::ArticulatedObject;
use assets::{load_asset, ImportOptions};
use assets::{Source, SourcedObject};
use generator::config::GeneratorConfig;
use generator::generate::{build_object, object_pairs_with, pairs_of_object, Variant};
use pairs::atomic::OutputError;
use pairs::math::{Isometry3, Matrix3, Point3, Real, Translation3, UnitQuaternion, Vector3};
use pairs::PairKind;
use simulators::urdf::link_name;
use simulators::{export_objects, write_object};

fn config(category: &str, kind: PairKind) -> GeneratorConfig {
    GeneratorConfig {
        kind,
        categories: vec![category.into()],
        points: 160,
        min_part_points: 4,
        seed: 11,
        ..Default::default()
    }
}

/// Every triangle as its three corner positions, degenerate ones (two corners at one
/// position, which the importer drops) left out.
fn triangles(object: &ArticulatedObject, link: usize) -> Vec<[Point3; 3]> {
    let mesh = &object.links[link].mesh;
    (0..mesh.triangles.len())
        .map(|t| mesh.corners(t))
        .filter(|[a, b, c]| a != b && b != c && a != c)
        .collect()
}

/// Exports object `index` of `config`, reads it back, and returns both.
fn round_trip(config: &GeneratorConfig, index: u32) -> (ArticulatedObject, ArticulatedObject) {
    let object = build_object(config, index).expect("a built-in object");
    let dir = tempfile::tempdir().expect("temp dir");
    let item = SourcedObject {
        object_id: index,
        object: object.clone(),
        source: Source::BuiltIn { split: "test".into() },
        surfaces: Vec::new(),
    };
    let written = write_object(
        &generator::objects::state_draw(config),
        &item,
        dir.path(),
        &Default::default(),
    )
    .expect("exported");
    let urdf = dir.path().join(&written.folder).join("mobility.urdf");
    let imported = load_asset(&urdf, &ImportOptions::default())
        .unwrap_or_else(|e| panic!("{}: {e}", urdf.display()))
        .object;
    (object, imported)
}

#[test]
fn every_category_reads_back_into_the_same_object_and_the_same_pairs() {
    for category in CATEGORIES {
        let config = config(category.name, PairKind::Sf2f);
        for index in [0, 3, 6] {
            let (object, imported) = round_trip(&config, index);
            let what = format!("{} object {index}", category.name);
            assert_eq!(imported.category, object.category, "{what}");
            assert_eq!(imported.joints, object.joints, "{what}: joints");
            assert_eq!(imported.mimics, object.mimics, "{what}: mimics");
            assert_eq!(imported.links.len(), object.links.len(), "{what}: links");
            for l in 0..object.links.len() {
                assert_eq!(triangles(&imported, l), triangles(&object, l), "{what}: link {l}");
            }
            let variant = Variant { index: 0, kind: PairKind::Sf2f, images: false };
            let built_in = object_pairs_with(&config, index, variant).expect("pairs");
            let read_back = pairs_of_object(&config, &imported, index, variant).expect("pairs");
            assert_eq!(built_in.len(), read_back.len(), "{what}");
            for (a, b) in built_in.iter().zip(&read_back) {
                assert_eq!(a.pair, b.pair, "{what}: pair {}", a.pair.id());
            }
        }
    }
}

#[test]
fn scanned_pairs_of_read_back_objects_are_identical_too() {
    for category in ["cabinet", "assembly", "windmill"] {
        let config = config(category, PairKind::Sp2p);
        let (_, imported) = round_trip(&config, 1);
        let variant = Variant { index: 0, kind: PairKind::Sp2p, images: false };
        let built_in = object_pairs_with(&config, 1, variant).expect("pairs");
        let read_back = pairs_of_object(&config, &imported, 1, variant).expect("pairs");
        for (a, b) in built_in.iter().zip(&read_back) {
            assert_eq!(a.pair, b.pair, "{category}: pair {}", a.pair.id());
        }
    }
}

fn isometry(pose: &pairs::Pose) -> Isometry3 {
    let rotation = Matrix3::from_row_slice(&pose.rotation);
    let rotation = UnitQuaternion::from_matrix(&rotation);
    Isometry3::from_parts(Translation3::from(Vector3::from(pose.translation)), rotation)
}

#[test]
fn provenance_rebuilds_every_part_motion_from_the_object() {
    for category in ["cabinet", "assembly", "robot_arm", "folding_table"] {
        let config = config(category, PairKind::Sf2f);
        let object = build_object(&config, 2).expect("object");
        let variant = Variant { index: 0, kind: PairKind::Sf2f, images: false };
        for generated in object_pairs_with(&config, 2, variant).expect("pairs") {
            let pair = &generated.pair;
            let provenance = pair.provenance();
            let values = |named: &std::collections::BTreeMap<String, Real>| -> Vec<Real> {
                assert_eq!(named.len(), object.joints.len(), "every joint is recorded");
                object.joints.iter().map(|j| named[&j.name]).collect()
            };
            let (pose_p, pose_q) = (
                isometry(provenance.pose_p.as_ref().expect("pose_p")),
                isometry(provenance.pose_q.as_ref().expect("pose_q")),
            );
            let links_p = link_poses(&object, &values(&provenance.joints_p));
            let links_q = link_poses(&object, &values(&provenance.joints_q));
            let (np, nq) = (pair.input().p.normalisation, pair.input().q.normalisation);
            for (link, part) in generated.parts.of_link.iter().enumerate() {
                let motion = &pair.truth().motions[usize::from(*part)];
                // A point of the link at rest, seen in both normalised frames.
                let rest = object.links[link].mesh.vertices[0];
                let p = ((pose_p * links_p[link]) * rest).coords - np.centre;
                let q = ((pose_q * links_q[link]) * rest).coords - nq.centre;
                let (p, q) = (Point3::from(p / np.scale), Point3::from(q / nq.scale));
                let moved = motion.apply(&p);
                assert!((moved - q).norm() < 1e-4, "{category} {}: link {link}", pair.id());
            }
        }
    }
}

#[test]
fn link_and_joint_names_follow_the_layout() {
    let config = config("folding_table", PairKind::Sf2f);
    let object = build_object(&config, 0).expect("object");
    let names: Vec<String> = object.joints.iter().map(|j| j.name.clone()).collect();
    let mut unique = names.clone();
    unique.sort_unstable();
    unique.dedup();
    assert_eq!(unique.len(), names.len(), "joint names are unique: {names:?}");
    assert_eq!(link_name(10), "link_10");
    let dir = tempfile::tempdir().expect("temp dir");
    let item = SourcedObject {
        object_id: 7,
        object,
        source: Source::Asset { path: "x".into() },
        surfaces: Vec::new(),
    };
    let written = write_object(
        &generator::objects::state_draw(&config),
        &item,
        dir.path(),
        &Default::default(),
    )
    .expect("exported");
    assert_eq!(written.folder, "000007_folding_table");
    let folder = dir.path().join(&written.folder);
    for file in ["mobility.urdf", "mobility_v2.json", "meta.json", "states.json"] {
        assert!(folder.join(file).is_file(), "{file}");
    }
    let states: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(folder.join("states.json")).expect("read"))
            .expect("json");
    let states = states["states"].as_array().expect("states");
    assert_eq!(states.len(), config.states_per_object as usize);
    assert_eq!(states[0].as_object().expect("a state").len(), names.len());
}

#[test]
fn a_non_empty_output_folder_is_refused_and_left_as_it_was() {
    let config = GeneratorConfig { objects: 2, ..config("laptop", PairKind::Sf2f) };
    let objects: Vec<SourcedObject> = (0..2)
        .map(|i| SourcedObject {
            object_id: i,
            object: build_object(&config, i).expect("object"),
            source: Source::BuiltIn { split: "test".into() },
            surfaces: Vec::new(),
        })
        .collect();
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("objects");
    std::fs::create_dir(&out).expect("mkdir");
    std::fs::write(out.join("notes.txt"), "mine").expect("write");
    let refused = export_objects(
        &generator::objects::state_draw(&config),
        &objects,
        &out,
        false,
        &Default::default(),
        |_| {},
    );
    assert!(matches!(refused, Err(simulators::ExportError::Output(OutputError::NotEmpty { .. }))));
    let left: Vec<_> = std::fs::read_dir(&out).expect("list").collect();
    assert_eq!(left.len(), 1);
    assert_eq!(std::fs::read_to_string(out.join("notes.txt")).expect("kept"), "mine");
    let written = export_objects(
        &generator::objects::state_draw(&config),
        &objects,
        &out,
        true,
        &Default::default(),
        |_| {},
    )
    .expect("forced");
    assert_eq!(written.len(), 2);
    assert!(!out.join("notes.txt").exists());
    assert!(out.join("000001_laptop/mobility.urdf").is_file());
    // Byte-identical when exported again.
    let again = dir.path().join("again");
    export_objects(
        &generator::objects::state_draw(&config),
        &objects,
        &again,
        false,
        &Default::default(),
        |_| {},
    )
    .expect("export");
    for file in ["000000_laptop/mobility.urdf", "000001_laptop/states.json", "objects.json"] {
        assert_eq!(
            std::fs::read(out.join(file)).expect("a"),
            std::fs::read(again.join(file)).expect("b"),
            "{file}"
        );
    }
}

#[test]
fn exported_user_assets_read_back_into_the_same_pairs() {
    // The example lamp in its three formats: continuous joints (given a range on import)
    // come out as revolute joints with that range, and read back the same.
    let examples = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/assets");
    let config = GeneratorConfig { points: 128, min_part_points: 4, seed: 5, ..Default::default() };
    let variant = Variant { index: 0, kind: PairKind::Sf2f, images: false };
    for asset in ["urdf/lamp.urdf", "obj/lamp.obj", "gltf/lamp.gltf"] {
        let original = load_asset(&examples.join(asset), &ImportOptions::default())
            .unwrap_or_else(|e| panic!("{asset}: {e}"))
            .object;
        let dir = tempfile::tempdir().expect("temp dir");
        let item = SourcedObject {
            object_id: 0,
            object: original.clone(),
            source: Source::Asset { path: asset.into() },
            surfaces: Vec::new(),
        };
        let written = write_object(
            &generator::objects::state_draw(&config),
            &item,
            dir.path(),
            &Default::default(),
        )
        .expect("exported");
        let urdf = dir.path().join(&written.folder).join("mobility.urdf");
        let read_back = load_asset(&urdf, &ImportOptions::default()).expect("reads back").object;
        assert_eq!(read_back.joints, original.joints, "{asset}");
        let a = pairs_of_object(&config, &original, 0, variant).expect("pairs");
        let b = pairs_of_object(&config, &read_back, 0, variant).expect("pairs");
        for (x, y) in a.iter().zip(&b) {
            assert_eq!(x.pair, y.pair, "{asset}: pair {}", x.pair.id());
        }
    }
}
