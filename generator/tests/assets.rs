//! User assets (issue 9): the three formats of the example lamp give the same object and
//! the same pairs, URDF forward kinematics matches hand-computed poses, imported objects
//! pass the plausibility and ground-truth checks of the built-in categories, and a folder
//! of assets becomes a dataset even when some of its assets are broken.

use std::path::{Path, PathBuf};

use articulated::check::LinkShapes;
use articulated::kinematics::link_poses;
use articulated::objects::ArticulatedObject;
use articulated::seed::{rng_for, Stream};
use assets::{load_asset, ImportOptions};
use generator::asset_dataset::{generate_asset_dataset, load_assets};
use generator::config::GeneratorConfig;
use generator::generate::{pairs_of_object, GeneratedPair, Variant};
use generator::protocol::draw_state;
use nalgebra::{Isometry3, Point3, Rotation3, Translation3, Unit, UnitQuaternion, Vector3};
use pairs::dataset::{Dataset, Manifest};
use pairs::math::Real;
use pairs::PairKind;
use parry3d::query::PointQuery;
use parry3d::shape::TriMesh;

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/assets")
}

fn lamp(format: &str) -> ArticulatedObject {
    let path = examples().join(format);
    load_asset(&path, &ImportOptions::default()).unwrap_or_else(|e| panic!("{format}: {e}")).object
}

fn small() -> GeneratorConfig {
    GeneratorConfig { points: 128, min_part_points: 4, seed: 5, ..Default::default() }
}

fn pairs_of(object: &ArticulatedObject, kind: PairKind) -> Vec<GeneratedPair> {
    let config = GeneratorConfig { kind, ..small() };
    let variant = Variant { index: 0, kind, images: false };
    pairs_of_object(&config, object, 0, variant).expect("the lamp gives its pairs")
}

#[test]
fn the_three_formats_of_the_lamp_give_one_object_and_identical_pairs() {
    let obj = lamp("obj/lamp.obj");
    assert_eq!(obj.category, "lamp");
    let names: Vec<&str> = obj.links.iter().map(|l| l.name.as_str()).collect();
    assert_eq!(names, ["base", "arm", "shade"], "the pole is welded into the base");
    assert_eq!(obj.links[0].mesh.convex_pieces().count(), 2, "base and pole stay two pieces");
    for other in ["urdf/lamp.urdf", "gltf/lamp.gltf"] {
        assert_eq!(lamp(other), obj, "{other} differs from the OBJ");
    }
    let reference: Vec<_> = pairs_of(&obj, PairKind::Sf2f).into_iter().map(|g| g.pair).collect();
    assert_eq!(reference.len(), 5);
    for other in ["urdf/lamp.urdf", "gltf/lamp.gltf"] {
        let pairs: Vec<_> =
            pairs_of(&lamp(other), PairKind::Sf2f).into_iter().map(|g| g.pair).collect();
        assert_eq!(pairs, reference, "{other}");
    }
}

#[test]
fn a_glb_of_the_lamp_is_the_gltf() {
    let text = std::fs::read_to_string(examples().join("gltf/lamp.gltf")).expect("example");
    let mut json: serde_json::Value = serde_json::from_str(&text).expect("json");
    let uri = json["buffers"][0]["uri"].as_str().expect("uri").to_string();
    let payload = uri.split_once(',').expect("data URI").1;
    use base64::Engine as _;
    let bin = base64::engine::general_purpose::STANDARD.decode(payload).expect("base64");
    json["buffers"][0].as_object_mut().expect("buffer").remove("uri");
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("lamp.glb");
    std::fs::write(&path, glb(&serde_json::to_vec(&json).expect("json"), &bin)).expect("write");
    let object = load_asset(&path, &ImportOptions::default()).expect("GLB").object;
    assert_eq!(object, lamp("gltf/lamp.gltf"));
}

