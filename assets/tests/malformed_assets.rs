//! Malformed assets give a clear, typed error and never panic (issue 9): one case per line,
//! each a small file written to a temporary folder, with the error variant expected and a
//! fragment its message must contain.

use std::path::Path;

use assets::{load_asset, ImportError, ImportOptions};

/// Writes `files` (name, bytes) into a fresh folder and loads the first one.
fn load(files: &[(&str, &[u8])]) -> ImportError {
    let dir = tempfile::tempdir().expect("tempdir");
    for (name, bytes) in files {
        let path = dir.path().join(name);
        std::fs::create_dir_all(path.parent().unwrap_or(Path::new("."))).expect("mkdir");
        std::fs::write(path, bytes).expect("write");
    }
    match load_asset(&dir.path().join(files[0].0), &ImportOptions::default()) {
        Ok(imported) => panic!("{} loaded: {:?}", files[0].0, imported.object.category),
        Err(e) => e,
    }
}

/// A URDF of a box `base` and a box `lid` on one joint with the given inner XML.
fn urdf_joint(joint: &str) -> Vec<u8> {
    format!(
        r#"<robot name="t">
  <link name="base"><visual><geometry><box size="1 1 1"/></geometry></visual></link>
  <link name="lid"><visual><origin xyz="0 0.55 0"/><geometry><box size="1 0.1 1"/></geometry></visual></link>
  {joint}
</robot>"#
    )
    .into_bytes()
}

/// A URDF whose `lid` link shows the mesh file `mesh`.
fn urdf_mesh(mesh: &str) -> Vec<u8> {
    format!(
        r#"<robot name="t">
  <link name="base"><visual><geometry><box size="1 1 1"/></geometry></visual></link>
  <link name="lid"><visual><geometry><mesh filename="{mesh}"/></geometry></visual></link>
  <joint name="hinge" type="revolute"><parent link="base"/><child link="lid"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="1" effort="1" velocity="1"/></joint>
</robot>"#
    )
    .into_bytes()
}

const TWO_BOXES_OBJ: &str =
    "g a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n\
g b\nv 0 0 2\nv 1 0 2\nv 0 1 2\nv 0 0 3\nf 5 6 7\nf 5 6 8\nf 5 7 8\nf 6 7 8\n";

fn sidecar(joints: &str) -> Vec<u8> {
    format!(r#"{{"joints": [{joints}]}}"#).into_bytes()
}

const HINGE: &str = r#"{"name": "h", "type": "revolute", "parent": "a", "child": "b", "axis": [1, 0, 0], "lower": 0, "upper": 1}"#;

/// A minimal glTF with one triangle in a base64 buffer whose `byteLength` is `claimed`.
fn gltf_claiming(claimed: u64) -> Vec<u8> {
    use base64::Engine as _;
    let mut data = Vec::new();
    for c in [0f32, 0., 0., 1., 0., 0., 0., 1., 0.] {
        data.extend(c.to_le_bytes());
    }
    let uri = base64::engine::general_purpose::STANDARD.encode(&data);
    format!(
        r#"{{"asset": {{"version": "2.0"}}, "scenes": [{{"nodes": [0]}}],
  "nodes": [{{"name": "n", "mesh": 0}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}}}]}}],
  "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]}}],
  "bufferViews": [{{"buffer": 0, "byteLength": 36}}],
  "buffers": [{{"byteLength": {claimed}, "uri": "data:application/octet-stream;base64,{uri}"}}]}}"#
    )
    .into_bytes()
}

macro_rules! fails {
    ($files:expr, $variant:pat, $needle:expr) => {{
        let err = load($files);
        let text = err.to_string();
        assert!(matches!(err, $variant), "unexpected error {err:?}");
        assert!(text.contains($needle), "{text:?} does not mention {:?}", $needle);
    }};
}

#[test]
fn missing_and_unreadable_mesh_files_name_the_link_and_the_file() {
    fails!(
        &[("t.urdf", &urdf_mesh("meshes/none.obj"))],
        ImportError::MissingMesh { .. },
        "none.obj"
    );
    fails!(
        &[("t.urdf", &urdf_mesh("meshes/none.obj"))],
        ImportError::MissingMesh { .. },
        "\"lid\""
    );
    fails!(
        &[("t.urdf", &urdf_mesh("package://p/none.stl"))],
        ImportError::MissingMesh { .. },
        "package://p/none.stl"
    );
    fails!(
        &[("t.urdf", &urdf_mesh("lid.dae")), ("lid.dae", b"<COLLADA/>")],
        ImportError::MeshFile { .. },
        "lid.dae"
    );
    fails!(
        &[("t.urdf", &urdf_mesh("lid.dae")), ("lid.dae", b"<COLLADA/>")],
        ImportError::MeshFile { .. },
        "convert"
    );
    fails!(
        &[("t.urdf", &urdf_mesh("lid.stl")), ("lid.stl", b"solid x\nfacet oops")],
        ImportError::MeshFile { .. },
        "lid.stl"
    );
    fails!(
        &[("t.obj", TWO_BOXES_OBJ.as_bytes())],
        ImportError::MissingSidecar { .. },
        "t.joints.json"
    );
}