/// A GLB container around a JSON chunk and a BIN chunk.
pub fn glb(json: &[u8], bin: &[u8]) -> Vec<u8> {
    let pad = |mut v: Vec<u8>, with: u8| {
        v.resize(v.len().next_multiple_of(4), with);
        v
    };
    let (json, bin) = (pad(json.to_vec(), b' '), pad(bin.to_vec(), 0));
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend(b"glTF");
    out.extend(2u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    out.extend((json.len() as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(&json);
    out.extend((bin.len() as u32).to_le_bytes());
    out.extend(b"BIN\0");
    out.extend(&bin);
    out
}

/// Rotation of a URDF `rpy`, written out as the product the URDF spec defines:
/// yaw about z times pitch about y times roll about x (fixed axes).
fn rpy(r: f64, p: f64, y: f64) -> Rotation3<f64> {
    Rotation3::from_axis_angle(&Vector3::z_axis(), y)
        * Rotation3::from_axis_angle(&Vector3::y_axis(), p)
        * Rotation3::from_axis_angle(&Vector3::x_axis(), r)
}

fn frame(xyz: [f64; 3], r: Rotation3<f64>) -> Isometry3<f64> {
    Isometry3::from_parts(Translation3::from(Vector3::from(xyz)), UnitQuaternion::from(r))
}

const CHAIN: &str = r#"<robot name="chain">
  <link name="base"><visual><geometry><box size="0.4 0.1 0.4"/></geometry></visual></link>
  <link name="l1"><visual><origin xyz="0.05 0.1 0" rpy="0 0 0.3"/><geometry><box size="0.1 0.2 0.05"/></geometry></visual></link>
  <link name="l2"><visual><origin xyz="0 0 0.1"/><geometry><box size="0.05 0.05 0.2"/></geometry></visual></link>
  <link name="l3"><visual><origin xyz="0.1 0 0" rpy="0.2 0 0"/><geometry><box size="0.2 0.04 0.04"/></geometry></visual></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <origin xyz="0.1 0.2 0.3" rpy="0.3 -0.2 0.5"/><axis xyz="1 1 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="j2" type="prismatic"><parent link="l1"/><child link="l2"/>
    <origin xyz="0 0.4 0" rpy="0 0.5 0"/><axis xyz="0 0 2"/>
    <limit lower="-0.5" upper="0.5" effort="1" velocity="1"/></joint>
  <joint name="j3" type="continuous"><parent link="l2"/><child link="l3"/>
    <origin xyz="0.2 0 -0.1" rpy="-0.4 0 0.25"/><axis xyz="0 1 1"/></joint>
</robot>"#;

#[test]
fn urdf_forward_kinematics_matches_hand_computed_link_poses() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("chain.urdf");
    std::fs::write(&path, CHAIN).expect("write");
    let object = load_asset(&path, &ImportOptions::default()).expect("chain").object;
    let names: Vec<&str> = object.links.iter().map(|l| l.name.as_str()).collect();
    assert_eq!(names, ["base", "l1", "l2", "l3"]);
    let (q1, q2, q3) = (0.7, -0.3, 2.5);
    // Link frames in the URDF's convention: parent frame * origin * joint motion.
    let unit =
        |v: [f64; 3]| Unit::try_new(Vector3::from(v), 1e-12).expect("the test axes are not zero");
    let turn = |axis: [f64; 3], q: f64| frame([0.0; 3], Rotation3::from_axis_angle(&unit(axis), q));
    let slide =
        |axis: [f64; 3], q: f64| frame((unit(axis).into_inner() * q).into(), Rotation3::identity());
    let t1 = frame([0.1, 0.2, 0.3], rpy(0.3, -0.2, 0.5)) * turn([1.0, 1.0, 0.0], q1);
    let t2 = t1 * frame([0.0, 0.4, 0.0], rpy(0.0, 0.5, 0.0)) * slide([0.0, 0.0, 2.0], q2);
    let t3 = t2 * frame([0.2, 0.0, -0.1], rpy(-0.4, 0.0, 0.25)) * turn([0.0, 1.0, 1.0], q3);
    // Each link's visual box: its frame, the visual origin, and its half extents.
    let boxes = [
        (Isometry3::identity(), frame([0.0; 3], Rotation3::identity()), [0.2, 0.05, 0.2]),
        (t1, frame([0.05, 0.1, 0.0], rpy(0.0, 0.0, 0.3)), [0.05, 0.1, 0.025]),
        (t2, frame([0.0, 0.0, 0.1], Rotation3::identity()), [0.025, 0.025, 0.1]),
        (t3, frame([0.1, 0.0, 0.0], rpy(0.2, 0.0, 0.0)), [0.1, 0.02, 0.02]),
    ];
    let poses = link_poses(&object, &[q1 as Real, q2 as Real, q3 as Real]);
    for (link, (link_frame, visual, half)) in boxes.iter().enumerate() {
        let posed: Vec<Point3<f64>> = object.links[link]
            .mesh
            .vertices
            .iter()
            .map(|v| (poses[link] * v).cast::<f64>())
            .collect();
        assert_eq!(posed.len(), 8, "link {link}");
        for corner in 0..8 {
            let sign = |bit: usize| if corner >> bit & 1 == 1 { 1.0 } else { -1.0 };
            let local = Point3::new(sign(0) * half[0], sign(1) * half[1], sign(2) * half[2]);
            let expected = link_frame * visual * local;
            let nearest = posed.iter().map(|p| (p - expected).norm()).fold(f64::MAX, f64::min);
            assert!(nearest < 1e-5, "link {link} corner {corner}: off by {nearest}");
        }
    }
    // The prismatic joint's axis was given as (0, 0, 2): unit length in the model.
    assert!((object.joints[1].axis.norm() - 1.0).abs() < 1e-6);
    let (lo, hi) = object.joints[2].limits;
    assert!((lo + std::f32::consts::PI).abs() < 1e-5 && (hi - std::f32::consts::PI).abs() < 1e-5);
}

#[test]
fn mimic_joints_follow_their_leader_in_every_drawn_state() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("gripper.urdf");
    let finger = |name: &str, x: f64| {
        format!(
            r#"<link name="{name}"><visual><origin xyz="{x} 0.15 0"/><geometry><box size="0.05 0.2 0.1"/></geometry></visual></link>"#
        )
    };
    let text = format!(
        r#"<robot name="gripper">
  <link name="palm"><visual><geometry><box size="0.4 0.1 0.1"/></geometry></visual></link>
  {}{}
  <joint name="left" type="prismatic"><parent link="palm"/><child link="a"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="0.1" effort="1" velocity="1"/></joint>
  <joint name="right" type="prismatic"><parent link="palm"/><child link="b"/><axis xyz="1 0 0"/>
    <limit lower="-0.1" upper="0" effort="1" velocity="1"/><mimic joint="left" multiplier="-1"/></joint>
</robot>"#,
        finger("a", -0.15),
        finger("b", 0.15)
    );
    std::fs::write(&path, text).expect("write");
    let object = load_asset(&path, &ImportOptions::default()).expect("gripper").object;
    assert_eq!(object.mimics.len(), 1);
    let (m, leader) = (object.mimics[0].joint, object.mimics[0].leader);
    let mut rng = rng_for(1, 0, Stream::States);
    for _ in 0..20 {
        let state = draw_state(&object, 0.3, &mut rng);
        assert_eq!(state[m], -state[leader]);
    }
}

/// The plausibility checks of `articulated::check` (links touch their parents and do not
/// pass through each other) and the ground-truth checks of `tests/ground_truth.rs` (each
/// part's motion maps P onto Q's posed surface; flow is motion minus position).
fn check_imported(object: &ArticulatedObject, kind: PairKind) {
    object.validate().expect("valid");
    let shapes = LinkShapes::new(object);
    let size = shapes.size();
    let mut rng = rng_for(2, 0, Stream::States);
    let lows: Vec<Real> = object.joints.iter().map(|j| j.limits.0).collect();
    let highs: Vec<Real> = object.joints.iter().map(|j| j.limits.1).collect();
    let drawn = (0..8).map(|_| draw_state(object, 0.3, &mut rng));
    for state in [lows, highs].into_iter().chain(drawn) {
        let poses = link_poses(object, &state);
        let gaps = shapes.joint_gaps(object, &poses, 0.01 * size);
        assert!(gaps.iter().all(Option::is_none), "a link floats at {state:?}: {gaps:?}");
        let hit = shapes.deepest_penetration(&poses, 0.02 * size);
        assert_eq!(hit, None, "links overlap at {state:?}");
    }
    for generated in pairs_of(object, kind) {
        let (input, truth) = (generated.pair.input(), generated.pair.truth());
        for part in 0..truth.num_parts() {
            let (mut vertices, mut indices) = (Vec::new(), Vec::new());
            for (link, l) in object.links.iter().enumerate() {
                if usize::from(generated.parts.of_link[link]) == part {
                    let offset = vertices.len() as u32;
                    let norm = input.q.normalisation;
                    let posed =
                        l.mesh.vertices.iter().map(|v| norm.apply(&(generated.poses_q[link] * v)));
                    vertices.extend(posed);
                    indices.extend(l.mesh.triangles.iter().map(|t| t.map(|i| i + offset)));
                }
            }
            let mesh = TriMesh::new(vertices, indices).expect("mesh");
            for (i, p) in input.p.points.iter().enumerate() {
                if usize::from(truth.part_p[i]) != part {
                    continue;
                }
                let moved = truth.motions[part].apply(p);
                if truth.corr_mask[i] && input.kind == PairKind::Sf2f {
                    let d = mesh.distance_to_local_point(&moved, false);
                    assert!(d < 1e-4, "{}: point {i} lands {d} from Q", input.id);
                }
                assert!(
                    (moved - p - truth.flow.as_ref().expect("a flow")[i]).norm() < 1e-5,
                    "{}: flow {i}",
                    input.id
                );
            }
        }
    }
}

#[test]
fn imported_lamps_pass_the_plausibility_and_ground_truth_checks() {
    check_imported(&lamp("urdf/lamp.urdf"), PairKind::Sf2f);
    check_imported(&lamp("obj/lamp.obj"), PairKind::Sf2p);
}

#[test]
fn a_folder_with_a_broken_asset_still_gives_the_others_pairs() {
    let dir = tempfile::tempdir().expect("tempdir");
    let root = dir.path().join("assets");
    std::fs::create_dir_all(root.join("good")).expect("mkdir");
    for name in ["lamp.obj", "lamp.joints.json"] {
        std::fs::copy(examples().join("obj").join(name), root.join("good").join(name))
            .expect("copy");
    }
    std::fs::write(root.join("broken.urdf"), "<robot name=\"x\"><link name=").expect("write");
    std::fs::write(root.join("not-an-asset.obj"), "v 0 0 0\n").expect("write");
    let config = small();
    let sources = load_assets(&root, &config).expect("listed");
    assert_eq!(sources.len(), 2, "an OBJ without a sidecar is a mesh, not an asset");
    let out = dir.path().join("out");
    let made =
        generate_asset_dataset(&config, &root, &sources, &out, false, |_| {}).expect("dataset");
    assert_eq!(made.failures.len(), 1);
    assert_eq!(made.failures[0].0, "broken.urdf");
    assert!(made.failures[0].1.contains("URDF"), "{}", made.failures[0].1);
    let manifest = Manifest::read(&out).expect("manifest");
    assert_eq!(manifest.counts.pairs, 5);
    let assets = &manifest.origin.assets;
    assert_eq!(assets.len(), 2);
    assert!(assets[0].error.is_some() && assets[1].error.is_none());
    assert_eq!(assets[1].path, "good/lamp.obj");
    assert!(assets[1].files.contains_key("good/lamp.joints.json"));
    assert_eq!(assets[1].file.sha256.len(), 64);
    let dataset = Dataset::open(&out).expect("open");
    dataset.verify().expect("checksums");
    let pairs: Vec<_> = dataset.pairs().expect("pairs").collect::<Result<_, _>>().expect("read");
    assert!(pairs
        .iter()
        .all(|p| p.provenance().category == "lamp" && p.provenance().object_id == 1));
}

#[test]
fn a_gltf_takes_its_joints_from_a_sidecar_instead_of_extras() {
    let text = std::fs::read_to_string(examples().join("gltf/lamp.gltf")).expect("example");
    let mut json: serde_json::Value = serde_json::from_str(&text).expect("json");
    for node in json["nodes"].as_array_mut().expect("nodes") {
        node.as_object_mut().expect("node").remove("extras");
    }
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("lamp.gltf");
    std::fs::write(&path, serde_json::to_vec(&json).expect("json")).expect("write");
    let sidecar = dir.path().join("lamp.joints.json");
    std::fs::copy(examples().join("obj/lamp.joints.json"), &sidecar).expect("copy");
    let imported = load_asset(&path, &ImportOptions::default()).expect("glTF with sidecar");
    assert_eq!(imported.object, lamp("obj/lamp.obj"));
    assert_eq!(imported.files, vec![sidecar]);
}

#[test]
fn package_meshes_are_found_on_the_package_path() {
    let dir = tempfile::tempdir().expect("tempdir");
    let (robot, packages) = (dir.path().join("robot"), dir.path().join("share"));
    std::fs::create_dir_all(robot.join("urdf")).expect("mkdir");
    std::fs::create_dir_all(packages.join("lamp_description/meshes")).expect("mkdir");
    for mesh in ["base.stl", "pole.obj", "arm.obj", "shade.stl"] {
        let from = examples().join("urdf/meshes").join(mesh);
        std::fs::copy(from, packages.join("lamp_description/meshes").join(mesh)).expect("copy");
    }
    let urdf = std::fs::read_to_string(examples().join("urdf/lamp.urdf")).expect("urdf");
    let urdf = urdf
        .replace("\"meshes/", "\"package://lamp_description/meshes/")
        .replace("package://lamp/", "package://lamp_description/");
    let path = robot.join("urdf/lamp.urdf");
    std::fs::write(&path, urdf).expect("write");
    let missing = load_asset(&path, &ImportOptions::default()).expect_err("not on the path");
    assert!(missing.to_string().contains("package://lamp_description/meshes/"), "{missing}");
    let options = ImportOptions { package_paths: vec![packages], ..Default::default() };
    assert_eq!(load_asset(&path, &options).expect("found").object, lamp("urdf/lamp.urdf"));
}