#[test]
fn unknown_and_unsupported_joint_types_are_named() {
    let ball = r#"<joint name="knob" type="ball"><parent link="base"/><child link="lid"/></joint>"#;
    fails!(&[("t.urdf", &urdf_joint(ball))], ImportError::UnknownJointType { .. }, "ball");
    fails!(&[("t.urdf", &urdf_joint(ball))], ImportError::UnknownJointType { .. }, "knob");
    let planar =
        r#"<joint name="p" type="planar"><parent link="base"/><child link="lid"/></joint>"#;
    fails!(&[("t.urdf", &urdf_joint(planar))], ImportError::UnsupportedJoint { .. }, "planar");
    let ball = r#"{"name": "k", "type": "ball", "parent": "a", "child": "b"}"#;
    fails!(
        &[("t.obj", TWO_BOXES_OBJ.as_bytes()), ("t.joints.json", &sidecar(ball))],
        ImportError::UnknownJointType { .. },
        "ball"
    );
}

#[test]
fn cyclic_and_ill_formed_joint_graphs_are_refused() {
    let cycle = format!(
        "{HINGE}, {}",
        HINGE
            .replace("\"h\"", "\"g\"")
            .replace("\"a\", \"child\": \"b\"", "\"b\", \"child\": \"a\"")
    );
    fails!(
        &[("t.obj", TWO_BOXES_OBJ.as_bytes()), ("t.joints.json", &sidecar(&cycle))],
        ImportError::Cycle { .. },
        "cycle"
    );
    let urdf_cycle = r#"<joint name="j1" type="fixed"><parent link="base"/><child link="lid"/></joint>
      <joint name="j2" type="fixed"><parent link="lid"/><child link="base"/></joint>"#;
    fails!(&[("t.urdf", &urdf_joint(urdf_cycle))], ImportError::Cycle { .. }, "cycle");
    let self_loop = HINGE.replace("\"child\": \"b\"", "\"child\": \"a\"");
    fails!(
        &[("t.obj", TWO_BOXES_OBJ.as_bytes()), ("t.joints.json", &sidecar(&self_loop))],
        ImportError::Cycle { .. },
        "\"a\""
    );
    fails!(
        &[("t.obj", TWO_BOXES_OBJ.as_bytes()), ("t.joints.json", &sidecar(""))],
        ImportError::Roots { .. },
        "\"b\""
    );
    let unknown = HINGE.replace("\"child\": \"b\"", "\"child\": \"lid\"");
    fails!(
        &[("t.obj", TWO_BOXES_OBJ.as_bytes()), ("t.joints.json", &sidecar(&unknown))],
        ImportError::UnknownLink { .. },
        "lid"
    );
    let twice = format!("{HINGE}, {}", HINGE.replace("\"h\"", "\"h2\""));
    fails!(
        &[("t.obj", TWO_BOXES_OBJ.as_bytes()), ("t.joints.json", &sidecar(&twice))],
        ImportError::MultipleParents { .. },
        "h2"
    );
}

#[test]
fn bad_axes_and_limits_are_refused() {
    let nan = r#"<joint name="h" type="revolute"><parent link="base"/><child link="lid"/><axis xyz="nan 0 1"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint>"#;
    fails!(&[("t.urdf", &urdf_joint(nan))], ImportError::NonFinite { field: "axis", .. }, "axis");
    let zero = HINGE.replace("[1, 0, 0]", "[0, 0, 0]");
    fails!(
        &[("t.obj", TWO_BOXES_OBJ.as_bytes()), ("t.joints.json", &sidecar(&zero))],
        ImportError::ZeroAxis { .. },
        "zero length"
    );
    let tiny = HINGE.replace("[1, 0, 0]", "[1e-300, 0, 0]");
    fails!(
        &[("t.obj", TWO_BOXES_OBJ.as_bytes()), ("t.joints.json", &sidecar(&tiny))],
        ImportError::ZeroAxis { .. },
        "\"h\""
    );
    let no_limits = r#"<joint name="h" type="revolute"><parent link="base"/><child link="lid"/><axis xyz="0 0 1"/></joint>"#;
    fails!(&[("t.urdf", &urdf_joint(no_limits))], ImportError::BadLimits { .. }, "limits");
    let reversed = HINGE.replace("\"lower\": 0, \"upper\": 1", "\"lower\": 1, \"upper\": 0");
    fails!(
        &[("t.obj", TWO_BOXES_OBJ.as_bytes()), ("t.joints.json", &sidecar(&reversed))],
        ImportError::BadLimits { .. },
        "[1, 0]"
    );
    let no_axis = r#"{"name": "h", "type": "prismatic", "parent": "a", "child": "b", "lower": 0, "upper": 1}"#;
    fails!(
        &[("t.obj", TWO_BOXES_OBJ.as_bytes()), ("t.joints.json", &sidecar(no_axis))],
        ImportError::MissingField { field: "axis", .. },
        "axis"
    );
    let nan_origin = r#"<joint name="h" type="fixed"><parent link="base"/><child link="lid"/><origin xyz="0 inf 0"/></joint>"#;
    fails!(
        &[("t.urdf", &urdf_joint(nan_origin))],
        ImportError::NonFinite { field: "origin", .. },
        "origin"
    );
    let mimic_loop = r#"<joint name="h" type="revolute"><parent link="base"/><child link="lid"/><axis xyz="0 0 1"/><limit lower="0" upper="1" effort="1" velocity="1"/><mimic joint="h"/></joint>"#;
    fails!(&[("t.urdf", &urdf_joint(mimic_loop))], ImportError::Mimic { .. }, "cycle");
}

#[test]
fn empty_meshes_are_refused() {
    fails!(
        &[("t.obj", b"# nothing here\nv 0 0 0\n"), ("t.joints.json", &sidecar(""))],
        ImportError::EmptyMesh { .. },
        "no triangles"
    );
    fails!(
        &[("t.urdf", &urdf_mesh("lid.obj")), ("lid.obj", b"v 0 0 0\n")],
        ImportError::MeshFile { .. },
        "no triangles"
    );
    let degenerate = "g a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\ng b\nv 5 5 5\nf 4 4 4\n";
    fails!(
        &[("t.obj", degenerate.as_bytes()), ("t.joints.json", &sidecar(HINGE))],
        ImportError::EmptyMesh { .. },
        "\"b\""
    );
    let no_link_geometry = r#"<robot name="t"><link name="base"/><link name="lid"><visual><geometry><box size="1 1 1"/></geometry></visual></link>
      <joint name="h" type="prismatic"><parent link="base"/><child link="lid"/><axis xyz="0 0 1"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint></robot>"#;
    fails!(&[("t.urdf", no_link_geometry.as_bytes())], ImportError::EmptyMesh { .. }, "\"base\"");
    let flat_box = r#"<robot name="t"><link name="base"><visual><geometry><box size="1 0 1"/></geometry></visual></link></robot>"#;
    fails!(&[("t.urdf", flat_box.as_bytes())], ImportError::EmptyMesh { .. }, "\"base\"");
}

#[test]
fn names_that_are_not_utf8_are_refused() {
    let mut obj = b"g \xff\xfe\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".to_vec();
    fails!(
        &[("t.obj", &obj), ("t.joints.json", &sidecar(""))],
        ImportError::NotUtf8 { offset: 2, .. },
        "UTF-8"
    );
    obj = urdf_joint("");
    obj.splice(16..16, *b"\xc3\x28");
    fails!(&[("t.urdf", &obj)], ImportError::NotUtf8 { .. }, "t.urdf");
    fails!(
        &[
            ("t.obj", TWO_BOXES_OBJ.as_bytes()),
            ("t.joints.json", b"{\"joints\": [], \"category\": \"\xff\"}")
        ],
        ImportError::NotUtf8 { .. },
        "t.joints.json"
    );
    let mut gltf = gltf_claiming(36);
    let at = gltf.windows(3).position(|w| w == b"\"n\"").expect("the node name") + 1;
    gltf[at] = 0xff;
    fails!(&[("t.gltf", &gltf)], ImportError::NotUtf8 { .. }, "t.gltf");
}

#[test]
fn gltf_buffers_that_claim_more_than_they_hold_are_refused_without_allocating() {
    let two_gb = gltf_claiming(2_000_000_000);
    fails!(
        &[("t.gltf", &two_gb)],
        ImportError::Buffer { .. },
        "claims 2000000000 bytes but holds 36"
    );
    // The same claim inside a GLB, whose header also claims 2 GB.
    let mut glb = b"glTF".to_vec();
    glb.extend(2u32.to_le_bytes());
    glb.extend(2_000_000_000u32.to_le_bytes());
    glb.extend(&two_gb[..64]);
    fails!(&[("t.glb", &glb)], ImportError::Parse { format: "GLB", .. }, "length");
    // An accessor counting a billion vertices in a 36-byte view.
    let huge = String::from_utf8(gltf_claiming(36))
        .expect("utf8")
        .replace("\"count\": 3", "\"count\": 1000000000");
    fails!(&[("t.gltf", huge.as_bytes())], ImportError::Accessor { .. }, "do not fit");
    let cut = String::from_utf8(gltf_claiming(36))
        .expect("utf8")
        .replace("\"byteLength\": 36}]", "\"byteLength\": 48}]");
    fails!(
        &[("t.gltf", cut.as_bytes())],
        ImportError::Accessor { .. } | ImportError::Parse { .. },
        ""
    );
    fails!(
        &[("t.glb", b"glTF\x02\x00\x00\x00\x05\x00\x00\x00")],
        ImportError::Parse { format: "GLB", .. },
        "length"
    );
    let cyclic = String::from_utf8(gltf_claiming(36))
        .expect("utf8")
        .replace("\"name\": \"n\", \"mesh\": 0", "\"name\": \"n\", \"mesh\": 0, \"children\": [0]");
    let err = load(&[("t.gltf", cyclic.as_bytes())]);
    assert!(matches!(err, ImportError::Cycle { .. } | ImportError::Parse { .. }), "{err:?}");
}
